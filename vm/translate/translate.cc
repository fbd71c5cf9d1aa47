// The GLSL writer every target shares: the recorded program (shader_graph.h) as one scalar statement
// per operation, the interface around it, and the dialect's parts from the target's Profile.
#include "vm/translate/translate.h"

#include <bit>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "vm/asm/disassembler.h"
#include "vm/translate/compute_stage.h"
#include "vm/translate/shader_graph.h"

namespace vs11::translate {
namespace {

// Output locations, in the order of the interface comment: vs11_oPos, oD0, oD1, oT0..oT7, oFog, oPts.
struct OutputDeclaration {
  int slot;
  std::string name;
  bool scalar;  // oFog, oPts: lane x only
  int location;
};

std::vector<OutputDeclaration> OutputVariables() {
  std::vector<OutputDeclaration> variables = {{static_cast<int>(OutputSlot::kPosition), "vs11_oPos", false, 0}};
  int location = 1;
  for (int slot = static_cast<int>(OutputSlot::kDiffuse); slot < kOutputSlotCount; ++slot) {
    variables.push_back({slot, OutputSlotName(slot), false, location++});
  }
  variables.push_back({static_cast<int>(OutputSlot::kFog), "oFog", true, location++});
  variables.push_back({static_cast<int>(OutputSlot::kPointSize), "oPts", true, location++});
  return variables;
}

// Every float literal through its bits, so that the GLSL compiler's decimal parsing cannot change it.
std::string FloatLiteralName(std::uint32_t bits) { return fmt::format("f{:08X}", bits); }
std::string FloatFromBitsText(std::uint32_t bits) { return fmt::format("uintBitsToFloat(0x{:08X}u)", bits); }
std::string IntLiteralText(std::uint32_t bits) {
  const auto value = static_cast<std::int32_t>(bits);
  if (value == std::numeric_limits<std::int32_t>::min()) return "int(0x80000000u)";
  return std::to_string(value);
}
std::string FloatComment(std::uint32_t bits) {
  return fmt::format("{}", std::bit_cast<float>(bits));
}

constexpr std::string_view kLaneSuffix = "xyzw";

// Helpers, emitted when a node needs them. Bit operations rather than abs(), -x and isnan(): GLSL
// does not promise what those do with the sign of a NaN or -0, nor that isnan() sees NaNs at all.
constexpr std::string_view kAbsHelper =
    "float vs11_abs(float x) { return intBitsToFloat(floatBitsToInt(x) & 0x7FFFFFFF); }\n";
constexpr std::string_view kNegateHelper =
    "float vs11_neg(float x) { return intBitsToFloat(floatBitsToInt(x) ^ int(0x80000000u)); }\n";
constexpr std::string_view kIsNaNHelper =
    "bool vs11_isnan(float x) { return (floatBitsToInt(x) & 0x7FFFFFFF) > 0x7F800000; }\n";

class Writer {
 public:
  Writer(const Program& program, const ShaderGraph& shader, const Profile& profile, const TranslateOptions& options)
      : program_(program), shader_(shader), graph_(shader.graph), profile_(profile), options_(options),
        live_(LiveNodes(shader)) {}

  std::string Write() {
    std::string body = Body();
    // GLSL ES wants #version before anything else, comments included: the interface comes second.
    std::string text = profile_.Header();
    if (Compute()) {
      text += ComputeInterfaceComment({options_.source_name, TargetName(profile_.target()), FloatRulesDescription(),
                                       ComputeContraction(), options_.constant_count});
      text += ComputeDeclarations(options_.constant_count);
    } else {
      text += InterfaceComment();
      text += Declarations();
    }
    text += Helpers();
    text += body;
    return text;
  }

