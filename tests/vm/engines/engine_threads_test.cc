// Engines on several threads at once, as vm/core/machine.h promises: one engine per thread, with the
// Program, the ConstantBank and the input arrays shared read-only; and one engine's own threads
// (EngineOptions::threads). Every result is compared bit for bit with the same work done on one
// thread. CI's ThreadSanitizer stage (.ci/tsan) runs these.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_threads.h"
#include "vm/asm/program_file.h"
#include "vm/core/machine.h"
#include "vm/engines/batch_engine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_options.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using vs11::testing::RunOnThreads;

const std::string kAllKinds[] = {"ref", "batch", "jit"};

struct NamedProgram {
  std::string name;
  Program program;
};

// Every program of programs/, in name order. Not validated: the irradiance programs write no oPos,
// which the validator requires of a complete shader; the engines run them all the same.
std::vector<NamedProgram> ProgramsFolder() {
  LoadProgramOptions options;
  options.assemble.validate = false;
  std::vector<fs::path> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() == ".vsh") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<NamedProgram> programs;
  for (const fs::path& path : paths) {
    LoadedProgram loaded = LoadProgram(path, options);
    EXPECT_TRUE(loaded.program) << path << ": " << loaded.diagnostics.ToString();
    if (loaded.program) programs.push_back({path.filename().string(), std::move(*loaded.program)});
  }
  EXPECT_GE(programs.size(), 10u) << "programs/ lost its programs";
  return programs;
}

const NamedProgram& Find(const std::vector<NamedProgram>& programs, const std::string& name) {
  const auto found = std::find_if(programs.begin(), programs.end(), [&](const auto& p) { return p.name == name; });
  EXPECT_NE(found, programs.end()) << name;
  return found != programs.end() ? *found : programs.front();
}

// v0..v15 for `count` vertices, every lane different, values of both signs around 1 (normals,
// positions, blend indices of a few bones: what the folder's programs read).
VertexArrays PatternInputs(std::size_t count) {
  std::array<int, kInputRegisterCount> registers;
  for (int reg = 0; reg < kInputRegisterCount; ++reg) registers[reg] = reg;
  VertexArrays inputs = MakeInputArrays(count, registers);
  for (int reg = 0; reg < kInputRegisterCount; ++reg) {
    for (int c = 0; c < 4; ++c) {
      // A pattern of a prime period, computed once: a call of 2^18 vertices fills 64 lanes, and a
      // sine per value would cost more than the runs. A piece that started at the wrong vertex would
      // still read other values (pieces are whole batches, and no multiple of 64 below 2^18 is one
      // of 4099).
      constexpr std::size_t kPeriod = 4099;
      float* lane = inputs.lane(reg, c);
      for (std::size_t i = 0; i < std::min(count, kPeriod); ++i) {
        lane[i] = static_cast<float>(std::sin(0.37 * static_cast<double>(i) + 1.3 * reg + 0.7 * c)) * (1.0f + 0.25f * c);
      }
      for (std::size_t i = kPeriod; i < count; ++i) lane[i] = lane[i - kPeriod];
    }
  }
  return inputs;
}

ConstantBank PatternConstants() {
  ConstantBank bank;
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) bank[reg][c] = static_cast<float>(std::cos(0.61 * reg + 1.1 * c));
  }
  return bank;
}

VertexArrays RunEngine(Engine& engine, const Program& program, const VertexArrays& inputs) {
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  EXPECT_EQ(engine.Run(inputs, outputs).message(), "");
  return outputs;
}

VertexArrays RunOnce(std::string kind, const Program& program, const ConstantBank& constants,
                     const VertexArrays& inputs, const EngineOptions& options = {}) {
  return RunEngine(*MakeEngine(kind, program, constants, options).value(), program, inputs);
}

// The first lane of two runs' outputs whose bits differ, reported with `context`.
void ExpectSameBits(const VertexArrays& actual, const VertexArrays& expected, const std::string& context) {
  ASSERT_EQ(actual.registers(), expected.registers()) << context;
  ASSERT_EQ(actual.count(), expected.count()) << context;
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      const float* a = actual.lane(slot, c);
      const float* e = expected.lane(slot, c);
      for (std::size_t i = 0; i < expected.count(); ++i) {
        if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(e[i])) {
          ADD_FAILURE() << context << ": " << OutputSlotName(slot) << "." << "xyzw"[c] << " of vertex " << i << " is "
                        << a[i] << ", alone " << e[i];
          return;
        }
      }
    }
  }
}

