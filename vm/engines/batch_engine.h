// The batch engine: one program over many vertices at once, structure of arrays, wide SIMD chosen at
// run time (Highway dynamic dispatch), bit-identical to the reference engine.
#pragma once

#include <cstddef>
#include <memory>

#include "vm/core/machine.h"

namespace vs11 {

std::unique_ptr<Engine> MakeBatchEngine(const Program& program, const ConstantBank& api_constants,
                                        const EngineOptions& options);

// The jit engine: the batch engine with the program run as machine code made by
// vm/engines/jit_compiler.h (its instruction set from options.settings' JitOptions,
// vm/engines/jit_options.h) when it can be compiled, and on the kernels otherwise.
std::unique_ptr<Engine> MakeJitEngine(const Program& program, const ConstantBank& api_constants,
                                      const EngineOptions& options);

// The fewest vertices one piece of a split call gets (EngineOptions::threads > 1): a call of fewer
// than twice this many runs on the calling thread alone. kNeverSplit for a program that threads
// cannot speed up (see batch_engine.cc). Tests size their calls with it so that they split.
inline constexpr std::size_t kNeverSplit = static_cast<std::size_t>(-1);
std::size_t MinVerticesPerPiece(const Program& program);

}  // namespace vs11
