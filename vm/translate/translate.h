// vs_1_1 to GLSL 3.30, GLSL ES 3.00, 3.10, 3.20 and SPIR-V, vertex or compute shaders, (`vs11 translate`). The translation reproduces vs11's
// engines: it records the shared instruction semantics (vm/core/semantics.h, vm/core/operands.h) into
// the IR (vm/ir/, shader_graph.h), so every instruction, modifier and corner case (rcp of 0, NaN
// in min/max/sge/slt, expp/logp/lit/frc, mov a0 flooring, out-of-range c[a0.x + n], unwritten outputs)
// computes what the engines compute. The interface a user wires up is written at the top of every
// output and in the README ("vs11 translate").
#pragma once

#include <string>

#include "vm/core/name_table.h"
#include "vm/core/float_rules.h"
#include "vm/core/isa.h"
#include "vm/core/program.h"
#include "vm/translate/profile.h"

namespace vs11::translate {

// Where gl_Position's coordinates are expressed: D3D's clip space as the program wrote it, or the
// target API's (GL: z from [0, w] to [-w, w]; Vulkan: y negated). kTargetApi is GL's for the GLSL
// targets and Vulkan's for SPIR-V.
enum class ClipSpace { kTargetApi, kD3d, kGl, kVulkan };
// The names of --clip (kTargetApi, the default, has none).
inline constexpr NameTable kClipSpaceNames("clip space", {
    Choice(ClipSpace::kD3d, "d3d", "as written"), Choice(ClipSpace::kGl, "gl", "z' = 2z - w"),
    Choice(ClipSpace::kVulkan, "vulkan", "y' = -y")});

struct TranslateOptions {
  Target target = Target::kGlsl330;
  int constant_count = kDefaultConstantCount;  // the `uniform vec4 c[N]` bank (--max-constants)
  ClipSpace clip = ClipSpace::kTargetApi;
  std::string source_name;  // named in the output's header comment
  // For running the translation where its bits are compared (the gl engine, vm/gl/gl_engine.h):
  // every output is declared `invariant`, which keeps Mesa from rewriting the operations they depend
  // on (no fused multiply-adds, no reassociation: its GLSL and NIR passes treat them as `precise`),
  // and every float literal reads a uniform `vs11_opaque_zero` (0 unless an application sets it) into
  // its bits, so that no compiler folds `x * 0.0` to +0 or drops `x + -0.0`, which loses signs of
  // zero. An application linking the translation with its own fragment shader should leave it off:
  // GLSL ES asks the next stage's inputs to be invariant too.
  bool exact_on_driver = false;
  // The rule every product follows (--float-rules; vm/core/float_rules.h): under kLegacy each product
  // is written as the compares and selects of semantics::Product around its multiply.
  FloatRules float_rules = FloatRules::kD3d9;
  // A vertex shader, or a compute shader over storage buffers (compute_interface.h; GLSL ES 3.10,
  // 3.20 and SPIR-V only: StageProblem). The statements are the same; the compute form has no
  // gl_Position (clip does not apply) and keeps all four lanes of oFog and oPts.
  Stage stage = Stage::kVertex;
};

// The GLSL output that carries output slot `slot` (OutputSlot): "vs11_oPos" for oPos (the raw value;
// gl_Position may be converted), "oD0", "oT3", "oFog"; `components` 1 for oFog and oPts, else 4. What
// a transform-feedback capture names (the gl engine, vm/gl/gl_engine.h). Under exact_on_driver oFog
// and oPts are vec4s as well, every lane as the program wrote it, as the engines keep them (`mov oFog,
// r0` writes four lanes, of which D3D uses x).
struct OutputVariable {
  std::string name;
  int components = 4;
};
OutputVariable OutputVariableOf(int slot, bool exact_on_driver = false);

// The GLSL that `options.target` starts from (for SPIR-V: the Vulkan GLSL that is compiled). Never
// fails: every program the engines run has a translation.
std::string TranslateToGlsl(const Program& program, const TranslateOptions& options);

// The target's output: GLSL text, or SPIR-V words (little-endian bytes) compiled by glslang; or the
// error: a program no engine of this model translates (EngineRefusal), a stage the target cannot
// hold (StageProblem, kOptionValue), glslang refusing the translation (kGlCompile, a vs11 bug).
Result<Artifact> Translate(const Program& program, const TranslateOptions& options);

}  // namespace vs11::translate
