// The jit compiler's compiled program called directly, as the batch engine calls it but with any
// vertex count (issue 19): for every instruction set the CPU runs, the compiled loop computes exactly
// `count` vertices, bit for bit as the reference engine does, and reads and writes nothing past them.
//
// Every lane ends where an inaccessible page begins, so a read or write past it faults in any build;
// an output lane also holds sentinel floats between `count` and that page, which must keep their
// bits. (AddressSanitizer does not see these accesses: it checks only the loads and stores the
// compiler generated, not the jit's machine code.)
#include "vm/engines/jit_compiler.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include "vm/asm/assembler.h"
#include "vm/asm/program_file.h"
#include "vm/core/machine.h"
#include "vm/engines/batch_plan.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {
namespace {

std::uint32_t Bits(float x) { return std::bit_cast<std::uint32_t>(x); }

// The counts the issue names (around the 16 lanes of a zmm register and the 32 vertices of two
// interleaved groups), and one large enough that the outputs are stored around the caches
// (kStreamingOutputBytes) with a remainder.
constexpr std::size_t kLargeCount = 65536 + 33;
constexpr std::size_t kCounts[] = {0, 1, 15, 16, 17, 31, 32, 33, kLargeCount};

// Floats after each output lane that must keep their bits: at least twice the widest iteration (two
// interleaved groups of 16), so that an iteration run past the end lands in them.
constexpr std::size_t kGuardFloats = 64;
constexpr std::uint32_t kSentinelBits = 0xFFBADBADu;  // a NaN no program computes from finite inputs
constexpr std::size_t kFloatsPerCacheLine = 64 / sizeof(float);

// `size` floats that end where an inaccessible page begins.
class FloatsBeforeGuardPage {
 public:
  explicit FloatsBeforeGuardPage(std::size_t size) : size_(size) {
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t data_bytes = (size * sizeof(float) + page - 1) / page * page;
    mapped_bytes_ = data_bytes + page;
    mapping_ = mmap(nullptr, mapped_bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapping_ == MAP_FAILED) {
      ADD_FAILURE() << "mmap of " << mapped_bytes_ << " bytes failed";
      mapping_ = nullptr;
      return;
    }
    std::byte* guard = static_cast<std::byte*>(mapping_) + data_bytes;
    EXPECT_EQ(mprotect(guard, page, PROT_NONE), 0);
    data_ = reinterpret_cast<float*>(guard) - size;
  }
  FloatsBeforeGuardPage(const FloatsBeforeGuardPage&) = delete;
  FloatsBeforeGuardPage& operator=(const FloatsBeforeGuardPage&) = delete;
  ~FloatsBeforeGuardPage() {
    if (mapping_ != nullptr) munmap(mapping_, mapped_bytes_);
  }
  float* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  std::size_t size_;
  std::size_t mapped_bytes_ = 0;
  void* mapping_ = nullptr;
  float* data_ = nullptr;
};
using Lane = std::unique_ptr<FloatsBeforeGuardPage>;

// An output lane's floats: `count`, then at least kGuardFloats sentinels, the total a whole number
// of cache lines so that the lane starts on one (the streaming stores need vector-aligned lanes).
constexpr std::size_t OutputLaneFloats(std::size_t count) {
  return (count + kGuardFloats + kFloatsPerCacheLine - 1) / kFloatsPerCacheLine * kFloatsPerCacheLine;
}

// The program: exp has a long dependency chain, so AVX-512 runs two groups of 16 vertices
// per iteration.
constexpr const char* kExpProgram = "vs_1_1\ndcl_position v0\nexp r0, v0.x\nmov oPos, r0\n";

// Every temporary alive at once, each mixed with two others three times: 48 values for 16 or 32
// vector registers, so the register allocator spills and reloads inside the loop.
std::string RegisterPressureProgram() {
  constexpr int kTemps = 12;
  std::string text = "vs_1_1\n";
  for (int k = 0; k < 16; ++k) text += "dcl_texcoord" + std::to_string(k) + " v" + std::to_string(k) + "\n";
  for (int t = 0; t < kTemps; ++t) {
    text += "mul r" + std::to_string(t) + ", v" + std::to_string(t) + ", c" + std::to_string(t) + "\n";
    text += "add r" + std::to_string(t) + ", r" + std::to_string(t) + ", v" + std::to_string(t + 4) + "\n";
  }
  for (int round = 0; round < 3; ++round) {
    for (int t = 0; t < kTemps; ++t) {
      text += "mad r" + std::to_string(t) + ", r" + std::to_string(t) + ", r" + std::to_string((t + 1) % kTemps) +
              ", r" + std::to_string((t + 5) % kTemps) + "\n";
    }
  }
  for (int k = 0; k < 8; ++k) text += "mov oT" + std::to_string(k) + ", r" + std::to_string(k) + "\n";
  text += "mov oPos, r8\nmov oD0, r9\nmov oD1, r10\nmov oFog, r11.x\n";
  return text;
}

struct NamedProgram {
  std::string name;
  Program program;
};

Program AssembleOrFail(const std::string& text, const std::string& name) {
  AssembleResult assembled = AssembleSource(text, name + ".vsh", {});
  EXPECT_TRUE(assembled.program.has_value()) << name << ": " << assembled.diagnostics.ToString();
  return assembled.program.value_or(Program{});
}

std::vector<std::string> ProgramNames() {
  std::vector<std::string> names = {"exp_to_position", "register_pressure"};
  const std::filesystem::path directory = std::filesystem::path(VS11_SOURCE_DIR) / "programs";
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.path().extension() == ".vsh") files.push_back(entry.path().stem().string());
  }
  std::sort(files.begin(), files.end());
  names.insert(names.end(), files.begin(), files.end());
  return names;
}

