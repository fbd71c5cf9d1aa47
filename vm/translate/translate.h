// vs_1_1 to GLSL 3.30, GLSL ES 3.00 and SPIR-V (`vs11 translate`). The translation reproduces vs11's
// engines: it traces the shared instruction semantics (vm/core/semantics.h, vm/core/operands.h) into
// straight-line code (shader_graph.h), so every instruction, modifier and corner case (rcp of 0, NaN
// in min/max/sge/slt, expp/logp/lit/frc, mov a0 flooring, out-of-range c[a0.x + n], unwritten outputs)
// computes what the engines compute. The interface a user wires up is written at the top of every
// output and in the README ("vs11 translate").
#pragma once

#include <string>

#include "vm/core/float_rules.h"
#include "vm/core/isa.h"
#include "vm/core/program.h"
#include "vm/translate/profile.h"

namespace vs11::translate {

// Where gl_Position's coordinates are expressed: D3D's clip space as the program wrote it, or the
// target API's (GL: z from [0, w] to [-w, w]; Vulkan: y negated). kTargetApi is GL's for the GLSL
// targets and Vulkan's for SPIR-V.
enum class ClipSpace { kTargetApi, kD3d, kGl, kVulkan };
std::optional<ClipSpace> ClipSpaceFromName(std::string_view name);  // "d3d" | "gl" | "vulkan"

struct TranslateOptions {
  Target target = Target::kGlsl330;
  int constant_count = kDefaultConstantCount;  // the `uniform vec4 c[N]` bank (--max-constants)
  ClipSpace clip = ClipSpace::kTargetApi;
  std::string source_name;  // named in the output's header comment
  // The rule every product follows (--float-rules; vm/core/float_rules.h): under kLegacy each product
  // is written as the compares and selects of semantics::Product around its multiply.
  FloatRules float_rules = FloatRules::kD3d9;
};

// The GLSL that `options.target` starts from (for SPIR-V: the Vulkan GLSL that is compiled). Never
// fails: every program the engines run has a translation.
std::string TranslateToGlsl(const Program& program, const TranslateOptions& options);

// The target's output: GLSL text, or SPIR-V words (little-endian bytes) compiled by glslang.
Artifact Translate(const Program& program, const TranslateOptions& options);

}  // namespace vs11::translate
