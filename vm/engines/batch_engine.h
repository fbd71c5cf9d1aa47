// The batch engine: one program over many vertices at once, structure of arrays, wide SIMD chosen at
// run time (Highway dynamic dispatch), bit-identical to the reference engine.
#pragma once

#include <memory>

#include "vm/core/machine.h"

namespace vs11 {

// With `compile_program`, the program runs as machine code made by vm/engines/jit_compiler.h (the jit
// engine) when it can be compiled, and on the kernels otherwise.
std::unique_ptr<Engine> MakeBatchEngine(const Program& program, const ConstantBank& api_constants,
                                        const EngineOptions& options, bool compile_program = false);

}  // namespace vs11
