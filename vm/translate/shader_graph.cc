#include "vm/translate/shader_graph.h"

#include "vm/ir/record.h"

namespace vs11::translate {
namespace {

ir::Vec4 Literal(const Vec4f& value) {
  ir::Vec4 result;
  for (int c = 0; c < 4; ++c) result[c] = ir::Constant(ir::Float{}, value[c]);
  return result;
}

// GLSL's registers: `in vec4 v#`, `uniform vec4 c[N]` with the program's defs as literals.
class ShaderBindings final : public ir::Bindings {
 public:
  explicit ShaderBindings(ShaderGraph& shader) : shader_(shader) {}

  ir::Vec4 ReadConstant(long index) override {
    if (index >= shader_.constant_count) return Literal({});
    ir::Vec4 value;
    if (const auto def = shader_.definitions.find(static_cast<int>(index)); def != shader_.definitions.end()) {
      for (int c = 0; c < 4; ++c) value[c] = ir::LiteralBits(def->second[c]);
      return value;
    }
    for (int c = 0; c < 4; ++c) value[c] = ir::RecordFloat(ir::Op::kConstant, {}, static_cast<std::uint32_t>(index * 4 + c));
    return value;
  }
  ir::Vec4 ReadInput(long index) override {
    shader_.inputs_read[static_cast<std::size_t>(index)] = true;
    ir::Vec4 value;
    for (int c = 0; c < 4; ++c) value[c] = ir::RecordFloat(ir::Op::kInput, {}, static_cast<std::uint32_t>(index * 4 + c));
    return value;
  }
  ir::Vec4 InitialOutput(int slot) override {
    return shader_.written[slot].bits() != 0 ? Literal({}) : Literal(UnwrittenOutputValue(slot));
  }

 private:
  ShaderGraph& shader_;
};

}  // namespace

ShaderGraph RecordShader(const Program& program, int constant_count, FloatRules rules) {
  ShaderGraph shader;
  shader.constant_count = constant_count;
  shader.written = WrittenOutputLanes(program);
  for (const Instruction& instruction : program.instructions) {
    const int index = instruction.dest.reg.index;
    if (instruction.opcode == Opcode::kDef && index >= 0 && index < constant_count) shader.definitions[index] = instruction.def_bits;
  }
  ShaderBindings bindings(shader);
  ir::Bindings* const vertices[] = {&bindings};
  const std::vector<ir::RecordedOutputs> outputs = ir::RecordProgram(shader.graph, program, vertices, rules);
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    for (int c = 0; c < 4; ++c) shader.outputs[slot][c] = outputs[0].outputs[slot][c].id;
  }
  return shader;
}

std::vector<bool> LiveNodes(const ShaderGraph& shader) {
  std::vector<int> roots;
  for (const auto& slot : shader.outputs) roots.insert(roots.end(), slot.begin(), slot.end());
  return ir::FindLiveness(shader.graph, roots).live;
}

}  // namespace vs11::translate
