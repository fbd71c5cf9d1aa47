// The gl engine (`--engine gl`): the program's GLSL ES 3.00 translation (vm/translate) run by a real
// OpenGL ES 3.0 driver, Mesa's llvmpipe by default or an EGL device's (gl_context.h), through transform
// feedback. Inputs, constants and outputs are every engine's (vm/core/machine.h): the VertexArrays'
// lanes go to vertex attributes vN, the API bank to `uniform vec4 c[N]` (the program's def constants
// are in the translation), and every output register the program writes comes back from the capture.
// Its bits are the reference engine's wherever the driver computes IEEE single precision as the
// translation asks (README, "vs11 translate" and "The gl engine"); where no device can be had,
// MakeGlEngine returns the error, and a Run that fails leaves NaN outputs and says why in error().
#pragma once

#include <memory>
#include <optional>

#include "vm/core/machine.h"
#include "vm/core/result.h"
#include "vm/translate/translate.h"

namespace vs11::gl {

// The translation the gl engine runs for `options`: GLSL ES 3.20 with every output `precise` on an
// OpenGL ES 3.2 context (`es32`), so that no driver fuses a multiply and an add, else GLSL ES 3.00;
// D3D's clip space (the capture reads the raw vs11_oPos; gl_Position is not used), a bank of
// `constant_count` registers. Every engine option that changes the arithmetic reaches the
// translation here.
translate::TranslateOptions GlTranslateOptions(const EngineOptions& options, int constant_count, bool es32);

// The gl engine's own options (EngineOptions::settings).
struct GlOptions {
  // The EGL device (gl_context.h's ListGlDevices index, `--gl-device N`); nullopt: Mesa's llvmpipe.
  std::optional<int> device;
};

// An error where the context (kGlUnavailable) or the program (kGlCompile, kGlError) cannot be had.
// EngineOptions::threads does not apply (the driver keeps its own threads: llvmpipe's LP_NUM_THREADS);
// options.settings' GlOptions picks the device.
Result<std::unique_ptr<Engine>> MakeGlEngine(const Program& program, const ConstantBank& api_constants,
                                             const EngineOptions& options);

// Registers the gl engine (vm/engines/engine_factory.h's RegisterEngine), so that MakeEngine("gl", ...)
// builds MakeGlEngine. The tools call it once before they parse their arguments; vm/engines sits below
// vm/gl and cannot name it.
void RegisterGlEngine();

}  // namespace vs11::gl
