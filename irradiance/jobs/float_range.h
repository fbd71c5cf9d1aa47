// What a job hands on (coefficients, the vs_1_1 program's float constants, the irradiance map, a
// batch record) is finite and fits float, or the job fails with a message that names the texel range
// it came from. Projection never overflows for finite texels (irradiance/sh/sh_projection.h), but a
// map bright enough gives coefficients, or an irradiance, beyond FLT_MAX, which no float register
// or float image can hold.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/sh9.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The smallest and largest channel value of a cube's texels (0, 0 for an empty cube).
struct TexelRange {
  float min = 0.0f;
  float max = 0.0f;
};
TexelRange RangeOfTexels(const CubeMap& cube);
TexelRange RangeOfTexels(const Image& image);

// "<what> is beyond float range (texels from MIN to MAX): scale the environment down", the message
// of a job that fails for it.
std::string BeyondFloatRangeMessage(std::string_view what, const TexelRange& range);

// Success when every coefficient fits float and every constant register is finite; else
// BeyondFloatRangeMessage naming which (kBeyondFloatRange).
Status CheckCoefficientsFitFloat(const Sh9Rgb& coefficients, std::span<const glm::vec4> constants,
                                 const TexelRange& range);

// Whether every channel of every texel is finite.
bool AllTexelsFinite(const CubeMap& cube);

// Whether every number in `json`, at any depth, is finite (nlohmann writes NaN and infinities as null).
bool AllNumbersFinite(const nlohmann::ordered_json& json);

}  // namespace vs11::irradiance
