// Not a test that runs by default: writes what the back ends make of every program in programs/ and of
// 300 random programs (the jit's machine code at AVX2 and AVX-512, the translator's GLSL and SPIR-V,
// both float rules), one file per case, into $VS11_BACKEND_DUMP. tests/vm/ir/compare_backend_outputs.sh
// runs it on two builds and compares the files byte for byte: how a change to the IR (vm/ir/) or a
// back end is shown to leave their output unchanged. Machine code is pinned by that comparison, not by
// a test here, which every deliberate change of the code generator would break.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"
#include "vm/asm/assembler.h"
#include "vm/engines/jit_compiler.h"
#include "vm/translate/translate.h"

namespace vs11 {
namespace {

void WriteFile(const std::filesystem::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void Dump(const std::filesystem::path& dir, const std::string& name, const Program& program) {
  for (const FloatRules rules : {FloatRules::kD3d9, FloatRules::kLegacy}) {
    const std::string rule_name = rules == FloatRules::kLegacy ? "legacy" : "d3d9";
    for (const JitIsa isa : jit::SupportedIsas()) {
      // With and without uniform inputs (v0.w and v1.x compiled in as literals).
      const std::vector<jit::UniformInput> uniforms = {{0, 3, 2.0f}, {1, 0, -0.5f}};
      for (const bool uniform : {false, true}) {
        std::string why_not;
        const auto compiled = jit::Compile(program, why_not, isa, uniform ? uniforms : std::vector<jit::UniformInput>{},
                                           rules);
        ASSERT_NE(compiled, nullptr) << why_not;
        const std::span<const std::uint8_t> code = compiled->code();
        WriteFile(dir / ("jit_" + name + "_" + std::string(kJitIsaNames.Name(isa)) + "_" + rule_name +
                         (uniform ? "_uniform" : "") + ".bin"),
                  code.data(), code.size());
      }
    }
    for (const translate::Target target : {translate::Target::kGlsl330, translate::Target::kGlslEs300,
                                           translate::Target::kGlslEs320, translate::Target::kSpirv}) {
      for (const bool exact : {false, true}) {
        if (exact && target == translate::Target::kSpirv) continue;  // the gl engine's form: GLSL only
        translate::TranslateOptions options;
        options.target = target;
        options.float_rules = rules;
        options.exact_on_driver = exact;
        options.source_name = name;
        options.constant_count = name.starts_with("random") ? 256 : kDefaultConstantCount;
        const Result<translate::Artifact> artifact = translate::Translate(program, options);
        ASSERT_TRUE(artifact.ok()) << artifact.message();
        WriteFile(dir / ("translate_" + name + "_" + std::string(translate::TargetName(target)) + "_" + rule_name +
                         (exact ? "_exact" : "") + ".out"),
                  artifact->bytes.data(), artifact->bytes.size());
      }
    }
  }
}

TEST(BackendOutputDump, DISABLED_EveryProgramAndRandomOnes) {
  const char* dir_text = std::getenv("VS11_BACKEND_DUMP");
  ASSERT_NE(dir_text, nullptr) << "set VS11_BACKEND_DUMP to the directory to write into";
  const std::filesystem::path dir(dir_text);
  std::filesystem::create_directories(dir);
  for (const auto& entry : std::filesystem::directory_iterator(VS11_SOURCE_DIR "/programs")) {
    if (entry.path().extension() != ".vsh") continue;
    AssembleOptions options;
    options.require_position = false;  // the irradiance programs write colours only
    const AssembleResult result = AssembleFile(entry.path(), options);
    ASSERT_TRUE(result.program.has_value()) << entry.path() << result.diagnostics.ToString();
    Dump(dir, entry.path().stem().string(), *result.program);
  }
  random_program::ProgramGenerator generator(20240611);
  for (int k = 0; k < 300; ++k) Dump(dir, "random" + std::to_string(k), generator.MakeProgram());
}

}  // namespace
}  // namespace vs11
