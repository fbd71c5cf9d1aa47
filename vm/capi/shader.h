// The C library's shader (include/vs11/vs11_c.h) in C++: a validated program with its constants, its
// input binding (a D3D8 declaration, or a D3D9 declaration given with each run) and a lazily built
// engine. vm/capi/c_api.cc wraps it in the C functions; nothing here throws but std::bad_alloc.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <vs11/vs11_c.h>

#include "vm/capi/layouts.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11::capi {

inline constexpr int kMaxConstantCount = 8192;
inline constexpr std::size_t kProcessChunk = 4096;  // vertices decoded, run and written at a time

// Which API's rules a shader follows: D3D9's dcl_ inputs, or D3D8's registers bound by a declaration.
enum class Api { kD3d8, kD3d9 };

struct Validation {
  vs11c_status status = VS11C_OK;
  std::vector<vs11c_message> messages;
  std::optional<Program> program;                // when the tokens decode
  std::optional<D3d8Declaration> d3d8_declaration;  // D3D8, when the declaration reads
};
// Decodes and validates; `declaration` is used for kD3d8 only.
Validation ValidateShader(Api api, std::span<const std::uint32_t> declaration, std::span<const std::uint32_t> tokens,
                          int constant_count);

// 0 -> the default (96); nullopt when out of range.
std::optional<int> ConstantCountOf(const vs11c_shader_options* options);

class Shader {
 public:
  Shader(Api api, Program program, std::optional<D3d8Declaration> declaration, int constant_count);
  vs11c_status SetConstants(unsigned start, const float* values, std::size_t vector_count);
  vs11c_status SetEngine(const char* name, int rules);  // rules: a vs11c_float_rules
  vs11c_status SetTexture(unsigned sampler, int format, unsigned width, unsigned height, const float* texels,
                          int address_u, int address_v);
  vs11c_status Process(const vs11c_vertex_element* declaration, std::span<const vs11c_stream> streams,
                       std::size_t vertex_count, const vs11c_output& output);
  // Why the latest Process that returned VS11C_ENGINE_FAILED failed; empty before any did.
  const std::string& engine_error() const { return engine_error_; }

 private:
  Status EnsureEngine();
  // Keeps `status`'s message as engine_error().
  vs11c_status EngineFailed(const Status& status);

  Api api_;
  Program program_;
  std::optional<D3d8Declaration> d3d8_declaration_;
  ConstantBank constants_;
  std::string engine_name_;
  FloatRules float_rules_ = FloatRules::kD3d9;
  std::unique_ptr<Engine> engine_;  // built at the first run after a change of engine
  bool constants_changed_ = false;
  std::string engine_error_;
};

}  // namespace vs11::capi
