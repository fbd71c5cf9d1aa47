#include "vm/engines/engine_factory.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <limits>

#include <fmt/format.h>

#include "vm/engines/batch_engine.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {
namespace {

constexpr std::size_t kEngineKindCount = static_cast<std::size_t>(EngineKind::kGl) + 1;

std::array<std::atomic<EngineMaker>, kEngineKindCount>& Makers() {
  static std::array<std::atomic<EngineMaker>, kEngineKindCount> makers{};
  return makers;
}

class FailedEngine final : public Engine {
 public:
  explicit FailedEngine(std::string error) : error_(std::move(error)) {}
  void Run(const VertexArrays&, VertexArrays& outputs) override {
    for (int reg : outputs.registers()) {
      for (int c = 0; c < 4; ++c) {
        float* lane = outputs.lane(reg, c);
        std::fill(lane, lane + outputs.count(), std::numeric_limits<float>::quiet_NaN());
      }
    }
  }
  void SetConstants(const ConstantBank&) override {}
  std::string error() const override { return error_; }

 private:
  std::string error_;
};

}  // namespace

void RegisterEngineMaker(EngineKind kind, EngineMaker maker) { Makers()[static_cast<std::size_t>(kind)] = maker; }

std::unique_ptr<Engine> MakeFailedEngine(std::string error) { return std::make_unique<FailedEngine>(std::move(error)); }

std::unique_ptr<Engine> MakeEngine(EngineKind kind, const Program& program, const ConstantBank& api_constants,
                                   const EngineOptions& options) {
  if (kind == EngineKind::kReference) return MakeReferenceEngine(program, api_constants, options.float_rules);
  if (kind == EngineKind::kBatch || kind == EngineKind::kJit) {
    return MakeBatchEngine(program, api_constants, options, kind == EngineKind::kJit);
  }
  if (EngineMaker maker = Makers()[static_cast<std::size_t>(kind)].load()) return maker(program, api_constants, options);
  return MakeFailedEngine(fmt::format("the {} engine is not part of this program (only the vs11 and irrmap tools "
                                      "link vm/gl and register it)",
                                      EngineName(kind)));
}

}  // namespace vs11
