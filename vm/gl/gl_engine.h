// The gl engine (`--engine gl`): the program's GLSL ES translation (vm/translate) run by a real
// OpenGL ES driver, Mesa's llvmpipe by default or an EGL device's (gl_context.h): as a compute shader
// on ES 3.1 contexts (gl_compute_engine.h), else a vertex shader through transform feedback (GlPath). Inputs, constants and outputs are every engine's (vm/core/machine.h): the VertexArrays'
// lanes go to vertex attributes vN, the API bank to `uniform vec4 c[N]` (the program's def constants
// are in the translation), and every output register the program writes comes back from the capture.
// Its bits are the reference engine's wherever the driver computes IEEE single precision as the
// translation asks (README, "vs11 translate" and "The gl engine"); where no device can be had,
// MakeGlEngine returns the error, and a Run that fails returns why and leaves NaN outputs. A
// later model's program with static flow runs specialised for its i#/b# values (static_flow_engine.h).
#pragma once

#include <memory>
#include <optional>
#include <string_view>

#include "vm/core/machine.h"
#include "vm/core/name_table.h"
#include "vm/core/result.h"
#include "vm/translate/translate.h"

namespace vs11::gl {

// The translation the gl engine runs for `options`: GLSL ES 3.20 with every output `precise` on an
// OpenGL ES 3.2 context (`es32`), so that no driver fuses a multiply and an add, else GLSL ES 3.00;
// D3D's clip space (the capture reads the raw vs11_oPos; gl_Position is not used), a bank of
// `constant_count` registers. Every engine option that changes the arithmetic reaches the
// translation here.
translate::TranslateOptions GlTranslateOptions(const EngineOptions& options, int constant_count, bool es32);

// How the gl engine runs the translation: a compute shader over storage buffers (gl_compute.h; needs
// OpenGL ES 3.1, as llvmpipe and NVIDIA offer), or a vertex shader with transform feedback (ES 3.0,
// at most 65536 vertices a draw). kAuto: compute where the context offers ES 3.1.
enum class GlPath { kAuto, kCompute, kTransformFeedback };
inline constexpr NameTable kGlPathNames("gl path", {
    Choice(GlPath::kCompute, "compute", "a compute shader, OpenGL ES 3.1"),
    Choice(GlPath::kTransformFeedback, "transform-feedback", "a vertex shader, ES 3.0"),
    Choice(GlPath::kAuto, "auto", "compute where the context offers it")});

// The gl engine's own options (EngineOptions::settings).
struct GlOptions {
  // The EGL device (gl_context.h's ListGlDevices index, `--gl-device N`); nullopt: Mesa's llvmpipe.
  std::optional<int> device;
  // `--gl-path`: kCompute on a context without ES 3.1 is the engine's error, not a fallback.
  GlPath path = GlPath::kAuto;
};

// What a gl engine says of itself: the path it runs (never kAuto).
class GlPathOwner {
 public:
  virtual ~GlPathOwner() = default;
  virtual GlPath path() const = 0;
};

// The path `engine` runs, where it is a gl engine; nullopt for any other engine.
std::optional<GlPath> GlPathOf(const Engine& engine);

// An error where the context (kGlUnavailable) or the program (kGlCompile, kGlError) cannot be had, or
// where --gl-path compute is asked of a context without OpenGL ES 3.1 (kGlUnavailable).
// EngineOptions::threads does not apply (the driver keeps its own threads: llvmpipe's LP_NUM_THREADS);
// options.settings' GlOptions picks the device and the path.
Result<std::unique_ptr<Engine>> MakeGlEngine(const Program& program, const ConstantBank& api_constants,
                                             const EngineOptions& options);

// Registers the gl engine (vm/engines/engine_factory.h's RegisterEngine), so that MakeEngine("gl", ...)
// builds MakeGlEngine. The tools call it once before they parse their arguments; vm/engines sits below
// vm/gl and cannot name it.
void RegisterGlEngine();

}  // namespace vs11::gl
