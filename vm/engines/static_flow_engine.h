// The batch, jit and gl engines on a later model's program (vs_2_0 on) whose flow control is static: the
// program is specialised for the integer and boolean constants (vm/core/static_flow.h) into straight
// code, which the engine runs as a vs_1_1 program with the later model's registers. A specialisation
// is built when the engine is made and again in SetConstants only when i#, b# or the bank's size
// change; the last few are kept by those values with their compiled engines, so switching back costs
// nothing.
#pragma once

#include <memory>
#include <string_view>

#include "vm/core/machine.h"

namespace vs11 {

using StraightLineEngineMaker = Result<std::unique_ptr<Engine>> (*)(const Program&, const ConstantBank&,
                                                                 const EngineOptions&);

// `program` must pass EngineRefusal(program, engine); `make` builds the engine that runs each
// specialisation. Fails when the program does not specialise for `api_constants` (the unrolling is too
// long) or `make` fails on the specialisation. When later constants do not, SetConstants returns why
// (kEngineUnavailable from the specialisation, or `make`'s own code), and every Run until a
// SetConstants that works returns the same Diagnostic and writes NaN (Engine::Run).
Result<std::unique_ptr<Engine>> MakeStaticFlowEngine(const Program& program, const ConstantBank& api_constants,
                                                     const EngineOptions& options, std::string_view engine,
                                                     StraightLineEngineMaker make);

// How many specialisations `engine` (one MakeStaticFlowEngine made) has built; -1 for another engine.
int SpecialisationCount(const Engine& engine);

}  // namespace vs11
