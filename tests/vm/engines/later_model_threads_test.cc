// A later model's program on batch and jit split over threads (EngineOptions::threads): a loop over
// c#[aL] that each vertex leaves at its own iteration (break_gt on its input) and a call from the loop
// body. At 1, 2 and 8 threads both give the reference engine's bits. CI's ThreadSanitizer stage (.ci/tsan)
// runs this file (VS11_TSAN_TEST_FILES in tests/CMakeLists.txt).
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/engines/later_model_comparison.h"
#include "vm/core/static_flow.h"
#include "vm/engines/batch_engine.h"

namespace vs11 {
namespace {

constexpr const char* kProgram =
    "vs_2_x\n"
    "defi i0, 6, 0, 1, 0\n"
    "def c0, 0.25, 1, 0, 0\n"
    "dcl_position v0\n"
    "dcl_normal v1\n"
    "mov r0, v0\n"
    "mov r1, c0.z\n"
    "loop aL, i0\n"
    "add r1, r1, c10[aL]\n"
    "break_gt r1.x, v0.x\n"  // each vertex leaves at its own iteration
    "call l0\n"
    "endloop\n"
    "mov oPos, r0\n"
    "mov oD0, r1\n"
    "ret\n"
    "label l0\n"
    "mad r0, r0, v1, c0.x\n"
    "ret\n";

TEST(LaterModelThreads, BatchAndJitAtOneTwoAndEightThreadsGiveTheReferencesBits) {
  const Program program = later_model::Assemble(kProgram);
  ConstantBank bank(256);
  for (int k = 0; k < 6; ++k) bank[10 + k] = {0.375f * static_cast<float>(k + 1), 0.5f, -0.25f, 1.0f};
  // Enough vertices that 8 threads each get a piece of the specialised program.
  const Result<Program> straight = SpecialiseStaticFlow(program, StaticFlowKeyOf(ModelConstants(program, bank)), "batch");
  ASSERT_TRUE(straight.ok()) << straight.message();
  const std::size_t piece = MinVerticesPerPiece(*straight);
  ASSERT_NE(piece, kNeverSplit) << "the specialised program should be worth splitting";
  const std::size_t count = 16 * piece + 37;
  RecordProperty("vertices", static_cast<int>(count));
  std::mt19937 random(33);
  std::uniform_real_distribution<float> value(-1.0f, 4.0f);
  const VertexArrays inputs = later_model::RandomInputs(count, [&] { return value(random); });

  const VertexArrays reference = later_model::RunOn("ref", program, bank, inputs, {});
  for (const char* engine : {"batch", "jit"}) {
    for (int threads : {1, 2, 8}) {
      EngineOptions options;
      options.threads = threads;
      EXPECT_EQ(later_model::Difference(reference, later_model::RunOn(engine, program, bank, inputs, options)), "")
          << engine << " at " << threads << " threads, " << count << " vertices";
    }
  }
}

}  // namespace
}  // namespace vs11
