// The one place that knows every engine: builds the engine of a kind (core/machine.h declares the
// interface; the engines below implement it). The gl engine lives above this layer (vm/gl runs
// vm/translate's GLSL), so it registers its maker here instead of being included.
#pragma once

#include <memory>
#include <string>

#include "vm/core/machine.h"

namespace vs11 {

// `program` must be well formed (Decode accepted it); validation is the caller's choice. Temporaries
// read before they are written (possible only with validation skipped) read 0. Never null: an engine
// that cannot be had (kGl without a registered maker or without a device) is an engine whose error()
// says why and whose outputs are NaN.
std::unique_ptr<Engine> MakeEngine(EngineKind kind, const Program& program, const ConstantBank& api_constants,
                                   const EngineOptions& options = {});

// An engine built by a library above vm/engines: vm/gl's RegisterGlEngine() registers kGl's. A maker
// never returns null (MakeFailedEngine instead). Registering is thread-safe; the last maker wins.
using EngineMaker = std::unique_ptr<Engine> (*)(const Program& program, const ConstantBank& api_constants,
                                                const EngineOptions& options);
void RegisterEngineMaker(EngineKind kind, EngineMaker maker);

// An engine that runs nothing: every output lane of every Run is NaN, and error() is `error`.
std::unique_ptr<Engine> MakeFailedEngine(std::string error);

}  // namespace vs11
