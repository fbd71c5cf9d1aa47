// Hostile programs that once took minutes (issue #30, §6), as rows whose time must grow linearly:
// BM_PreprocessChainedDefines/N preprocesses N #defines, each naming the one before, then a line
// using the last (the macro bound lifted, so all N are defined; the use stops at kMaxMacroNesting);
// BM_ReferenceEngineDefinitions/N runs a program of N defs and one add over 4096 vertices on the
// reference engine, which must not pay for the defs per vertex.

#include <limits>
#include <string>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "vm/asm/assembler.h"
#include "vm/asm/preprocessor.h"
#include "vm/engines/engine_factory.h"

namespace vs11::bench {
namespace {

constexpr std::size_t kVertices = 4096;

void BM_PreprocessChainedDefines(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  std::string text = "#define A0 v0\n";
  for (int i = 1; i < count; ++i) text += fmt::format("#define A{} A{}\n", i, i - 1);
  text += fmt::format("mov oPos, A{}\n", count - 1);
  PreprocessOptions options;
  options.max_macros = std::numeric_limits<std::size_t>::max();
  for (auto _ : state) benchmark::DoNotOptimize(Preprocess(text, "chain.vsh", options));
  state.SetItemsProcessed(state.iterations() * count);
}
BENCHMARK(BM_PreprocessChainedDefines)->Arg(50000)->Arg(100000)->Arg(400000)->Unit(benchmark::kMillisecond);

void BM_ReferenceEngineDefinitions(benchmark::State& state) {
  std::string text = "vs.1.1\n";
  for (int i = 0; i < state.range(0); ++i) text += fmt::format("def c{}, {}, 0, 0, 1\n", i % 96, i);
  text += "add oPos, v0, c0\n";
  AssembleOptions options;
  options.validate = false;  // the validator refuses more defs than registers
  const AssembleResult assembled = AssembleSource(text, "defs.vsh", options);
  const std::vector<int> registers = {0};
  const VertexArrays inputs = MakeInputArrays(kVertices, registers);
  VertexArrays outputs = MakeOutputArrays(kVertices, *assembled.program);
  const auto engine = MakeEngine("ref", *assembled.program, ConstantBank()).value();
  for (auto _ : state) {
    if (const Status ran = engine->Run(inputs, outputs); !ran) {
      state.SkipWithError(ran.message().c_str());
      break;
    }
  }
  state.SetItemsProcessed(state.iterations() * kVertices);
}
BENCHMARK(BM_ReferenceEngineDefinitions)->Arg(16)->Arg(16384)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vs11::bench