// Each kind: four threads make their own engine for one shared program, constant bank and input
// arrays (the jit compiles on all four at once) and run it twice.
TEST(EngineThreads, EnginesOnSeparateThreadsShareOneProgramConstantsAndInputs) {
  const std::vector<NamedProgram> programs = ProgramsFolder();
  const Program& program = Find(programs, "sh9_irradiance.vsh").program;
  const ConstantBank constants = PatternConstants();
  const VertexArrays inputs = PatternInputs(3000);
  for (std::string kind : kAllKinds) {
    const VertexArrays alone = RunOnce(kind, program, constants, inputs);
    RunOnThreads(4, [&](int t) {
      std::unique_ptr<Engine> engine = MakeEngine(kind, program, constants).value();
      for (int round = 0; round < 2; ++round) {
        ExpectSameBits(RunEngine(*engine, program, inputs), alone,
                       std::string(kind) + " thread " + std::to_string(t) + " round " + std::to_string(round));
      }
    });
  }
}

// One thread per program of programs/, all compiling and running their jit engines at once: with
// every input lane read, then with two lanes known uniform (VertexArrays::FillUniform), which makes
// Run compile another variant of the program (vm/engines/batch_engine.cc, SelectCompiled).
// Odd threads force AVX2, so both instruction sets compile side by side where the CPU has AVX-512.
TEST(EngineThreads, JitCompilesAndRunsEveryProgramAtOnce) {
  const std::vector<NamedProgram> programs = ProgramsFolder();
  const ConstantBank constants = PatternConstants();
  const VertexArrays inputs = PatternInputs(1000);
  VertexArrays uniform_inputs = PatternInputs(1000);
  uniform_inputs.FillUniform(0, 3, 1.0f);
  uniform_inputs.FillUniform(1, 2, -0.5f);
  auto options_of = [](std::size_t index) {
    EngineOptions options;
    options = WithJitIsa(options, index % 2 ? JitIsa::kAvx2 : JitIsa::kBest);
    return options;
  };
  std::vector<VertexArrays> alone, alone_uniform;
  for (std::size_t p = 0; p < programs.size(); ++p) {
    alone.push_back(RunOnce("jit", programs[p].program, constants, inputs, options_of(p)));
    alone_uniform.push_back(RunOnce("jit", programs[p].program, constants, uniform_inputs, options_of(p)));
  }
  RunOnThreads(static_cast<int>(programs.size()), [&](int t) {
    const std::size_t p = static_cast<std::size_t>(t);
    const Program& program = programs[p].program;
    std::unique_ptr<Engine> engine = MakeEngine("jit", program, constants, options_of(p)).value();
    ExpectSameBits(RunEngine(*engine, program, inputs), alone[p], programs[p].name);
    ExpectSameBits(RunEngine(*engine, program, uniform_inputs), alone_uniform[p], programs[p].name + ", uniform lanes");
    ExpectSameBits(RunEngine(*engine, program, inputs), alone[p], programs[p].name + ", again");
  });
}

// The batch and jit engines split a large call over EngineOptions::threads: every program of
// programs/ at every count of threads gives the bits of one thread. Each call is sized to four of
// the program's pieces (MinVerticesPerPiece), so that 2, 3 and 4 threads all split it; a program
// that never splits runs 2^16 vertices and must give one thread's bits too.
TEST(EngineThreads, ThreadSplitGivesTheBitsOfOneThreadForEveryProgram) {
  const ConstantBank constants = PatternConstants();
  int split_programs = 0;
  for (const NamedProgram& named : ProgramsFolder()) {
    const std::size_t piece = MinVerticesPerPiece(named.program);
    const std::size_t count = piece == kNeverSplit ? std::size_t{1} << 16 : 4 * piece + 37;
    split_programs += piece != kNeverSplit;
    const VertexArrays inputs = PatternInputs(count);
    for (std::string kind : {"batch", "jit"}) {
      const VertexArrays one = RunOnce(kind, named.program, constants, inputs);
      for (int threads : {2, 3, 4}) {
        EngineOptions options;
        options.threads = threads;
        ExpectSameBits(RunOnce(kind, named.program, constants, inputs, options), one,
                       named.name + " " + std::string(kind) + " threads " + std::to_string(threads) +
                           ", " + std::to_string(count) + " vertices");
      }
    }
  }
  EXPECT_GE(split_programs, 10) << "most programs of programs/ should be worth splitting at some count";
}

// Engines that split their calls, run from several threads at once: threads inside threads.
TEST(EngineThreads, SplittingEnginesRunSideBySide) {
  const std::vector<NamedProgram> programs = ProgramsFolder();
  const Program& program = Find(programs, "sh9_irradiance.vsh").program;
  const ConstantBank constants = PatternConstants();
  const VertexArrays inputs = PatternInputs(std::size_t{1} << 17);
  const VertexArrays one = RunOnce("jit", program, constants, inputs);
  RunOnThreads(3, [&](int t) {
    EngineOptions options;
    options.threads = 2;
    const std::string kind = t == 1 ? "batch" : "jit";
    ExpectSameBits(RunOnce(kind, program, constants, inputs, options), one,
                   std::string(kind) + " on thread " + std::to_string(t));
  });
}

}  // namespace
}  // namespace vs11
