// Float-range checks of the jobs' results. See float_range.h.
#include "irradiance/jobs/float_range.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace vs11::irradiance {

TexelRange RangeOfTexels(const Image& image) {
  TexelRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  for (const glm::vec3& texel : image.pixels) {
    for (int c = 0; c < 3; ++c) {
      range.min = std::min(range.min, texel[c]);
      range.max = std::max(range.max, texel[c]);
    }
  }
  return image.pixels.empty() ? TexelRange{} : range;
}

TexelRange RangeOfTexels(const CubeMap& cube) {
  TexelRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  for (const Image& face : cube.faces) {
    const TexelRange face_range = RangeOfTexels(face);
    if (face.pixels.empty()) continue;
    range.min = std::min(range.min, face_range.min);
    range.max = std::max(range.max, face_range.max);
  }
  return range.min <= range.max ? range : TexelRange{};
}

std::string BeyondFloatRangeMessage(std::string_view what, const TexelRange& range) {
  return fmt::format("{} beyond float range (texels from {:g} to {:g}): scale the environment down", what, range.min,
                     range.max);
}

Status CheckCoefficientsFitFloat(const Sh9Rgb& coefficients, std::span<const glm::vec4> constants,
                                 const TexelRange& range) {
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (const glm::dvec3& c : coefficients.coefficients) {
    for (int channel = 0; channel < 3; ++channel) {
      if (!(std::abs(c[channel]) <= kFloatMax)) {
        return Failure(DiagnosticCode::kBeyondFloatRange, BeyondFloatRangeMessage("the SH coefficients are", range));
      }
    }
  }
  for (const glm::vec4& r : constants) {
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || !std::isfinite(r.w)) {
      return Failure(DiagnosticCode::kBeyondFloatRange, BeyondFloatRangeMessage("the program's constants are", range));
    }
  }
  return {};
}

bool AllTexelsFinite(const CubeMap& cube) {
  for (const Image& face : cube.faces) {
    for (const glm::vec3& texel : face.pixels) {
      if (!std::isfinite(texel.x) || !std::isfinite(texel.y) || !std::isfinite(texel.z)) return false;
    }
  }
  return true;
}

bool AllNumbersFinite(const nlohmann::ordered_json& json) {
  if (json.is_number_float()) return std::isfinite(json.get<double>());
  if (json.is_structured()) {
    for (const auto& element : json) {
      if (!AllNumbersFinite(element)) return false;
    }
  }
  return true;
}

}  // namespace vs11::irradiance
