// The gl engine's compute path (gl_engine.h, GlPath::kCompute): the program's compute translation
// over storage buffers (gl_compute.h), on a context with OpenGL ES 3.1 or later.
#pragma once

#include <memory>
#include "vm/core/machine.h"
#include "vm/core/result.h"
#include "vm/gl/gl_context.h"

namespace vs11::gl {

// An error where the program does not compile or link on the context (kGlCompile), or GL fails.
Result<std::unique_ptr<Engine>> MakeGlComputeEngine(const Program& program, const ConstantBank& api_constants,
                                                    const EngineOptions& options, std::unique_ptr<GlContext> context);

}  // namespace vs11::gl
