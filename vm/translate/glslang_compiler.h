// glslang (Debian's glslang-dev) as the translator's compiler and checker: it compiles the Vulkan GLSL
// of the SPIR-V target to SPIR-V, and checks that the GLSL targets' text compiles and links as a
// vertex shader of its version; SPIRV-Tools validates SPIR-V for Vulkan 1.0.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/result.h"
#include "vm/translate/profile.h"

namespace vs11::translate {

// Compiles and links `glsl` as a shader of `stage` (a vertex shader unless told) in `target`'s dialect
// (the #version line decides its version): the SPIR-V words for Target::kSpirv (none for the GLSL
// targets), or glslang's messages (kGlCompile). Thread-safe.
Result<std::vector<std::uint32_t>> CompileWithGlslang(const std::string& glsl, Target target,
                                                      Stage stage = Stage::kVertex);

// Compiles and links `hlsl` as an HLSL vertex shader whose entry point is `entry_point`, through
// glslang's HLSL front end (as `glslangValidator -D`), for checks of HLSL that vs11 writes
// (irrmap --sh-export hlsl): success, or glslang's messages (kGlCompile). Thread-safe.
Status CompileHlslWithGlslang(const std::string& hlsl, const std::string& entry_point);

// Success when `words` is valid SPIR-V for Vulkan 1.0, else SPIRV-Tools' message (kInvalidSpirv).
Status ValidateSpirv(const std::vector<std::uint32_t>& words);

}  // namespace vs11::translate
