// Running one program on several engines and comparing their outputs bit for bit, for the later
// models' differential tests (static_flow_test.cc, later_arithmetic_test.cc).
#pragma once

#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "vm/engines/jit_options.h"

namespace vs11::engine_comparison {

// `program`'s outputs on engine `name` (a failure to make it is a test failure; the outputs stay 0).
inline VertexArrays RunOn(std::string_view name, const Program& program, const ConstantBank& bank,
                          const VertexArrays& inputs, const EngineOptions& options) {
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  Result<std::unique_ptr<Engine>> engine = MakeEngine(name, program, bank, options);
  EXPECT_TRUE(engine.ok()) << name << ": " << engine.message();
  if (engine.ok()) (*engine)->Run(inputs, outputs);
  return outputs;
}

// The first lane whose bits differ (any NaN matches any NaN), or empty.
inline std::string Difference(const VertexArrays& expected, const VertexArrays& actual) {
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < expected.count(); ++i) {
        const float a = expected.lane(slot, c)[i], b = actual.lane(slot, c)[i];
        if (std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b)) continue;
        return fmt::format("{}.{} of vertex {}: ref {} got {}", OutputSlotName(slot), kLaneLetters[c], i, a, b);
      }
    }
  }
  return {};
}

// An engine to compare with ref: "batch", or "jit avx2" (the engine's name, then its instruction set).
struct Candidate {
  std::string name;
  EngineOptions options;
  std::string engine() const { return name.substr(0, name.find(' ')); }
};

// batch, and the jit at every instruction set the CPU has, under `rules`.
inline std::vector<Candidate> Candidates(FloatRules rules) {
  std::vector<Candidate> candidates = {{"batch", {.float_rules = rules}}};
  for (JitIsa isa : jit::SupportedIsas()) {
    candidates.push_back({fmt::format("jit {}", kJitIsaNames.Name(isa)), WithJitIsa({.float_rules = rules}, isa)});
  }
  return candidates;
}

}  // namespace vs11::engine_comparison