 private:
  std::string Ref(int id) const {
    const ir::Node& node = graph_[id];
    switch (node.op) {
      case ir::Op::kLiteral:
        return node.type == ir::Type::kFloat ? FloatLiteralName(node.immediate) : IntLiteralText(node.immediate);
      case ir::Op::kInput: return fmt::format("v{}.{}", node.immediate / 4, kLaneSuffix[node.immediate % 4]);
      case ir::Op::kConstant: return fmt::format("c[{}].{}", node.immediate / 4, kLaneSuffix[node.immediate % 4]);
      case ir::Op::kComponent: return fmt::format("{}.{}", Ref(node.args[0]), kLaneSuffix[node.immediate]);
      default: return fmt::format("t{}", id);
    }
  }

  std::string Expression(const ir::Node& node) {
    auto arg = [&](int i) { return Ref(node.args[static_cast<std::size_t>(i)]); };
    switch (node.op) {
      case ir::Op::kRelativeRow: return fmt::format("vs11_c_rel({})", arg(0));
      case ir::Op::kAdd: case ir::Op::kIntAdd: return arg(0) + " + " + arg(1);
      case ir::Op::kSub: case ir::Op::kIntSub: return arg(0) + " - " + arg(1);
      case ir::Op::kMul: return arg(0) + " * " + arg(1);
      case ir::Op::kDiv: return arg(0) + " / " + arg(1);
      case ir::Op::kFloor: return fmt::format("floor({})", arg(0));
      case ir::Op::kSqrt: return fmt::format("sqrt({})", arg(0));
      case ir::Op::kAbs: uses_abs_ = true; return fmt::format("vs11_abs({})", arg(0));
      case ir::Op::kNegate: uses_negate_ = true; return fmt::format("vs11_neg({})", arg(0));
      case ir::Op::kUnordered:  // IsNaN(x) records x unordered with itself
        uses_isnan_ = true;
        if (node.args[0] == node.args[1]) return fmt::format("vs11_isnan({})", arg(0));
        return fmt::format("vs11_isnan({}) || vs11_isnan({})", arg(0), arg(1));
      case ir::Op::kLess: return arg(0) + " < " + arg(1);
      case ir::Op::kGreater: case ir::Op::kIntGreater: return arg(0) + " > " + arg(1);
      case ir::Op::kGreaterEqual: return arg(0) + " >= " + arg(1);
      case ir::Op::kEqual: return arg(0) + " == " + arg(1);
      case ir::Op::kSelect: return fmt::format("{} ? {} : {}", arg(0), SelectOperand(node, 1), SelectOperand(node, 2));
      case ir::Op::kBitsOf: return fmt::format("floatBitsToInt({})", arg(0));
      case ir::Op::kFloatFromBits: return fmt::format("intBitsToFloat({})", arg(0));
      case ir::Op::kToInt: return fmt::format("int({})", arg(0));
      case ir::Op::kToFloat: return fmt::format("float({})", arg(0));
      case ir::Op::kIntAnd: return arg(0) + " & " + arg(1);
      case ir::Op::kIntOr: return arg(0) + " | " + arg(1);
      case ir::Op::kShiftLeft: return fmt::format("{} << {}", arg(0), node.immediate);
      case ir::Op::kShiftRight: return fmt::format("{} >> {}", arg(0), node.immediate);
      default: return Ref(static_cast<int>(&node - graph_.nodes().data()));
    }
  }

  static bool IsInline(ir::Op op) {
    return op == ir::Op::kLiteral || op == ir::Op::kInput || op == ir::Op::kConstant || op == ir::Op::kComponent;
  }

  static std::string_view TypeName(ir::Type type) {
    switch (type) {
      case ir::Type::kFloat: return "float";
      case ir::Type::kInt: return "int";
      case ir::Type::kMask: return "bool";
      case ir::Type::kVec4: return "vec4";
    }
    return "float";
  }

