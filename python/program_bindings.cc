// vs11.assemble, vs11.load and the Program class: tokens, disassembly, validation, counts and the
// register names a program reads and writes. Loading goes through the same library calls as the
// vs11 tool (vm/cli/cli_support.cc), so a program's metadata (`; vs11: fragment=yes`) counts here too.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings.h"
#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/disassembler.h"
#include "vm/asm/validator.h"
#include "vm/core/machine.h"
#include "vm/reference/verify.h"

namespace vs11::python {
namespace {

void CheckConstantCount(int max_constants) {
  if (max_constants < kDefaultConstantCount || max_constants > kMaxConstantIndex + 1) {
    throw py::value_error(fmt::format("max_constants={} is out of range: {} to {} (MaxVertexShaderConst)",
                                      max_constants, kDefaultConstantCount, kMaxConstantIndex + 1));
  }
}

// Raises AssemblyError when there are errors, warns for the warnings otherwise.
PyProgram Finish(std::optional<Program> program, const Diagnostics& diagnostics, std::string name,
                 int constant_count, bool fragment) {
  if (!program || diagnostics.HasErrors()) RaiseAssemblyError(diagnostics);
  WarnDiagnostics(diagnostics);
  return PyProgram{std::move(*program), std::move(name), constant_count, fragment};
}

PyProgram Assemble(const std::string& source, const std::string& name, std::optional<bool> fragment,
                   int max_constants) {
  CheckConstantCount(max_constants);
  vs11::MetadataResult metadata = vs11::ParseProgramMetadata(source, name);
  AssembleOptions options;
  options.constant_count = max_constants;
  const bool is_fragment = fragment.value_or(metadata.metadata.fragment);
  options.require_position = !is_fragment;
  AssembleResult assembled = AssembleSource(source, name, options);
  Diagnostics diagnostics = metadata.diagnostics;
  diagnostics.Append(assembled.diagnostics);
  return Finish(std::move(assembled.program), diagnostics, name, max_constants, is_fragment);
}

PyProgram Load(const std::filesystem::path& path, std::optional<bool> fragment, int max_constants) {
  CheckConstantCount(max_constants);
  LoadProgramOptions options;
  options.assemble.constant_count = max_constants;
  vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(path, options, fragment);
  const bool is_fragment = fragment.value_or(loaded.metadata.fragment);
  return Finish(std::move(loaded.program), loaded.diagnostics, path.string(), max_constants, is_fragment);
}

py::list Validate(const PyProgram& self) {
  ValidatorOptions options;
  options.constant_count = self.constant_count;
  options.require_position = !self.fragment;
  Diagnostics diagnostics = vs11::Validate(self.program, options);
  if (diagnostics.HasErrors()) RaiseAssemblyError(diagnostics);
  return DiagnosticsToPython(diagnostics);
}

py::dict Count(const PyProgram& self) {
  const ProgramStats stats = ComputeStats(self.program);
  py::dict counts;
  counts["instructions"] = stats.instructions;
  counts["slots"] = stats.slots;
  counts["constants"] = stats.constants;
  counts["temporaries"] = stats.temporaries;
  counts["inputs"] = stats.inputs;
  // vs_1_1 has no flow control: every instruction runs once per vertex (as `vs11 count` says).
  counts["dynamic_instructions_per_vertex"] = stats.instructions;
  counts["uses_relative_addressing"] = stats.uses_relative_addressing;
  return counts;
}

// v# declared by a dcl or read by an instruction, in register order.
std::vector<std::string> InputNames(const Program& program) {
  std::set<int> registers;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode == Opcode::kDcl) registers.insert(instruction.dest.reg.index);
    for (int s = 0; s < instruction.info().source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file == RegisterFile::kInput) registers.insert(reg.index);
    }
  }
  std::vector<std::string> names;
  for (int reg : registers) names.push_back(fmt::format("v{}", reg));
  return names;
}

std::vector<std::string> OutputNames(const Program& program) {
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  std::vector<std::string> names;
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    if (written[slot].bits() != 0) names.push_back(OutputSlotName(slot));
  }
  return names;
}

py::array_t<std::uint32_t> Tokens(const PyProgram& self) {
  const std::vector<std::uint32_t> words = Encode(self.program);
  py::array_t<std::uint32_t> tokens(static_cast<py::ssize_t>(words.size()));
  std::copy(words.begin(), words.end(), tokens.mutable_data());
  return tokens;
}

}  // namespace

