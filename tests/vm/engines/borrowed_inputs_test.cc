// Inputs the engines read in place from the caller's memory (VertexArrays::Borrow, the Python
// module's no-copy path) with any stride: interleaved registers, (x, y, z) with w from a stride-0
// lane, rows in reverse. Every engine must give, bit for bit, what it gives on the same values in
// lanes of the arrays' own, at counts around the batch size and on a call split over threads.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/program_file.h"
#include "vm/core/machine.h"
#include "vm/engines/batch_engine.h"
#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;

constexpr int kRegisters = kInputRegisterCount;
constexpr int kXyzRegister = 1;       // given as (x, y, z): w is one float read with stride 0
constexpr int kReversedRegister = 2;  // its rows stored last to first: a negative stride
constexpr float kImpliedW = 1.0f;

float Pattern(std::size_t vertex, int reg, int c) {
  if (reg == kXyzRegister && c == 3) return kImpliedW;
  return static_cast<float>(std::sin(0.37 * static_cast<double>(vertex % 4099) + 1.3 * reg + 0.7 * c)) *
         (1.0f + 0.25f * static_cast<float>(c));
}

// The same values twice: in lanes of the arrays' own, and as one caller buffer of vertices (each
// vertex's registers side by side, 4 floats each, so a lane's stride is 64 floats) that `borrowed`
// reads in place.
struct TwoLayouts {
  VertexArrays owned;
  std::vector<float> buffer;
  VertexArrays borrowed;
};

TwoLayouts MakeInputs(std::size_t count) {
  TwoLayouts inputs;
  std::array<int, kRegisters> all;
  for (int reg = 0; reg < kRegisters; ++reg) all[reg] = reg;
  inputs.owned = MakeInputArrays(count, all);
  inputs.buffer.resize(count * kRegisters * 4);
  constexpr std::ptrdiff_t kVertexStride = kRegisters * 4;
  for (int reg = 0; reg < kRegisters; ++reg) {
    for (int c = 0; c < 4; ++c) {
      float* lane = inputs.owned.lane(reg, c);
      for (std::size_t i = 0; i < count; ++i) {
        lane[i] = Pattern(i, reg, c);
        const std::size_t row = reg == kReversedRegister ? count - 1 - i : i;
        inputs.buffer[row * kVertexStride + reg * 4 + c] = lane[i];
      }
    }
  }
  inputs.borrowed = MakeInputArrays(count, {});
  for (int reg = 0; reg < kRegisters; ++reg) {
    std::array<StridedLane, 4> lanes;
    for (int c = 0; c < 4; ++c) {
      const float* first = inputs.buffer.data() + reg * 4 + c;
      lanes[c] = reg == kReversedRegister
                     ? StridedLane{first + static_cast<std::ptrdiff_t>(count - 1) * kVertexStride, -kVertexStride}
                     : StridedLane{first, kVertexStride};
    }
    if (reg == kXyzRegister) lanes[3] = {&kImpliedW, 0};
    inputs.borrowed.Borrow(reg, lanes);
  }
  return inputs;
}

std::vector<std::pair<std::string, Program>> ProgramsFolder() {
  LoadProgramOptions options;
  options.assemble.validate = false;  // the irradiance programs write no oPos
  std::vector<fs::path> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VS11_SOURCE_DIR) / "programs")) {
    if (entry.path().extension() == ".vsh") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<std::pair<std::string, Program>> programs;
  for (const fs::path& path : paths) {
    LoadedProgram loaded = LoadProgram(path, options);
    EXPECT_TRUE(loaded.program) << path << ": " << loaded.diagnostics.ToString();
    if (loaded.program) programs.emplace_back(path.filename().string(), std::move(*loaded.program));
  }
  EXPECT_GE(programs.size(), 10u);
  return programs;
}

ConstantBank PatternConstants() {
  ConstantBank bank;
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) bank[reg][c] = static_cast<float>(std::cos(0.61 * reg + 1.1 * c));
  }
  return bank;
}

VertexArrays RunOn(std::string kind, const Program& program, const VertexArrays& inputs, int threads = 1) {
  EngineOptions options;
  options.threads = threads;
  VertexArrays outputs = MakeOutputArrays(inputs.count(), program);
  EXPECT_EQ(MakeEngine(kind, program, PatternConstants(), options).value()->Run(inputs, outputs).message(), "");
  return outputs;
}

void ExpectSameBits(const VertexArrays& actual, const VertexArrays& expected, const std::string& context) {
  ASSERT_EQ(actual.registers(), expected.registers()) << context;
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < expected.count(); ++i) {
        const float a = actual.lane(slot, c)[i], e = expected.lane(slot, c)[i];
        if (std::bit_cast<std::uint32_t>(a) != std::bit_cast<std::uint32_t>(e)) {
          ADD_FAILURE() << context << ": " << OutputSlotName(slot) << "." << "xyzw"[c] << " of vertex " << i << " is "
                        << a << " read in place, " << e << " from lanes of its own";
          return;
        }
      }
    }
  }
}

TEST(BorrowedInputs, ViewsReadTheCallersMemoryWithItsStrides) {
  TwoLayouts inputs = MakeInputs(5);
  EXPECT_EQ(inputs.borrowed.registers(), inputs.owned.registers());
  for (int reg = 0; reg < kRegisters; ++reg) {
    EXPECT_TRUE(inputs.borrowed.borrowed(reg));
    EXPECT_FALSE(inputs.owned.borrowed(reg));
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(inputs.borrowed.view(reg, c)[i], inputs.owned.view(reg, c)[i]);
    }
  }
  EXPECT_EQ(inputs.borrowed.uniform(kXyzRegister, 3), kImpliedW);  // stride 0: one value
  EXPECT_EQ(inputs.borrowed.uniform(kXyzRegister, 2), std::nullopt);
  inputs.buffer[3] = 42.0f;  // v0.w of vertex 0: read where it lies, not copied
  EXPECT_EQ(inputs.borrowed.view(0, 3)[0], 42.0f);
}

TEST(BorrowedInputs, EveryEngineGivesTheBitsOfOwnedLanesForEveryProgram) {
  for (const auto& [name, program] : ProgramsFolder()) {
    for (std::size_t count : {1, 257, 1000}) {  // a part of a batch; a whole batch and 1; 3 and a part
      const TwoLayouts inputs = MakeInputs(count);
      for (std::string kind : {"ref", "batch", "jit"}) {
        ExpectSameBits(RunOn(kind, program, inputs.borrowed), RunOn(kind, program, inputs.owned),
                       name + " " + std::string(kind) + ", " + std::to_string(count) + " vertices");
      }
    }
  }
}

// A call large enough to split over two threads (four of its pieces, MinVerticesPerPiece).
TEST(BorrowedInputs, ASplitCallGivesTheBitsOfOwnedLanes) {
  for (const auto& [name, program] : ProgramsFolder()) {
    if (name != "sh9_irradiance.vsh") continue;
    const std::size_t piece = MinVerticesPerPiece(program);
    ASSERT_NE(piece, kNeverSplit) << name;
    const TwoLayouts inputs = MakeInputs(4 * piece + 37);
    for (std::string kind : {"batch", "jit"}) {
      ExpectSameBits(RunOn(kind, program, inputs.borrowed, 2), RunOn(kind, program, inputs.owned, 1),
                     name + " " + std::string(kind) + " on 2 threads");
    }
  }
}

}  // namespace
}  // namespace vs11