  // main(): the float literals, then each instruction's statements under its text, then the outputs.
  std::string Body() {
    std::string text = "void main() {\n";
    if (Compute()) text += ComputePrologue(shader_.inputs_read, InputUsages());
    for (std::size_t n = 0; n < graph_.size(); ++n) {
      const ir::Node& node = graph_.nodes()[n];
      if (live_[n] && node.op == ir::Op::kLiteral && node.type == ir::Type::kFloat) {
        text += fmt::format("  float {} = {};  // {}\n", FloatLiteralName(node.immediate), LiteralText(node.immediate),
                            FloatComment(node.immediate));
      }
    }
    const Syntax syntax = SyntaxOf(program_);
    std::size_t next = 0;
    for (int i = -1; i < static_cast<int>(program_.instructions.size()); ++i) {
      if (i >= 0 && program_.instructions[static_cast<std::size_t>(i)].info().is_executable()) {
        text += fmt::format("  // {}\n", FormatInstruction(program_.instructions[static_cast<std::size_t>(i)], syntax));
      }
      for (; next < graph_.size() && graph_.nodes()[next].instruction == i; ++next) {
        const ir::Node& node = graph_.nodes()[next];
        if (!live_[next] || IsInline(node.op)) continue;
        if (node.op == ir::Op::kRelativeRow) uses_relative_ = true;
        text += fmt::format("  {} t{} = {};\n", TypeName(node.type), next, Expression(node));
      }
    }
    text += "  // outputs (unwritten lanes hold vs11's values)\n";
    if (Compute()) return text + ComputeOutputs() + "}\n";
    for (const OutputDeclaration& output : OutputVariables()) {
      const auto& lanes = shader_.outputs[static_cast<std::size_t>(output.slot)];
      if (Scalar(output)) {
        text += fmt::format("  {} = {};\n", output.name, Ref(lanes[0]));
      } else {
        text += fmt::format("  {} = vec4({}, {}, {}, {});\n", output.name, Ref(lanes[0]), Ref(lanes[1]), Ref(lanes[2]),
                            Ref(lanes[3]));
      }
    }
    text += "  gl_Position = " + ClipConversion() + ";\n";
    if (shader_.written[static_cast<int>(OutputSlot::kPointSize)].bits() != 0) {
      text += options_.exact_on_driver ? "  gl_PointSize = oPts.x;\n" : "  gl_PointSize = oPts;\n";
    }
    text += "}\n";
    return text;
  }

  bool Compute() const { return options_.stage == Stage::kCompute; }

  // Each output register the program writes, all four lanes, into a local vec4 (`precise` where the
  // dialect has it, which reaches every operation the value depends on, as the vertex stage's
  // outputs) and then to the output buffer.
  std::string ComputeOutputs() const {
    std::string text;
    for (const OutputDeclaration& output : OutputVariables()) {
      if (shader_.written[static_cast<std::size_t>(output.slot)].bits() == 0) continue;
      const auto& lanes = shader_.outputs[static_cast<std::size_t>(output.slot)];
      text += fmt::format("  {}vec4 {} = vec4({}, {}, {}, {});\n", profile_.HasPrecise() ? "precise " : "", output.name,
                          Ref(lanes[0]), Ref(lanes[1]), Ref(lanes[2]), Ref(lanes[3]));
      text += ComputeStore(output.slot, output.name);
    }
    return text;
  }

  std::string_view ComputeContraction() const {
    if (profile_.HasPrecise()) {
      return "every output's value is a `precise` vec4, which reaches each operation it depends on: no\n"
             "//   driver fuses a product and a sum into one rounding.";
    }
    return profile_.Contraction();
  }

  // oFog and oPts are floats, lane x, but for exact_on_driver (OutputVariableOf).
  bool Scalar(const OutputDeclaration& output) const { return output.scalar && !options_.exact_on_driver; }

  ClipSpace EffectiveClip() const {
    if (options_.clip != ClipSpace::kTargetApi) return options_.clip;
    return profile_.target() == Target::kSpirv ? ClipSpace::kVulkan : ClipSpace::kGl;
  }

  std::string ClipConversion() const {
    switch (EffectiveClip()) {
      case ClipSpace::kGl: return "vec4(vs11_oPos.xy, 2.0 * vs11_oPos.z - vs11_oPos.w, vs11_oPos.w)";
      case ClipSpace::kVulkan: return "vec4(vs11_oPos.x, -vs11_oPos.y, vs11_oPos.zw)";
      default: return "vs11_oPos";
    }
  }

