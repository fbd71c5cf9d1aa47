// The embedded irradiance programs. See paper_program.h.
#include "irradiance/report/paper_program.h"

#include <array>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "programs/embedded_programs.h"
#include "vm/asm/assembler.h"
#include "vm/engines/engine_factory.h"
#include "vm/reference/verify.h"

namespace vs11::irradiance {

Result<PaperProgram> PaperProgram::Load() { return LoadOrder(ShOrder::kOrder2); }

Result<PaperProgram> PaperProgram::LoadOrder(ShOrder order) {
  const std::string_view file = Info(order).program_file;
  return LoadEmbedded(file, EmbeddedText(file));
}

std::string_view PaperProgram::EmbeddedText(std::string_view file_name) {
  for (const auto& [name, text] : programs::kEmbeddedPrograms) {
    if (name == file_name) return text;
  }
  return {};
}

Result<PaperProgram> PaperProgram::LoadEmbedded(std::string_view name, std::string_view text) {
  const std::string file_name(name);
  MetadataResult metadata = ParseProgramMetadata(text, file_name);
  AssembleOptions assemble;
  assemble.validate = false;  // validated below as a fragment: it writes no oPos
  AssembleResult assembled = AssembleSource(text, file_name, assemble);
  Diagnostics diagnostics = metadata.diagnostics;
  diagnostics.Append(assembled.diagnostics);
  if (assembled.program) {
    diagnostics.Append(ValidateFragment(*assembled.program, assemble.constant_count, assembled.dx9_syntax));
  }
  if (!assembled.program || diagnostics.HasErrors()) {
    return Failure(DiagnosticCode::kEmbeddedProgram,
                   "the embedded program " + file_name + " does not assemble:\n" + diagnostics.ToString(), {file_name});
  }
  const ProgramMetadata& m = metadata.metadata;
  if (!m.normal || !m.output || !m.constants) {
    return Failure(DiagnosticCode::kEmbeddedProgram,
                   fmt::format("{} lacks its normal=, output= or constants= metadata line", file_name), {file_name});
  }
  PaperProgram program;
  program.program_ = std::move(*assembled.program);
  program.normal_register_ = *m.normal;
  program.output_slot_ = *m.output;
  program.constant_base_ = *m.constants;
  return program;
}

ConstantBank PaperProgram::Constants(const SevenConstants& constants) const {
  ConstantBank bank;
  for (std::size_t i = 0; i < constants.registers.size(); ++i) {
    const glm::vec4& v = constants.registers[i];
    bank[constant_base_ + static_cast<int>(i)] = {v.x, v.y, v.z, v.w};
  }
  return bank;
}

ConstantBank PaperProgram::Constants(std::span<const NamedRegister> registers) const {
  ConstantBank bank;
  for (std::size_t i = 0; i < registers.size(); ++i) {
    const glm::vec4& v = registers[i].value;
    bank[constant_base_ + static_cast<int>(i)] = {v.x, v.y, v.z, v.w};
  }
  return bank;
}

Result<std::vector<glm::dvec3>> PaperProgram::Irradiance(const SevenConstants& constants,
                                                         std::span<const glm::dvec3> normals, std::string engine,
                                                         const EngineOptions& engine_options) const {
  return Irradiance(Constants(constants), normals, engine, engine_options);
}

Result<std::vector<glm::dvec3>> PaperProgram::Irradiance(const ConstantBank& bank,
                                                         std::span<const glm::dvec3> normals, std::string engine,
                                                         const EngineOptions& engine_options) const {
  const std::array<int, 1> input_registers = {normal_register_};
  VertexArrays inputs = MakeInputArrays(normals.size(), input_registers);
  for (int c = 0; c < 3; ++c) {
    float* lane = inputs.lane(normal_register_, c);
    for (std::size_t i = 0; i < normals.size(); ++i) lane[i] = static_cast<float>(normals[i][c]);
  }
  VertexArrays outputs = MakeOutputArrays(normals.size(), program_);
  Result<std::unique_ptr<Engine>> machine = MakeEngine(engine, program_, bank, engine_options);
  if (!machine) return machine.error();
  if (Status ran = (*machine)->Run(inputs, outputs); !ran) return ran.error();
  std::vector<glm::dvec3> irradiance(normals.size());
  for (int c = 0; c < 3; ++c) {
    const float* lane = outputs.lane(output_slot_, c);
    for (std::size_t i = 0; i < normals.size(); ++i) irradiance[i][c] = lane[i];
  }
  return irradiance;
}

}  // namespace vs11::irradiance
