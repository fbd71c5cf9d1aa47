// The engine registry: engines are found by name, listed for --help and errors from one place, and
// one registration adds an engine (vm/engines/engine_factory.h).
#include "vm/engines/engine_factory.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/engines/jit_options.h"

namespace vs11 {
namespace {

Program FogProgram() {
  AssembleResult assembled = AssembleSource("vs.1.1\ndp4 oPos.x, v0, c0\nmov oFog.x, v0.x\n", "fog.vsh", {});
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  return *assembled.program;
}

std::vector<std::string> Names() {
  std::vector<std::string> names;
  for (const EngineInfo& engine : RegisteredEngines()) names.emplace_back(engine.name);
  return names;
}

// A stand-in for an engine of another library: the reference engine under another name.
Result<std::unique_ptr<Engine>> MakeTestEngine(const Program& program, const ConstantBank& api_constants,
                                               const EngineOptions& options) {
  return MakeEngine("ref", program, api_constants, options);
}

TEST(EngineRegistry, ListsTheEnginesOfThisFolderFirstInOrder) {
  const std::vector<std::string> names = Names();
  ASSERT_GE(names.size(), 3u);
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 3), (std::vector<std::string>{"ref", "batch", "jit"}));
  EXPECT_TRUE(EngineNameList().starts_with("ref, batch"));
  // "..., jit (...)" or "... or jit (...)": the gl engine may be registered by an earlier test.
  EXPECT_TRUE(EngineDescriptions().starts_with("ref (scalar reference), batch (SIMD kernels)"));
  EXPECT_NE(EngineDescriptions().find("jit (the program compiled to AVX-512 or AVX2 code"), std::string::npos);
}

TEST(EngineRegistry, FindsAnEngineByNameOrAliasOnly) {
  ASSERT_TRUE(FindEngine("reference"));
  EXPECT_EQ(FindEngine("reference")->name, "ref");
  EXPECT_EQ(FindEngine("jit")->name, "jit");
  EXPECT_FALSE(FindEngine("JIT"));
  EXPECT_FALSE(FindEngine(""));
  EXPECT_FALSE(FindEngine("warp"));
  const std::vector<std::string> spellings = EngineSpellings();
  EXPECT_NE(std::find(spellings.begin(), spellings.end(), "reference"), spellings.end());
}

TEST(EngineRegistry, OneRegistrationAddsAnEngineToEveryList) {
  RegisterEngine({"test_engine", "", "a test's engine", &MakeTestEngine});
  EXPECT_EQ(Names().back(), "test_engine");
  EXPECT_TRUE(EngineNameList("'").ends_with(" or 'test_engine'")) << EngineNameList("'");
  EXPECT_TRUE(EngineDescriptions().ends_with(" or test_engine (a test's engine)"));
  const Program program = FogProgram();
  VertexArrays inputs = MakeInputArrays(2, std::vector<int>{0});
  inputs.lane(0, 0)[1] = 3.0f;
  VertexArrays outputs = MakeOutputArrays(2, program);
  Result<std::unique_ptr<Engine>> made = MakeEngine("test_engine", program, ConstantBank());
  ASSERT_TRUE(made.ok()) << made.message();
  std::unique_ptr<Engine> engine = std::move(made).value();
  ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
  EXPECT_EQ(outputs.lane(static_cast<int>(OutputSlot::kFog), 0)[1], 3.0f);

  RegisterEngine({"test_engine", "", "replaced", &MakeTestEngine});
  const std::vector<std::string> names = Names();
  EXPECT_EQ(std::count(names.begin(), names.end(), "test_engine"), 1);
  EXPECT_EQ(FindEngine("test_engine")->summary, "replaced");
  UnregisterEngine("test_engine");
  EXPECT_FALSE(FindEngine("test_engine"));
}

TEST(EngineRegistry, AnUnknownNameGivesAnErrorThatSaysWhichThereAre) {
  const Program program = FogProgram();
  const Result<std::unique_ptr<Engine>> engine = MakeEngine("warp", program, ConstantBank());
  ASSERT_FALSE(engine.ok());
  EXPECT_EQ(engine.error().code, DiagnosticCode::kEngineUnavailable);
  EXPECT_NE(engine.message().find("the warp engine is not part of this program (it has ref, batch"), std::string::npos)
      << engine.message();
}

TEST(EngineSettings, CarryEachEnginesOwnOptionsByType) {
  EngineOptions options;
  EXPECT_EQ(options.settings.Get<JitOptions>().isa, JitIsa::kBest);
  options = WithJitIsa(options, JitIsa::kAvx2);
  EXPECT_EQ(options.settings.Get<JitOptions>().isa, JitIsa::kAvx2);
  const EngineOptions copy = options;
  EXPECT_EQ(copy.settings.Get<JitOptions>().isa, JitIsa::kAvx2);
}

}  // namespace
}  // namespace vs11
