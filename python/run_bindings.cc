// Program.run and Program.trace: the machine over NumPy arrays, through the same library calls as
// `vs11 run` (vm/cli/run_command.cc): MakeEngine, the unset-register warnings, TraceVertex.
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "python/array_conversion.h"
#include "vm/core/thread_pool.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/trace.h"
#include "vm/io/vertex_io.h"

namespace vs11::python {
namespace {


std::string CheckedEngine(const std::string& engine, const py::int_& threads) {
  std::optional<EngineInfo> kind = FindEngine(engine);
  // The module registers no engine of its own: vm/gl's would bring EGL into every Python process.
  if (!kind && engine == "gl") {
    throw py::value_error("engine='gl': the gl engine runs in the vs11 and irrmap tools only (the module does not "
                          "link EGL)");
  }
  if (!kind) throw py::value_error(fmt::format("engine='{}': use {}", engine, EngineNameList("'")));
  if (SaturatedInt(threads) < 1 || SaturatedInt(threads) > kMaxThreadsOption) {
    throw py::value_error(fmt::format("threads={} is out of range: 1 to {}", std::string(py::str(py::handle(threads))), kMaxThreadsOption));
  }
  return std::string(kind->name);
}

// Runs the engine `kind` over `inputs`; RuntimeError where it cannot be built or its run fails (the
// module's engines, the CPU ones, never fail to run). Touches no Python object, so it may run without
// the GIL.
void RunBuiltEngine(const std::string& kind, const Program& program, const ConstantBank& bank,
                    const EngineOptions& options, const VertexArrays& inputs, VertexArrays& outputs) {
  Result<std::unique_ptr<Engine>> engine = MakeEngine(kind, program, bank, options);
  if (!engine) throw std::runtime_error(engine.message());
  if (const Status ran = (*engine)->Run(inputs, outputs); !ran) throw std::runtime_error(ran.message());
}

FloatRules CheckedFloatRules(const std::string& name) {
  std::optional<FloatRules> rules = kFloatRulesNames.Find(name);
  if (!rules) throw py::value_error(fmt::format("float_rules='{}': use {}", name, kFloatRulesNames.List()));
  return *rules;
}

// The warnings `vs11 run` prints before it starts, as Python warnings.
void WarnUnsetRegisters(const PyProgram& self, const std::vector<int>& constants_given,
                        const std::vector<int>& inputs_given) {
  for (const std::string& warning : UnsetRegisterWarnings(self.program, constants_given, inputs_given)) {
    const std::string text = fmt::format("{}: warning: {}", self.name, warning);
    if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 2) != 0) throw py::error_already_set();
  }
}

// missing='error' (the default): a constant the program reads that nobody set, or an input it reads
// that was not given (a misspelt register, say), is a ValueError naming it; missing='zeros': they
// read 0 (inputs 0, 0, 0, 1) with a warning, as `vs11 run --missing zeros`.
void CheckUnsetRegisters(const PyProgram& self, const std::vector<int>& constants_given,
                         const std::vector<int>& inputs_given, const std::string& missing) {
  if (missing != "error" && missing != "zeros") {
    throw py::value_error(fmt::format("missing='{}': use 'error' (the default) or 'zeros'", missing));
  }
  if (missing == "error") {
    const Status set =
        CheckNoUnsetRegisters(FindUnsetRegisters(self.program, constants_given, inputs_given), inputs_given,
                              {"a def nor constants", "entry of inputs", "missing='zeros'"});
    if (!set) throw py::value_error(fmt::format("{}: {}", self.name, set.message()));
  }
  WarnUnsetRegisters(self, constants_given, inputs_given);
}

py::dict Run(const PyProgram& self, const py::dict& inputs, const py::object& constants, const std::string& engine,
             const py::int_& threads, const std::string& float_rules, const std::string& missing) {
  const std::string kind = CheckedEngine(engine, threads);
  const FloatRules rules = CheckedFloatRules(float_rules);
  std::vector<int> constants_given;
  const ConstantBank bank = ConstantsFromPython(constants, self.constant_count, constants_given);
  const RunInputs run_inputs = InputsFromPython(self.program, inputs);
  CheckUnsetRegisters(self, constants_given, run_inputs.registers, missing);
  auto outputs = std::make_unique<VertexArrays>(MakeOutputArrays(run_inputs.arrays.count(), self.program));
  {
    // Nothing below touches a Python object: other Python threads (and other engines) run meanwhile.
    py::gil_scoped_release release;
    RunBuiltEngine(kind, self.program, bank,
                   EngineOptions{.threads = static_cast<int>(SaturatedInt(threads)), .float_rules = rules},
                   run_inputs.arrays, *outputs);
  }
  return OutputsToPython(std::move(outputs));
}

