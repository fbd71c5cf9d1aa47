#include "vm/engines/static_flow_engine.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "vm/core/static_flow.h"

namespace vs11 {
namespace {

// Specialisations kept: a program's i#/b# usually take a few values (a bone count, a light count).
constexpr std::size_t kMaxSpecialisations = 8;

struct Specialisation {
  StaticFlowKey key;
  std::array<WriteMask, kOutputSlotCount> written;  // by the straight-line program
  std::unique_ptr<Engine> engine;
};

class StaticFlowEngine final : public Engine {
 public:
  StaticFlowEngine(const Program& program, const EngineOptions& options, std::string_view engine,
                   StraightLineEngineMaker make)
      : program_(program), written_(WrittenOutputLanes(program)), options_(options), name_(engine), make_(make) {}

  // Runs the specialisation for these constants from now on, building it unless it is cached; or why
  // the program does not specialise for them (Run then returns it and writes NaN).
  Status SetConstants(const ConstantBank& api_constants) override {
    const ConstantBank bank = ModelConstants(program_, api_constants);
    const StaticFlowKey key = StaticFlowKeyOf(bank);
    auto found = std::ranges::find_if(cache_, [&](const Specialisation& s) { return s.key == key; });
    if (found == cache_.end()) {
      ++specialisations_;
      Result<Program> straight = SpecialiseStaticFlow(program_, key, name_);
      if (!straight) return Fail(straight.error());
      Result<std::unique_ptr<Engine>> made = make_(*straight, bank, options_);
      if (!made) return Fail(made.error());
      if (cache_.size() == kMaxSpecialisations) cache_.erase(cache_.begin());  // the least recently used
      cache_.push_back({key, WrittenOutputLanes(*straight), std::move(made).value()});
    } else {
      std::rotate(found, found + 1, cache_.end());  // most recently used last
    }
    current_ = &cache_.back();
    failure_ = {};
    if (Status set = current_->engine->SetConstants(bank); !set) return Fail(set.error());
    return {};
  }

  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    if (current_ == nullptr) {
      FillWithNaN(outputs);
      return failure_;
    }
    if (Status ran = current_->engine->Run(inputs, outputs); !ran) return ran;
    // An output the program writes somewhere starts at 0 in the reference engine, even where this
    // specialisation never writes it (the straight-line engine would give UnwrittenOutputValue).
    for (int slot : outputs.registers()) {
      if (!written_[slot].bits() || current_->written[slot].bits()) continue;
      const Vec4f unwritten = UnwrittenOutputValue(slot);
      for (int c = 0; c < 4; ++c) {
        if (unwritten[c] != 0.0f) std::fill_n(outputs.lane(slot, c), inputs.count(), 0.0f);
      }
    }
    return {};
  }

  int specialisations() const { return specialisations_; }

 private:
  Program program_;
  std::array<WriteMask, kOutputSlotCount> written_;
  EngineOptions options_;
  std::string name_;
  StraightLineEngineMaker make_;
  std::vector<Specialisation> cache_;
  // Null after a failed SetConstants: Run then returns failure_.
  Specialisation* current_ = nullptr;
  Status failure_;
  int specialisations_ = 0;

  // Keeps `error` for the Runs that follow (the specialisation they would run is gone).
  Status Fail(const Diagnostic& error) {
    current_ = nullptr;
    failure_ = error;
    return failure_;
  }
};

}  // namespace

Result<std::unique_ptr<Engine>> MakeStaticFlowEngine(const Program& program, const ConstantBank& api_constants,
                                                     const EngineOptions& options, std::string_view engine,
                                                     StraightLineEngineMaker make) {
  auto made = std::make_unique<StaticFlowEngine>(program, options, engine, make);
  if (Status specialised = made->SetConstants(api_constants); !specialised) return specialised.error();
  return std::unique_ptr<Engine>(std::move(made));
}

int SpecialisationCount(const Engine& engine) {
  const auto* flow = dynamic_cast<const StaticFlowEngine*>(&engine);
  return flow != nullptr ? flow->specialisations() : -1;
}

}  // namespace vs11
