// libFuzzer target: arbitrary bytes as .vsh source; whatever assembles and validates is translated for
// every target, and glslang must compile and link the GLSL (SPIRV-Tools must accept the SPIR-V):
// translation never fails on a valid program. Seeds: programs/*.vsh (fuzz_assembler's).
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "vm/asm/assembler.h"
#include "vm/translate/glslang_compiler.h"
#include "vm/translate/translate.h"

namespace {

// Reads nothing from disk: an #include of the input's neighbours is not what this target explores.
std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

[[noreturn]] void Report(std::string_view what, const std::string& detail, const std::string& glsl) {
  std::fprintf(stderr, "fuzz_translate: %.*s\n%s\n%s\n", static_cast<int>(what.size()), what.data(), detail.c_str(), glsl.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vs11::AssembleOptions options;
  options.require_position = false;  // fragments translate too
  const vs11::AssembleResult assembled =
      vs11::AssembleSource({reinterpret_cast<const char*>(data), size}, "input.vsh", options, NoFiles);
  if (!assembled.program) return 0;
  using vs11::translate::Stage;
  using vs11::translate::Target;
  for (Stage stage : {Stage::kVertex, Stage::kCompute}) {
    for (Target target : {Target::kGlsl330, Target::kGlslEs300, Target::kGlslEs310, Target::kGlslEs320, Target::kSpirv}) {
      if (!vs11::translate::StageProblem(target, stage).ok()) continue;
      vs11::translate::TranslateOptions translate_options;
      translate_options.target = target;
      translate_options.stage = stage;
      const std::string glsl = vs11::translate::TranslateToGlsl(*assembled.program, translate_options);
      const auto compiled = vs11::translate::CompileWithGlslang(glsl, target, stage);
      if (!compiled) Report(vs11::translate::TargetName(target), compiled.message(), glsl);
      if (target != Target::kSpirv) continue;
      if (const vs11::Status valid = vs11::translate::ValidateSpirv(*compiled); !valid.ok()) {
        Report("spirv-val", valid.message(), glsl);
      }
    }
  }
  return 0;
}
