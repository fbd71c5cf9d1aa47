#include "vm/engines/engine_factory.h"

#include "vm/engines/batch_engine.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {

std::unique_ptr<Engine> MakeEngine(EngineKind kind, const Program& program, const ConstantBank& api_constants,
                                   const EngineOptions& options) {
  if (kind == EngineKind::kReference) return MakeReferenceEngine(program, api_constants, options.float_rules);
  return MakeBatchEngine(program, api_constants, options, kind == EngineKind::kJit);
}

}  // namespace vs11