Program LoadNamed(const std::string& name) {
  if (name == "exp_to_position") return AssembleOrFail(kExpProgram, name);
  if (name == "register_pressure") return AssembleOrFail(RegisterPressureProgram(), name);
  LoadProgramOptions options;
  options.assemble.require_position = false;  // the sh* programs are fragments that write only oD0
  const LoadedProgram loaded =
      LoadProgram(std::filesystem::path(VS11_SOURCE_DIR) / "programs" / (name + ".vsh"), options);
  EXPECT_TRUE(loaded.program.has_value()) << name << ": " << loaded.diagnostics.ToString();
  return loaded.program.value_or(Program{});
}

// Every input register filled with values in [-2, 2], and every constant in [-1, 1] under the
// program's own defs.
VertexArrays RandomInputs(std::size_t count, std::mt19937& rng) {
  std::vector<int> registers(kInputRegisterCount);
  for (int reg = 0; reg < kInputRegisterCount; ++reg) registers[static_cast<std::size_t>(reg)] = reg;
  VertexArrays inputs = MakeInputArrays(count, registers);
  std::uniform_real_distribution<float> value(-2.0f, 2.0f);
  for (int reg : registers) {
    for (int c = 0; c < 4; ++c) {
      float* lane = inputs.lane(reg, c);
      for (std::size_t i = 0; i < count; ++i) lane[i] = value(rng);
    }
  }
  return inputs;
}

ConstantBank RandomConstants(const Program& program, std::mt19937& rng) {
  ConstantBank bank;
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int reg = 0; reg < bank.size(); ++reg) bank[reg] = {value(rng), value(rng), value(rng), value(rng)};
  return ApplyDefinitions(program, bank);
}

// The constant table as the batch engine lays it out (vm/engines/batch_plan.h): row 0 zeros, c# at
// row kFirstConstantRow + #.
std::vector<float> ConstantTable(const ConstantBank& bank) {
  std::vector<float> table(4 * static_cast<std::size_t>(batch::kFirstConstantRow + bank.size()), 0.0f);
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) table[batch::ConstantIndex(reg, c)] = bank[reg][c];
  }
  return table;
}