  // A select's operand. Under exact_on_driver, a float the select's own comparison also reads passes
  // through the opaque uniform: Mesa turns `a < b ? a : b` into fmin(a, b), which may return either
  // zero for +0 and -0, where vs11's min returns b (and likewise for max).
  std::string SelectOperand(const ir::Node& node, int i) {
    const int id = node.args[static_cast<std::size_t>(i)];
    const std::string text = Ref(id);
    if (!options_.exact_on_driver || node.type != ir::Type::kFloat) return text;
    const ir::Node& condition = graph_[node.args[0]];
    if (condition.args[0] != id && condition.args[1] != id) return text;
    return fmt::format("uintBitsToFloat(floatBitsToUint({}) ^ vs11_opaque_zero)", text);
  }

  // A float literal with its bits; under exact_on_driver through a uniform the compiler cannot see.
  std::string LiteralText(std::uint32_t bits) const {
    if (!options_.exact_on_driver) return FloatFromBitsText(bits);
    return fmt::format("uintBitsToFloat(0x{:08X}u ^ vs11_opaque_zero)", bits);
  }

  std::string_view ClipDescription() const {
    switch (EffectiveClip()) {
      case ClipSpace::kGl:
        return "GL's clip space: z' = 2z - w (D3D's depth range [0, w] to GL's [-w, w]); x, y, w as written\n"
               "//             (+y is up in both; D3D's viewport puts row 0 at the top, GL's at the bottom)";
      case ClipSpace::kVulkan:
        return "Vulkan's clip space: y' = -y (Vulkan's +y points down the viewport, D3D's up); x, z, w as\n"
               "//             written (both use the depth range [0, w])";
      default: return "D3D's clip space as written (--clip d3d)";
    }
  }

  std::string_view FloatRulesDescription() const {
    if (options_.float_rules == FloatRules::kLegacy) {
      return "legacy (--float-rules legacy): every product of mul, mad, dp3, dp4, the m*x* macros, dst and\n"
             "//   lit's power is (b == 0 ? 0 : a) * (a == 0 ? 0 : b), so 0 * inf and 0 * NaN give 0";
    }
    return "d3d9: IEEE products, 0 * inf and 0 * NaN give NaN (--float-rules legacy makes them 0)";
  }

  std::string InterfaceComment() const {
    std::string text = fmt::format(
        "// vs_1_1 program {} translated by vs11 for {}.\n"
        "// Interface:\n"
        "//   vN        layout(location = N) in vec4 vN; attributes not supplied read (0, 0, 0, 1)\n"
        "//   c0..c{}   the constant bank, vec4 c[{}] (--max-constants); def constants are applied here and win over\n"
        "//             the bank, under relative addressing too; c[a0.x + n] outside the bank reads (0, 0, 0, 0)\n"
        "//   oPos      vs11_oPos (out vec4, the value the program wrote) and gl_Position in\n"
        "//             {}\n"
        "//   oD0 oD1 oT0..oT7  out vec4 of those names; oFog oPts: out float (oPts also to gl_PointSize when written)\n"
        "//   unwritten outputs hold what vs11's engines give: oD0 (1, 1, 1, 1), oD1 (0, 0, 0, 1), all else 0\n"
        "//   {}\n"
        "// Arithmetic: the operations of vs11's engines in their order, each IEEE single precision, so every\n"
        "// result is bit-exact where the driver rounds division and sqrt correctly and keeps NaNs and denormals;\n"
        "// GLSL only promises 2.5 ULP for x / y and 1 / inversesqrt()'s bound for sqrt, which rcp, rsq and the\n"
        "// log2 reduction of log, logp and lit use. Everything else is exact by construction.\n"
        "//   Float rules: {}\n"
        "//   Contraction: {}\n",
        options_.source_name.empty() ? "(unnamed)" : options_.source_name, TargetName(profile_.target()),
        options_.constant_count - 1, options_.constant_count, ClipDescription(), profile_.OutputMatching(),
        FloatRulesDescription(), profile_.Contraction());
    return text;
  }

