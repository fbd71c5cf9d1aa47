// The batch engine: one program over many vertices at once, structure of arrays, wide SIMD chosen at
// run time (Highway dynamic dispatch), bit-identical to the reference engine.
#pragma once

#include <memory>

#include "vm/machine.h"

namespace vs11 {

std::unique_ptr<Engine> MakeBatchEngine(const Program& program, const ConstantBank& api_constants,
                                        const EngineOptions& options);

}  // namespace vs11
