// A divergent branch: one vs_2_x program with if_comp/else, 65 536 vertices, on ref, batch and jit.
// BM_DynamicFlow/<engine>/alternating: neighbouring vertices take opposite sides (every SIMD group
// diverges); /one_side: every vertex takes the if side. The ref engine runs only the side a vertex
// takes; batch and jit run both sides under execution masks (vm/core/static_flow.h), so they cost the
// same either way and the ratio shows what divergence costs the ref engine. items_per_second =
// vertices per second.
#include <cstddef>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "vm/asm/assembler.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"

namespace vs11::bench {
namespace {

constexpr int kVertices = 65536;

constexpr const char* kDivergentProgram =
    "vs_2_x\n"
    "dcl_position v0\n"
    "dcl_normal v1\n"
    "if_gt v0.x, c0.x\n"
    "  m4x4 r0, v0, c4\n"
    "  mad r0, r0, c1, v1\n"
    "  dp3 r1.x, v1, c2\n"
    "  mul r0.xyz, r0, r1.x\n"
    "else\n"
    "  m4x4 r0, v1, c8\n"
    "  add r0, r0, -v0\n"
    "  dp4 r1.x, v0, c3\n"
    "  max r0.xyz, r0, r1.x\n"
    "endif\n"
    "mov oPos, r0\n"
    "mov oD0, r1.x\n";

Program DivergentProgram() {
  const AssembleResult assembled = AssembleSource(kDivergentProgram, "divergent.vsh", {},
                                                  [](const std::filesystem::path&) { return std::optional<std::string>(); });
  if (!assembled.program) std::abort();
  return *assembled.program;
}

void DynamicFlow(benchmark::State& state, const std::string& engine_name, bool alternating) {
  const Program program = DivergentProgram();
  ConstantBank constants(256);
  for (int k = 0; k < constants.size(); ++k) constants[k] = {0.25f * static_cast<float>(k % 7), 0.5f, -0.75f, 1.0f};
  constants[0] = {0, 0, 0, 0};  // the if side where v0.x > 0
  const std::vector<int> registers = {0, 1};
  VertexArrays inputs = MakeInputArrays(kVertices, registers);
  for (std::size_t i = 0; i < kVertices; ++i) {
    const bool if_side = !alternating || i % 2 == 0;
    inputs.lane(0, 0)[i] = if_side ? 1.0f + static_cast<float>(i % 5) : -1.0f - static_cast<float>(i % 3);
    for (int c = 1; c < 4; ++c) inputs.lane(0, c)[i] = 0.125f * static_cast<float>((i + c) % 9);
    for (int c = 0; c < 4; ++c) inputs.lane(1, c)[i] = 0.25f * static_cast<float>((i * 3 + c) % 11) - 1.0f;
  }
  VertexArrays outputs = MakeOutputArrays(kVertices, program);
  Result<std::unique_ptr<Engine>> engine = MakeEngine(engine_name, program, constants, {});
  if (!engine) {
    state.SkipWithError(engine.message().c_str());
    return;
  }
  for (auto _ : state) {
    if (const Status ran = (*engine)->Run(inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(outputs.lane(0, 0));
  }
  state.SetItemsProcessed(state.iterations() * kVertices);
}

const bool kRegistered = [] {
  for (const char* engine : {"ref", "batch", "jit"}) {
    for (const bool alternating : {true, false}) {
      const std::string name = std::string("BM_DynamicFlow/") + engine + (alternating ? "/alternating" : "/one_side");
      benchmark::RegisterBenchmark(name.c_str(), [engine, alternating](benchmark::State& state) {
        DynamicFlow(state, engine, alternating);
      })->Unit(benchmark::kMicrosecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace vs11::bench
