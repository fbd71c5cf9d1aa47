// What the later-model engine tests (static_flow_test.cc, dynamic_flow_test.cc) share: assembling a
// program, inputs v0 and v1 drawn per lane, running one engine, the engines compared with ref (batch,
// and the jit on every instruction set the CPU has), and the first lane whose bits differ.
#pragma once

#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "vm/engines/jit_options.h"

namespace vs11::later_model {

inline Program Assemble(const std::string& source) {
  const AssembleResult assembled =
      AssembleSource(source, "later.vsh", {}, [](const std::filesystem::path&) { return std::optional<std::string>(); });
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString() << "\n" << source;
  return assembled.program ? *assembled.program : Program{};
}

// v0 and v1 of `count` vertices, each lane drawn by `value()`.
template <class Value>
VertexArrays RandomInputs(std::size_t count, Value value) {
  const std::vector<int> registers = {0, 1};
  VertexArrays inputs = MakeInputArrays(count, registers);
  for (int reg : registers) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < count; ++i) inputs.lane(reg, c)[i] = value();
    }
  }
  return inputs;
}

inline VertexArrays RunOn(std::string_view name, const Program& program, const ConstantBank& bank,
                          const VertexArrays& inputs, EngineOptions options) {
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  Result<std::unique_ptr<Engine>> engine = MakeEngine(name, program, bank, options);
  EXPECT_TRUE(engine.ok()) << engine.message();
  if (engine.ok()) {
    EXPECT_EQ((*engine)->Run(inputs, outputs).message(), "");
  }
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

// What the random-program writers draw from: numbers, temporaries r0-r3, source swizzles.
class Draws {
 public:
  explicit Draws(unsigned seed) : random_(seed) {}
  int Pick(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  std::string Temp() { return fmt::format("r{}", Pick(0, 3)); }
  std::string SwizzleSuffix() {
    static constexpr const char* kSwizzles[] = {"", ".x", ".yzxw", ".wwzy", ".zzzz"};
    return kSwizzles[Pick(0, 4)];
  }
  // What one instruction has read so far: the later models' read ports allow one c# and one v#.
  struct Reads {
    bool constant = false;
    bool input = false;
  };
  // A temporary, v0-v1, c0-c`last_constant` or (in a loop) c[aL + 0..`last_offset`]; a temporary where
  // the instruction already reads a register of the file drawn.
  std::string Register(bool in_loop, Reads& reads, int last_constant, int last_offset) {
    const int kind = Pick(0, in_loop ? 3 : 2);
    if (kind == 0 || (kind == 1 && reads.input) || (kind >= 2 && reads.constant)) return Temp();
    if (kind == 1) {
      reads.input = true;
      return fmt::format("v{}", Pick(0, 1));
    }
    reads.constant = true;
    return kind == 2 ? fmt::format("c{}", Pick(0, last_constant)) : fmt::format("c[aL + {}]", Pick(0, last_offset));
  }

 private:
  std::mt19937 random_;
};

struct Candidate {
  std::string engine;
  std::string name;  // the engine and its instruction set
  EngineOptions options;
};

inline std::vector<Candidate> Candidates(FloatRules rules) {
  std::vector<Candidate> candidates = {{"batch", "batch", {.float_rules = rules}}};
  for (JitIsa isa : jit::SupportedIsas()) {
    candidates.push_back({"jit", fmt::format("jit {}", kJitIsaNames.Name(isa)), WithJitIsa({.float_rules = rules}, isa)});
  }
  return candidates;
}

}  // namespace vs11::later_model
