#include "vm/engines/engine_factory.h"

#include <algorithm>
#include <mutex>

#include <fmt/format.h>

#include "vm/engines/batch_engine.h"
#include "vm/engines/reference_engine.h"
#include "vm/engines/static_flow_engine.h"

namespace vs11 {
namespace {

Result<std::unique_ptr<Engine>> MakeReference(const Program& program, const ConstantBank& api_constants,
                                              const EngineOptions& options) {
  return MakeReferenceEngine(program, api_constants, options.float_rules);
}

Result<std::unique_ptr<Engine>> MakeBatch(const Program& program, const ConstantBank& api_constants,
                                          const EngineOptions& options) {
  if (!Info(program.model()).runs) return MakeStaticFlowEngine(program, api_constants, options, "batch", &MakeBatch);
  return MakeBatchEngine(program, api_constants, options);
}

Result<std::unique_ptr<Engine>> MakeJit(const Program& program, const ConstantBank& api_constants,
                                        const EngineOptions& options) {
  if (!Info(program.model()).runs) return MakeStaticFlowEngine(program, api_constants, options, "jit", &MakeJit);
  return MakeJitEngine(program, api_constants, options);
}

// The engines of this folder, in the order --help lists them. An engine of this folder is added here;
// one of a library above registers itself (RegisterEngine).
constexpr EngineInfo kBuiltInEngines[] = {
    {"ref", "reference", "scalar reference", &MakeReference},
    {"batch", "", "SIMD kernels", &MakeBatch},
    {"jit", "", "the program compiled to AVX-512 or AVX2 code; the batch kernels on a CPU without AVX2", &MakeJit},
};

struct Registry {
  std::mutex mutex;
  std::vector<EngineInfo> engines{std::begin(kBuiltInEngines), std::end(kBuiltInEngines)};
};

Registry& TheRegistry() {
  static Registry registry;
  return registry;
}

}  // namespace

void RegisterEngine(const EngineInfo& info) {
  Registry& registry = TheRegistry();
  std::lock_guard lock(registry.mutex);
  auto same_name = [&](const EngineInfo& engine) { return engine.name == info.name; };
  if (auto found = std::find_if(registry.engines.begin(), registry.engines.end(), same_name);
      found != registry.engines.end()) {
    *found = info;
  } else {
    registry.engines.push_back(info);
  }
}

void UnregisterEngine(std::string_view name) {
  Registry& registry = TheRegistry();
  std::lock_guard lock(registry.mutex);
  std::erase_if(registry.engines, [&](const EngineInfo& engine) { return engine.name == name; });
}

std::vector<EngineInfo> RegisteredEngines() {
  Registry& registry = TheRegistry();
  std::lock_guard lock(registry.mutex);
  return registry.engines;
}

std::optional<EngineInfo> FindEngine(std::string_view name) {
  for (const EngineInfo& engine : RegisteredEngines()) {
    if (!name.empty() && (engine.name == name || engine.alias == name)) return engine;
  }
  return std::nullopt;
}

std::vector<std::string> EngineSpellings() {
  std::vector<std::string> spellings;
  for (const EngineInfo& engine : RegisteredEngines()) {
    spellings.emplace_back(engine.name);
    if (!engine.alias.empty()) spellings.emplace_back(engine.alias);
  }
  return spellings;
}

namespace {

// "a, b, c or d" of each registered engine's `describe`.
template <class Describe>
std::string JoinEngines(Describe describe) {
  const std::vector<EngineInfo> engines = RegisteredEngines();
  std::string list;
  for (std::size_t i = 0; i < engines.size(); ++i) {
    list += i == 0 ? "" : i + 1 == engines.size() ? " or " : ", ";
    list += describe(engines[i]);
  }
  return list;
}

}  // namespace

std::string EngineNameList(std::string_view quote) {
  return JoinEngines([&](const EngineInfo& engine) { return fmt::format("{0}{1}{0}", quote, engine.name); });
}

std::string EngineDescriptions() {
  return JoinEngines([](const EngineInfo& engine) { return fmt::format("{} ({})", engine.name, engine.summary); });
}

Result<std::unique_ptr<Engine>> MakeEngine(std::string_view name, const Program& program,
                                           const ConstantBank& api_constants, const EngineOptions& options) {
  if (std::optional<EngineInfo> engine = FindEngine(name)) {
    // By its name, so that an alias (reference) is refused or allowed as the engine itself.
    if (Status refusal = EngineRefusal(program, engine->name); !refusal) return refusal.error();
    return engine->make(program, api_constants, options);
  }
  if (Status refusal = EngineRefusal(program, name); !refusal) return refusal.error();
  return Failure(DiagnosticCode::kEngineUnavailable,
                 fmt::format("the {} engine is not part of this program (it has {}; the vs11 and irrmap tools "
                             "register vm/gl's gl engine)",
                             name, EngineNameList()));
}

}  // namespace vs11