  // The dcl comment of each input register, or empty.
  std::vector<std::string> InputUsages() const {
    std::vector<std::string> usages(kInputRegisterCount);
    for (const Instruction& instruction : program_.instructions) {
      if (instruction.opcode != Opcode::kDcl || instruction.dest.reg.index < 0 ||
          instruction.dest.reg.index >= kInputRegisterCount || instruction.usage < 0 ||
          instruction.usage >= static_cast<int>(kDeclUsageNames.size())) {
        continue;
      }
      usages[static_cast<std::size_t>(instruction.dest.reg.index)] =
          fmt::format("  // dcl_{}{}", kDeclUsageNames[static_cast<std::size_t>(instruction.usage)],
                      instruction.usage_index == 0 ? std::string() : std::to_string(instruction.usage_index));
    }
    return usages;
  }

  std::string Declarations() const {
    std::string text;
    const std::vector<std::string> usages = InputUsages();
    for (int reg = 0; reg < kInputRegisterCount; ++reg) {
      if (shader_.inputs_read[static_cast<std::size_t>(reg)] || !usages[static_cast<std::size_t>(reg)].empty()) {
        text += fmt::format("layout(location = {}) in vec4 v{};{}\n", reg, reg, usages[static_cast<std::size_t>(reg)]);
      }
    }
    text += profile_.ConstantBank(options_.constant_count);
    if (options_.exact_on_driver) {
      text += "uniform uint vs11_opaque_zero;  // 0: literals the compiler cannot fold (exact_on_driver)\n";
    }
    for (const OutputDeclaration& output : OutputVariables()) {
      text += fmt::format("{}{}out {} {};\n", options_.exact_on_driver ? "invariant " : "",
                          profile_.OutputQualifiers(output.location), Scalar(output) ? "float" : "vec4",
                          output.name);
    }
    return text;
  }

  std::string Helpers() const {
    std::string text;
    if (uses_abs_) text += kAbsHelper;
    if (uses_negate_) text += kNegateHelper;
    if (uses_isnan_) text += kIsNaNHelper;
    if (uses_relative_) {
      text += fmt::format(
          "// c[i] as vs11's engines read it: outside the bank (0, 0, 0, 0), a def constant over the bank.\n"
          "vec4 vs11_c_rel(int i) {{\n  if (i < 0 || i >= {}) return vec4(0.0);\n",
          options_.constant_count);
      for (const auto& [reg, bits] : shader_.definitions) {
        text += fmt::format("  if (i == {}) return vec4({}, {}, {}, {});\n", reg, LiteralText(bits[0]), LiteralText(bits[1]),
                            LiteralText(bits[2]), LiteralText(bits[3]));
      }
      text += "  return c[i];\n}\n";
    }
    return text;
  }

  const Program& program_;
  const ShaderGraph& shader_;
  const ir::Graph& graph_;
  const Profile& profile_;
  const TranslateOptions& options_;
  std::vector<bool> live_;
  bool uses_abs_ = false, uses_negate_ = false, uses_isnan_ = false, uses_relative_ = false;
};

}  // namespace

OutputVariable OutputVariableOf(int slot, bool exact_on_driver) {
  for (const OutputDeclaration& output : OutputVariables()) {
    if (output.slot == slot) return {output.name, output.scalar && !exact_on_driver ? 1 : 4};
  }
  return {OutputSlotName(slot), 4};
}

std::string TranslateToGlsl(const Program& program, const TranslateOptions& options) {
  const ShaderGraph shader = RecordShader(program, options.constant_count, options.float_rules);
  const std::unique_ptr<Profile> profile = MakeProfile(options.target);
  return Writer(program, shader, *profile, options).Write();
}

Result<Artifact> Translate(const Program& program, const TranslateOptions& options) {
  const Status refusal = EngineRefusal(program, "translate");
  const Status problem = refusal ? StageProblem(options.target, options.stage) : refusal;
  if (!problem.ok()) return problem.error();
  return MakeProfile(options.target)->Finish(TranslateToGlsl(program, options), options.stage);
}

}  // namespace vs11::translate