py::list DiagnosticsToPython(const Diagnostics& diagnostics) {
  py::list list;
  for (const Diagnostic& diagnostic : diagnostics.all()) {
    py::dict item;
    item["file"] = diagnostic.loc.file;
    item["line"] = diagnostic.loc.line;
    item["column"] = diagnostic.loc.column;
    item["severity"] = std::string(kSeverityNames.Name(diagnostic.severity));
    item["message"] = diagnostic.message;
    item["word_offset"] = diagnostic.word_offset;
    item["text"] = FormatDiagnostic(diagnostic);
    list.append(item);
  }
  return list;
}

void RaiseAssemblyError(const Diagnostics& diagnostics) {
  std::string message = diagnostics.ToString();
  while (!message.empty() && message.back() == '\n') message.pop_back();
  py::object error_type = py::module_::import("vs11._vs11").attr("AssemblyError");
  py::object error = error_type(message);
  error.attr("diagnostics") = DiagnosticsToPython(diagnostics);
  PyErr_SetObject(error_type.ptr(), error.ptr());
  throw py::error_already_set();
}

void WarnDiagnostics(const Diagnostics& diagnostics) {
  for (const Diagnostic& diagnostic : diagnostics.all()) {
    if (diagnostic.severity != Severity::kWarning) continue;
    if (PyErr_WarnEx(PyExc_UserWarning, FormatDiagnostic(diagnostic).c_str(), 2) != 0) throw py::error_already_set();
  }
}

void BindPrograms(py::module_& module) {
  py::handle error_type = PyErr_NewExceptionWithDoc(
      "vs11.AssemblyError",
      "A program did not assemble, load or validate. str(error) holds every diagnostic as the vs11 tool\n"
      "prints them (FILE:LINE:COLUMN: error: MESSAGE); .diagnostics holds them as dicts.",
      PyExc_ValueError, nullptr);
  module.add_object("AssemblyError", error_type);

  py::class_<PyProgram> program_class(module, "Program",
                                      "A validated vs_1_1 program (from vs11.assemble or vs11.load).");
  program_class
      .def_property_readonly("name", [](const PyProgram& self) { return self.name; },
                             "The file name diagnostics use.")
      .def_property_readonly("tokens", &Tokens, "The D3D9 bytecode as a uint32 NumPy array (a .vso file's words).")
      .def_property_readonly("inputs", [](const PyProgram& self) { return InputNames(self.program); },
                             "Input registers the program declares or reads: ['v0', ...].")
      .def_property_readonly("outputs", [](const PyProgram& self) { return OutputNames(self.program); },
                             "Output registers the program writes, in run()'s order: ['oPos', 'oD0', ...].")
      .def_property_readonly("fragment", [](const PyProgram& self) { return self.fragment; },
                             "True when validated as a fragment (no oPos write required).")
      .def("disassemble", [](const PyProgram& self) { return Disassemble(self.program); },
           "The program as assembly text that re-assembles to the same tokens (what `vs11 disasm` prints).")
      .def("validate", &Validate,
           "Validates again against the vs_1_1 rules; returns the warnings (dicts like\n"
           "AssemblyError.diagnostics) and raises AssemblyError on errors.")
      .def("count", &Count,
           "The static figures `vs11 count` prints: instructions, slots, constants, temporaries, inputs,\n"
           "dynamic_instructions_per_vertex (and uses_relative_addressing).")
      .def("__repr__", [](const PyProgram& self) {
        return fmt::format("<vs11.Program {} ({} slots)>", self.name, ComputeStats(self.program).slots);
      });
  BindRun(program_class);

  module.def("assemble", &Assemble, py::arg("source"), py::arg("name") = "<string>", py::arg("fragment") = py::none(),
             py::arg("max_constants") = kDefaultConstantCount,
             "Assembles and validates vs_1_1 source text (DX8 or DX9 syntax, preprocessed like a .vsh file).\n\n"
             "name: the file name used in diagnostics and to find #include files.\n"
             "fragment: True to accept a program that writes no oPos; None: the source's\n"
             "  `; vs11: fragment=yes|no` metadata line decides (else False).\n"
             "max_constants: constant registers the device has (96 to 2048).\n"
             "Raises AssemblyError on errors; warnings become Python warnings.\n\n"
             "Example:\n"
             "  p = vs11.assemble('vs_1_1\\ndcl_position v0\\nmov oPos, v0\\n')");
  module.def("load", &Load, py::arg("path"), py::arg("fragment") = py::none(),
             py::arg("max_constants") = kDefaultConstantCount,
             "Loads a .vsh source or .vso bytecode file and validates it; arguments as for assemble().\n\n"
             "Example:\n"
             "  p = vs11.load('programs/sh9_irradiance.vsh')");
}

}  // namespace vs11::python
