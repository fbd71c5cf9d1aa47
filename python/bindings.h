// What the binding files of the vs11 Python module share: the Program object, the AssemblyError
// exception, and the entry points module.cc calls.
#pragma once

#include <limits>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "vm/core/diagnostic.h"
#include "vm/core/program.h"

namespace vs11::python {

namespace py = pybind11;

// A program as Python sees it: the decoded program, the name its diagnostics use, and the
// constant-register count it was validated against (the bank its runs get).
struct PyProgram {
  Program program;
  std::string name;
  int constant_count = kDefaultConstantCount;
  bool fragment = false;  // validated without requiring an oPos write
};

// Every diagnostic as a dict {"file", "line", "column", "severity", "message", "word_offset",
// "text"}: "text" is the line the CLI prints (file:line:column: error: message). A dict rather than
// a class, so that fields added to Diagnostic appear as new keys.
py::list DiagnosticsToPython(const Diagnostics& diagnostics);

// Raises vs11.AssemblyError (a ValueError) whose message is every diagnostic, one line each, as the
// CLI prints them, and whose .diagnostics is DiagnosticsToPython(diagnostics).
[[noreturn]] void RaiseAssemblyError(const Diagnostics& diagnostics);

// Issues one Python warning (UserWarning) per warning diagnostic.
void WarnDiagnostics(const Diagnostics& diagnostics);

// A Python int of any size (2**70 too) as a long long, saturated at its ends: a caller's number out
// of every range is then a ValueError naming it, not pybind11's overflow error.
inline long long SaturatedInt(const py::handle& value) {
  int overflow = 0;
  const long long result = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0) return overflow > 0 ? std::numeric_limits<long long>::max() : std::numeric_limits<long long>::min();
  return result;
}

void BindPrograms(py::module_& module);                    // program_bindings.cc
void BindRun(py::class_<PyProgram>& program_class);         // run_bindings.cc
void BindIrradiance(py::module_& irradiance_module);        // irradiance_bindings.cc
void BindBatch(py::module_& irradiance_module);             // batch_bindings.cc

}  // namespace vs11::python