py::object Trace(const PyProgram& self, const py::dict& inputs, const py::object& constants, const py::int_& vertex_number,
                 const std::string& engine, const std::string& float_rules, const std::string& missing) {
  const std::string kind = CheckedEngine(engine, py::int_(1));
  const long long vertex = SaturatedInt(vertex_number);
  const std::string vertex_text = py::str(py::handle(vertex_number));
  const FloatRules rules = CheckedFloatRules(float_rules);
  std::vector<int> constants_given;
  const ConstantBank bank = ConstantsFromPython(constants, self.constant_count, constants_given);
  const RunInputs run_inputs = InputsFromPython(self.program, inputs);
  const std::size_t count = run_inputs.arrays.count();
  if (count == 0) throw py::index_error(fmt::format("vertex {}: the inputs hold no vertices", vertex_text));
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= count) {
    throw py::index_error(fmt::format("vertex {}: there are {} vertices (0 to {})", vertex_text, count, count - 1));
  }
  CheckUnsetRegisters(self, constants_given, run_inputs.registers, missing);
  VertexArrays outputs = MakeOutputArrays(run_inputs.arrays.count(), self.program);
  std::string json;
  {
    py::gil_scoped_release release;
    RunBuiltEngine(kind, self.program, bank, EngineOptions{.threads = 1, .float_rules = rules}, run_inputs.arrays,
                   outputs);
    VertexTrace trace = TraceVertex(self.program, bank, run_inputs.arrays, static_cast<std::size_t>(vertex), rules);
    CompareOutputs(outputs, trace);
    SourceLines sources;
    json = TraceJson(self.program, trace, sources);
  }
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

void BindRun(py::class_<PyProgram>& program_class) {
  program_class.def(
      "run", &Run, py::arg("inputs"), py::arg("constants") = py::none(), py::arg("engine") = "jit",
      py::arg("threads") = 1, py::arg("float_rules") = "d3d9", py::arg("missing") = "error",
      (std::string("Runs the program over n vertices and returns {output name: (n, 4) float32 array}.\n\n"
      "inputs: {'v0' or a dcl usage name ('position', 'normal', 'texcoord1'): array}, each array\n"
      "  (n, 4) or (n, 3) (w = 1, as D3D's FLOAT3), float32 or float64, any strides; every array\n"
      "  the same n. Inputs not given read (0, 0, 0, 1).\n"
      "constants: {'c4' or 4: four numbers}, or a (k, 4) array holding c0..c(k-1). The program's def\n"
      "  lines win.\n"
      "engine: 'jit' (default), 'batch' or 'ref'; all three give the same bits.\n"
      ) + fmt::format("threads: threads for the batch and jit engines (1 to {}).\n", kMaxThreadsOption) + std::string(
      "float_rules: 'd3d9' (default: IEEE products, 0 * inf = NaN) or 'legacy' (every product of mul,\n"
      "  mad, dp3, dp4, m*x*, dst and lit's power is 0 when an operand is 0), as `vs11 run --float-rules`.\n"
      "missing: 'error' (default): a constant the program reads that neither a def nor constants sets,\n"
      "  or an input it reads that inputs does not give (a misspelt register), is a ValueError naming\n"
      "  it; 'zeros': they read 0 (inputs 0, 0, 0, 1), each with a UserWarning, as `vs11 run --missing zeros`.\n"
            "No copy of a float32 input whose strides are whole floats (C-contiguous (n, 4) or (n, 3),\n"
      "slices, Fortran order): the engines read it in place, gathering 256 vertices at a time into a\n"
      "few KB of their own that stay in cache; it must not change while run() works. float64 and\n"
      "other strides are converted once into the engines' layout. The returned arrays are views of\n"
      "the engine's output buffer (no copy). The GIL is released while the engine runs. A def that\n"
      "overrides a given constant is warned about (UserWarning) as `vs11 run` warns. Raises ValueError\n"
      "for bad arrays or names.\n\n"
      "Example:\n"
      "  out = p.run({'v0': np.array([[0, 0, 1]], np.float32)}, {'c0': [1, 2, 3, 4]})\n"
      "  out['oD0']  # (1, 4) float32"))
          .c_str());
  program_class.def(
      "trace", &Trace, py::arg("inputs"), py::arg("constants") = py::none(), py::arg("vertex") = 0,
      py::arg("engine") = "jit", py::arg("float_rules") = "d3d9", py::arg("missing") = "error",
      "Runs one vertex instruction by instruction on the reference engine and returns the record\n"
      "`vs11 run --trace-json` writes for it: a dict with 'vertex', 'identical', 'inputs', 'steps'\n"
      "(one dict per executed instruction: 'index', 'instruction', 'reads', 'write', and 'file',\n"
      "'line', 'source' for assembled text; a later model's in the order its flow control runs them,\n"
      "with 'flow', 'address' and 'predicated_off' where they apply) and 'outputs' (the reference's and\n"
      "`engine`'s values).\n"
      "inputs, constants, float_rules and missing as for run(); raises IndexError for a vertex out of range.\n\n"
      "Example:\n"
      "  steps = p.trace({'v0': normals}, constants, vertex=2)['steps']");
}

}  // namespace vs11::python
