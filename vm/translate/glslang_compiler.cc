#include "vm/translate/glslang_compiler.h"

#include <mutex>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>

namespace vs11::translate {
namespace {

// glslang keeps process-wide tables that InitializeProcess builds once; it is never finalised, since
// another thread may be compiling.
void InitializeGlslangOnce() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

constexpr int kDefaultGlslVersion = 100;  // used only by a text without #version, which we never write

// Vulkan 1.0 and SPIR-V 1.0, for a shader in `source` (GLSL or HLSL).
void SetVulkanEnvironment(glslang::TShader& shader, glslang::EShSource source, EShLanguage language = EShLangVertex) {
  shader.setEnvInput(source, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
}

// glslang's messages about a shader it refused.
Diagnostic Refused(std::string log) { return Failure(DiagnosticCode::kGlCompile, std::move(log)); }

// Parses `shader` and links it, alone, into `program`; where either fails, glslang's messages.
Status ParseAndLink(glslang::TShader& shader, EShMessages messages, glslang::TProgram& program) {
  if (!shader.parse(GetDefaultResources(), kDefaultGlslVersion, false, messages)) {
    return Refused(std::string(shader.getInfoLog()) + shader.getInfoDebugLog());
  }
  program.addShader(&shader);
  if (!program.link(messages)) return Refused(std::string(program.getInfoLog()) + program.getInfoDebugLog());
  return {};
}

}  // namespace

Result<std::vector<std::uint32_t>> CompileWithGlslang(const std::string& glsl, Target target, Stage stage) {
  InitializeGlslangOnce();
  const EShLanguage language = stage == Stage::kCompute ? EShLangCompute : EShLangVertex;
  glslang::TShader shader(language);
  const char* text = glsl.c_str();
  const char* name = "translation";
  shader.setStringsWithLengthsAndNames(&text, nullptr, &name, 1);
  auto messages = static_cast<EShMessages>(EShMsgDefault);
  if (target == Target::kSpirv) {
    SetVulkanEnvironment(shader, glslang::EShSourceGlsl, language);
    // Debug info keeps the source (with its interface comment) and the variables' names in the binary.
    messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgDebugInfo);
  }
  glslang::TProgram program;
  if (Status linked = ParseAndLink(shader, messages, program); !linked) return linked.error();
  std::vector<std::uint32_t> spirv;
  if (target == Target::kSpirv) {
    glslang::SpvOptions options;
    options.generateDebugInfo = true;
    options.validate = false;  // ValidateSpirv does it, with SPIRV-Tools' own messages
    spv::SpvBuildLogger logger;
    glslang::GlslangToSpv(*program.getIntermediate(language), spirv, &logger, &options);
    if (spirv.empty()) return Refused(logger.getAllMessages());
  }
  return spirv;
}

Status CompileHlslWithGlslang(const std::string& hlsl, const std::string& entry_point) {
  InitializeGlslangOnce();
  glslang::TShader shader(EShLangVertex);
  const char* text = hlsl.c_str();
  const char* name = "hlsl";
  shader.setStringsWithLengthsAndNames(&text, nullptr, &name, 1);
  shader.setEntryPoint(entry_point.c_str());
  SetVulkanEnvironment(shader, glslang::EShSourceHlsl);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl);
  glslang::TProgram program;
  return ParseAndLink(shader, messages, program);
}

Status ValidateSpirv(const std::vector<std::uint32_t>& words) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
  std::string messages;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
    messages += "word " + std::to_string(position.index) + ": " + message + "\n";
  });
  if (tools.Validate(words)) return {};
  return Failure(DiagnosticCode::kInvalidSpirv, messages.empty() ? std::string("invalid SPIR-V") : messages);
}

}  // namespace vs11::translate