// Runs `compiled` over `inputs` through a lane table of its own: inputs copied into `count` floats
// before a guard page, every output lane OutputLaneFloats(count) sentinels before one.
// Returns the output lanes by lane table index (kOutputLaneBase + 4 slot + c).
std::vector<Lane> RunCompiled(const jit::CompiledProgram& compiled, const VertexArrays& inputs,
                                       const std::vector<float>& constants, std::int32_t constant_count) {
  const std::size_t count = inputs.count();
  std::vector<const float*> read_lanes(batch::kArenaLaneBase, nullptr);
  std::vector<float*> write_lanes(batch::kArenaLaneBase, nullptr);
  std::vector<Lane> input_lanes;
  for (int reg = 0; reg < kInputRegisterCount; ++reg) {
    for (int c = 0; c < 4; ++c) {
      const Lane& lane = input_lanes.emplace_back(std::make_unique<FloatsBeforeGuardPage>(count));
      std::copy_n(inputs.lane(reg, c), count, lane->data());
      read_lanes[static_cast<std::size_t>(batch::InputLane(reg, c))] = lane->data();
    }
  }
  std::vector<Lane> output_lanes;
  for (int lane = batch::kOutputLaneBase; lane < batch::kArenaLaneBase; ++lane) {
    const Lane& output = output_lanes.emplace_back(std::make_unique<FloatsBeforeGuardPage>(OutputLaneFloats(count)));
    std::fill_n(output->data(), output->size(), std::bit_cast<float>(kSentinelBits));
    read_lanes[static_cast<std::size_t>(lane)] = write_lanes[static_cast<std::size_t>(lane)] = output->data();
  }
  std::vector<float> spill(compiled.spill_floats());
  compiled.Run({.read_lanes = read_lanes.data(), .write_lanes = write_lanes.data(), .constants = constants.data(),
                .count = count, .literals = nullptr, .spill = spill.data(), .constant_count = constant_count});
  return output_lanes;
}

