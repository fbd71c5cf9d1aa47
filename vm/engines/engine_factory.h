// The engines by name: a registry of every engine the program can build (name, summary, maker), and
// MakeEngine. The core (core/machine.h) declares the interface and knows no engine. The engines of
// this folder (ref, batch, jit) are registered here, in engine_factory.cc's one list; an engine built
// by a library above (vm/gl's gl engine) registers itself through RegisterEngine, which the tools call
// explicitly (gl::RegisterGlEngine) before they parse their arguments. No registration happens in a
// static initialiser: a linker drops the unreferenced object files of a static library, and with them
// such registrations.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11 {

// Builds an engine, or says why it cannot (the gl engine without a device). Never a null engine.
using EngineMaker = Result<std::unique_ptr<Engine>> (*)(const Program& program, const ConstantBank& api_constants,
                                                        const EngineOptions& options);

struct EngineInfo {
  std::string_view name;     // what --engine takes and reports print: "ref", "batch"
  std::string_view alias;    // another spelling accepted for it ("reference"), or empty
  std::string_view summary;  // what it is, for --help: "SIMD kernels"
  EngineMaker make = nullptr;
};

// Adds an engine (its strings must outlive the process: literals), or replaces the one of the same
// name. Thread-safe.
void RegisterEngine(const EngineInfo& info);
// Removes the engine of this name, if any (tests: a program without the gl engine). Thread-safe.
void UnregisterEngine(std::string_view name);

// Every registered engine, this folder's first, then in the order of registration.
std::vector<EngineInfo> RegisteredEngines();
// The engine of this name or alias; nullopt when none is registered under it.
std::optional<EngineInfo> FindEngine(std::string_view name);
// Every name and alias ("ref", "reference", "batch", ...), for a command line's list of choices.
std::vector<std::string> EngineSpellings();
// "ref, batch, jit or gl" for messages: the registered names, `quote` around each.
std::string EngineNameList(std::string_view quote = "");
// "ref (scalar reference), batch (SIMD kernels), ... or gl (...)" for --help.
std::string EngineDescriptions();

// `program` must be well formed (Decode accepted it); validation is the caller's choice. Temporaries
// read before they are written (possible only with validation skipped) read 0. An error where the
// engine cannot be had: a name nobody registered (kEngineUnavailable), the gl engine without a device.
// The CPU engines (ref, batch, jit) never fail.
Result<std::unique_ptr<Engine>> MakeEngine(std::string_view name, const Program& program,
                                           const ConstantBank& api_constants, const EngineOptions& options = {});

}  // namespace vs11
