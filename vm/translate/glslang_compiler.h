// glslang (Debian's glslang-dev) as the translator's compiler and checker: it compiles the Vulkan GLSL
// of the SPIR-V target to SPIR-V, and checks that the GLSL targets' text compiles and links as a
// vertex shader of its version; SPIRV-Tools validates SPIR-V for Vulkan 1.0.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/translate/profile.h"

namespace vs11::translate {

struct GlslangResult {
  bool ok = false;
  std::string log;                   // glslang's messages when not ok
  std::vector<std::uint32_t> spirv;  // for Target::kSpirv
};

// Compiles and links `glsl` as a vertex shader of `target`'s dialect (the #version line decides its
// version). Thread-safe.
GlslangResult CompileWithGlslang(const std::string& glsl, Target target);

// nullopt when `words` is valid SPIR-V for Vulkan 1.0, else SPIRV-Tools' message.
std::optional<std::string> ValidateSpirv(const std::vector<std::uint32_t>& words);

}  // namespace vs11::translate