class JitCompiledLoop : public testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Programs, JitCompiledLoop, testing::ValuesIn(ProgramNames()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST_P(JitCompiledLoop, ComputesExactlyCountVerticesAndNothingPastThem) {
  const Program program = LoadNamed(GetParam());
  ASSERT_FALSE(program.instructions.empty());
  std::mt19937 rng(19);
  const ConstantBank bank = RandomConstants(program, rng);
  const std::vector<float> constants = ConstantTable(bank);
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  std::vector<std::unique_ptr<jit::CompiledProgram>> compiled;
  for (JitIsa isa : jit::SupportedIsas()) {
    std::string why_not;
    compiled.push_back(jit::Compile(program, why_not, isa));
    ASSERT_NE(compiled.back(), nullptr) << kJitIsaNames.Name(isa) << ": " << why_not;
    if (GetParam() == "register_pressure") {
      EXPECT_GT(compiled.back()->spilled_values(), 0) << kJitIsaNames.Name(isa);
    }
  }
  for (const std::size_t count : kCounts) {
    const VertexArrays inputs = RandomInputs(count, rng);
    VertexArrays expected = MakeOutputArrays(count, program);
    ASSERT_EQ(MakeReferenceEngine(program, bank)->Run(inputs, expected).message(), "");
    for (const auto& program_for_isa : compiled) {
      SCOPED_TRACE(testing::Message() << kJitIsaNames.Name(program_for_isa->isa()) << " ("
                                      << program_for_isa->vertices_per_iteration() << " vertices per iteration), "
                                      << count << " vertices");
      const std::vector<Lane> actual = RunCompiled(*program_for_isa, inputs, constants, bank.size());
      for (int slot = 0; slot < kOutputSlotCount; ++slot) {
        for (int c = 0; c < 4; ++c) {
          const FloatsBeforeGuardPage& lane_floats = *actual[static_cast<std::size_t>(4 * slot + c)];
          const float* lane = lane_floats.data();
          const std::string name = OutputSlotName(slot) + "." + "xyzw"[c];
          for (std::size_t i = count; i < lane_floats.size(); ++i) {
            ASSERT_EQ(Bits(lane[i]), kSentinelBits) << name << " written at vertex " << i << ", past the end";
          }
          if (!written[slot].has(c)) {
            for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(Bits(lane[i]), kSentinelBits) << name << " " << i;
            continue;
          }
          const float* reference = std::as_const(expected).lane(slot, c);
          for (std::size_t i = 0; i < count; ++i) {
            ASSERT_EQ(Bits(lane[i]), Bits(reference[i])) << name << " of vertex " << i;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace vs11

namespace vs11 {
namespace {

// Relative reads take one broadcast load where every vertex of a vector reads the same row and a
// gather where they differ (vm/engines/jit_compiler.cc EmitGather): both paths, and vectors that
// differ in one lane only, in the first or the last, or read outside the bank, give the reference
// engine's bits.
TEST(JitCompiler, RelativeReadsMatchTheReferenceWhetherTheRowIsSharedOrNot) {
  const Program program = AssembleOrFail(
      "vs_1_1\ndcl_position v0\ndcl_blendindices v1\n"
      "mov a0.x, v1.x\nm4x3 r0.xyz, v0, c[a0.x + 6]\nmov r0.w, c[a0.x + 7].w\n"
      "mov a0.x, v1.y\nadd oD0, v0, c[a0.x + 2]\nmov oPos, r0\n",
      "relative_rows");
  std::mt19937 rng(23);
  const ConstantBank bank = RandomConstants(program, rng);
  const std::vector<float> constants = ConstantTable(bank);
  constexpr std::size_t kVectors = 16, kVertices = 64 * kVectors;  // whole iterations at every ISA
  VertexArrays inputs = RandomInputs(kVertices, rng);
  float* first_index = inputs.lane(1, 0);
  float* second_index = inputs.lane(1, 1);
  std::uniform_int_distribution<int> bone(0, 20);
  for (std::size_t block = 0; block < kVectors; ++block) {
    // Per block of 64 vertices: one row for all, a row per vertex, or one row but for the first
    // or last vertex of every 8; the second index sometimes outside the bank (row 0 for all).
    const int shared = bone(rng);
    for (std::size_t i = 64 * block; i < 64 * (block + 1); ++i) {
      const std::size_t kind = block % 4, lane = i % 8;
      const bool odd_one = (kind == 2 && lane == 0) || (kind == 3 && lane == 7);
      first_index[i] = static_cast<float>(kind == 1 || odd_one ? bone(rng) : shared);
      second_index[i] = block % 3 == 0 ? 200.0f : static_cast<float>(kind == 1 ? bone(rng) : shared);
    }
  }
  VertexArrays expected = MakeOutputArrays(kVertices, program);
  ASSERT_EQ(MakeReferenceEngine(program, bank)->Run(inputs, expected).message(), "");
  for (const JitIsa isa : jit::SupportedIsas()) {
    std::string why_not;
    const std::unique_ptr<jit::CompiledProgram> compiled = jit::Compile(program, why_not, isa);
    ASSERT_NE(compiled, nullptr) << why_not;
    const std::vector<Lane> actual = RunCompiled(*compiled, inputs, constants, bank.size());
    for (const int slot : {static_cast<int>(OutputSlot::kPosition), static_cast<int>(OutputSlot::kDiffuse)}) {
      for (int c = 0; c < 4; ++c) {
        const float* lane = actual[static_cast<std::size_t>(4 * slot + c)]->data();
        const float* reference = std::as_const(expected).lane(slot, c);
        for (std::size_t i = 0; i < kVertices; ++i) {
          ASSERT_EQ(Bits(lane[i]), Bits(reference[i]))
              << kJitIsaNames.Name(isa) << " " << OutputSlotName(slot) << "." << "xyzw"[c] << " of vertex " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace vs11
