// The C library's ProcessVertices (include/vs11/vs11_c.h) against the engine alone: a D3D9 vs_1_1
// program with five inputs in two interleaved streams of packed types (FLOAT3 and SHORT4N; D3DCOLOR,
// FLOAT16_2 and UBYTE4N) written as a declaration (POSITIONT with a viewport, D3DCOLOR, float4,
// float2). BM_ProcessVertices/<engine> is the whole call; BM_ProcessVerticesEngineOnly/<engine> runs
// the same program on already-decoded float arrays, so the difference is what reading and writing
// D3D's vertex formats costs. items_per_second = vertices per second, 65 536 vertices.
#include <cstring>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <vs11/vs11_c.h>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/engines/engine_factory.h"

namespace vs11::bench {
namespace {

constexpr std::size_t kVertices = 65536;
constexpr const char* kSource = R"(vs_1_1
dcl_position v0
dcl_normal v1
dcl_color v2
dcl_texcoord0 v3
dcl_blendweight v4
m4x4 oPos, v0, c0
dp3 r0.x, v1, c4
max r0.x, r0.x, c5.x
mul oD0, v2, r0.x
mov oD1, v4
mov oT0, v3
)";
constexpr float kConstants[] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 0, 0.25f, 0, 0, 0};
constexpr vs11c_vertex_element kInput[] = {{0, 0, 2, 0, 0, 0}, {0, 12, 10, 0, 3, 0}, {1, 0, 4, 0, 10, 0},
                                           {1, 4, 15, 0, 5, 0}, {1, 8, 8, 0, 1, 0}, VS11C_DECL_END};
constexpr vs11c_vertex_element kOutput[] = {{0, 0, 3, 0, 9, 0}, {0, 16, 4, 0, 10, 0}, {0, 20, 3, 0, 10, 1},
                                            {0, 36, 1, 0, 5, 0}, VS11C_DECL_END};
constexpr std::size_t kStride0 = 20, kStride1 = 12, kOutputStride = 44;

Program Assembled() {
  AssembleResult assembled = AssembleSource(kSource, "process_vertices_bench.vsh", {});
  if (!assembled.program) std::abort();
  return *assembled.program;
}

void BM_ProcessVertices(benchmark::State& state, const char* engine) {
  const std::vector<std::uint32_t> tokens = Encode(Assembled());
  std::vector<std::uint8_t> stream0(kVertices * kStride0), stream1(kVertices * kStride1), output(kVertices * kOutputStride);
  for (std::size_t i = 0; i < stream0.size(); ++i) stream0[i] = static_cast<std::uint8_t>(i * 7);
  for (std::size_t i = 0; i < stream1.size(); ++i) stream1[i] = static_cast<std::uint8_t>(i * 13);
  for (std::size_t i = 0; i < kVertices; ++i) {
    const float position[3] = {static_cast<float>(i) * 0.001f, 1.0f, 0.5f};
    std::memcpy(stream0.data() + i * kStride0, position, sizeof position);
  }
  vs11c_shader* shader = nullptr;
  if (vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &shader) != VS11C_OK) std::abort();
  vs11c_shader_set_constants(shader, 0, kConstants, 6);
  vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_D3D9);
  const vs11c_stream streams[] = {{stream0.data(), kStride0}, {stream1.data(), kStride1}};
  const vs11c_viewport viewport{0, 0, 640, 480, 0, 1};
  const vs11c_output layout{output.data(), kOutputStride, 0, kOutput, &viewport};
  for (auto _ : state) {
    if (vs11c_process_vertices(shader, kInput, streams, 2, kVertices, &layout) != VS11C_OK) std::abort();
    benchmark::DoNotOptimize(output.data());
  }
  vs11c_shader_destroy(shader);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kVertices));
}

void BM_ProcessVerticesEngineOnly(benchmark::State& state, const char* engine) {
  const Program program = Assembled();
  ConstantBank constants;
  for (int r = 0; r < 6; ++r) std::memcpy(constants[r].data(), kConstants + 4 * r, sizeof(Vec4f));
  const int registers[] = {0, 1, 2, 3, 4};
  VertexArrays inputs = MakeInputArrays(kVertices, registers);
  for (int reg : registers) {
    for (int c = 0; c < 4; ++c) std::fill_n(inputs.lane(reg, c), kVertices, 0.25f * static_cast<float>(c + reg));
  }
  VertexArrays outputs = MakeOutputArrays(kVertices, program);
  Result<std::unique_ptr<Engine>> made = MakeEngine(engine, program, constants);
  if (!made) {
    state.SkipWithError(made.message().c_str());
    return;
  }
  const std::unique_ptr<Engine> run = std::move(made).value();
  for (auto _ : state) {
    if (const Status ran = run->Run(inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
    benchmark::DoNotOptimize(outputs.view(0, 0).base);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kVertices));
}

BENCHMARK_CAPTURE(BM_ProcessVertices, ref, "ref");
BENCHMARK_CAPTURE(BM_ProcessVertices, batch, "batch");
BENCHMARK_CAPTURE(BM_ProcessVertices, jit, "jit");
BENCHMARK_CAPTURE(BM_ProcessVerticesEngineOnly, batch, "batch");
BENCHMARK_CAPTURE(BM_ProcessVerticesEngineOnly, jit, "jit");

}  // namespace
}  // namespace vs11::bench
