#include "vm/translate/compute_stage.h"

#include <algorithm>

#include <fmt/format.h>

#include "vm/translate/compute_interface.h"

namespace vs11::translate {

std::string ComputeInterfaceComment(const ComputeInterfaceText& text) {
  return fmt::format(
      "// vs_1_1 program {} translated by vs11 for {}, as a compute shader: one invocation per vertex.\n"
      "// Interface (vs11's README, \"vs11 translate\", --stage compute):\n"
      "//   binding 0  uniform block Vs11Constants (std140): vec4 c[{}], the constant bank; def constants\n"
      "//              are applied here and win over it; c[a0.x + n] outside the bank reads (0, 0, 0, 0)\n"
      "//   binding 1  uniform block Vs11Layout (std140): where each input and output lies, in floats:\n"
      "//              component k of vN for vertex i is vs11_in[vs11_input_base[N][k] + i * vs11_input_stride[N].x],\n"
      "//              supplied where vs11_input_stride[N].y != 0, else (0, 0, 0, 1); the outputs likewise by slot\n"
      "//              (oPos 0, oFog 1, oPts 2, oD0 3, oD1 4, oT0..oT7 5..12), written where .y != 0;\n"
      "//              vs11_vertex_count vertices; vs11_opaque_zero must be 0\n"
      "//   binding 2  storage buffer Vs11Inputs {{ float vs11_in[]; }}\n"
      "//   binding 3  storage buffer Vs11Outputs {{ float vs11_out[]; }}: the four lanes of every output\n"
      "//              register the program writes (unwritten lanes of it 0), nothing else\n"
      "//   work groups of {} along x; vertex i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * {} +\n"
      "//   gl_GlobalInvocationID.x, so counts beyond one dimension's limit dispatch in two\n"
      "// Arithmetic: the operations of vs11's engines in their order, each IEEE single precision (as the\n"
      "// vertex form: x / y and sqrt as the driver rounds them, denormals and NaNs as it keeps them).\n"
      "//   Float rules: {}\n"
      "//   Contraction: {}\n",
      text.source_name.empty() ? "(unnamed)" : text.source_name, text.target_name, text.constant_count,
      kComputeWorkGroupSize, kComputeWorkGroupSize, text.float_rules, text.contraction);
}

std::string ComputeDeclarations(int constant_count) {
  return fmt::format(
      "layout(local_size_x = {}) in;\n"
      "layout(std140, binding = {}) uniform Vs11Constants {{ vec4 c[{}]; }};\n"
      "layout(std140, binding = {}) uniform Vs11Layout {{\n"
      "  uvec4 vs11_input_base[{}];\n  uvec4 vs11_input_stride[{}];\n"
      "  uvec4 vs11_output_base[{}];\n  uvec4 vs11_output_stride[{}];\n"
      "  uint vs11_vertex_count;\n  uint vs11_opaque_zero;\n}};\n"
      "layout(std430, binding = {}) readonly buffer Vs11Inputs {{ float vs11_in[]; }};\n"
      "layout(std430, binding = {}) writeonly buffer Vs11Outputs {{ float vs11_out[]; }};\n"
      "vec4 vs11_input(int r, uint i) {{\n"
      "  if (vs11_input_stride[r].y == 0u) return vec4(0.0, 0.0, 0.0, 1.0);\n"
      "  uvec4 at = vs11_input_base[r] + uvec4(i * vs11_input_stride[r].x);\n"
      "  return vec4(vs11_in[at.x], vs11_in[at.y], vs11_in[at.z], vs11_in[at.w]);\n}}\n"
      "void vs11_store(int slot, uint i, vec4 value) {{\n"
      "  if (vs11_output_stride[slot].y == 0u) return;\n"
      "  uvec4 at = vs11_output_base[slot] + uvec4(i * vs11_output_stride[slot].x);\n"
      "  vs11_out[at.x] = value.x;\n  vs11_out[at.y] = value.y;\n  vs11_out[at.z] = value.z;\n"
      "  vs11_out[at.w] = value.w;\n}}\n",
      kComputeWorkGroupSize, kComputeConstantsBinding, constant_count, kComputeLayoutBinding, kInputRegisterCount,
      kInputRegisterCount, kOutputSlotCount, kOutputSlotCount, kComputeInputsBinding, kComputeOutputsBinding);
}

std::string ComputePrologue(const std::vector<bool>& inputs_read, const std::vector<std::string>& usages) {
  std::string text = fmt::format(
      "  uint vs11_vertex = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * {}u + gl_GlobalInvocationID.x;\n"
      "  if (vs11_vertex >= vs11_vertex_count) return;\n",
      kComputeWorkGroupSize);
  for (std::size_t reg = 0; reg < inputs_read.size(); ++reg) {
    if (!inputs_read[reg]) continue;
    text += fmt::format("  vec4 v{} = vs11_input({}, vs11_vertex);{}\n", reg, reg, reg < usages.size() ? usages[reg] : "");
  }
  return text;
}

std::string ComputeStore(int slot, std::string_view variable) {
  return fmt::format("  vs11_store({}, vs11_vertex, {});\n", slot, variable);
}

void ComputeLayoutBlock::SetInput(int reg, const UVec4& base, std::uint32_t stride) {
  input_base[static_cast<std::size_t>(reg)] = base;
  input_stride[static_cast<std::size_t>(reg)] = {stride, 1, 0, 0};
}

void ComputeLayoutBlock::SetOutput(int slot, const UVec4& base, std::uint32_t stride) {
  output_base[static_cast<std::size_t>(slot)] = base;
  output_stride[static_cast<std::size_t>(slot)] = {stride, 1, 0, 0};
}

std::array<std::uint32_t, 2> ComputeDispatchSize(std::size_t vertex_count, std::uint32_t max_groups_x) {
  const std::size_t groups = (vertex_count + kComputeWorkGroupSize - 1) / kComputeWorkGroupSize;
  if (groups == 0) return {0, 0};
  const std::size_t x = std::min<std::size_t>(groups, std::max<std::uint32_t>(max_groups_x, 1));
  return {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>((groups + x - 1) / x)};
}

}  // namespace vs11::translate
