// The one place that knows every engine: builds the engine of a kind (core/machine.h declares the
// interface; the engines below implement it).
#pragma once

#include <memory>

#include "vm/core/machine.h"

namespace vs11 {

// `program` must be well formed (Decode accepted it); validation is the caller's choice. Temporaries
// read before they are written (possible only with validation skipped) read 0.
std::unique_ptr<Engine> MakeEngine(EngineKind kind, const Program& program, const ConstantBank& api_constants,
                                   const EngineOptions& options = {});

}  // namespace vs11
