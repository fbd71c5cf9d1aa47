// The vs11 extension module (_vs11), re-exported by the vs11 package (python/vs11/__init__.py).
#include "python/bindings.h"
#include "vm/core/version.h"

PYBIND11_MODULE(_vs11, module) {
  module.doc() =
      "The Direct3D vs_1_1 vertex-shader machine (assembler, validator, engines) and the irradiance\n"
      "environment-map pipeline, with NumPy arrays in and out.";
  module.attr("__version__") = std::string(vs11::Vs11Version());  // CMake's project(VERSION)
  vs11::python::BindPrograms(module);
  pybind11::module_ irradiance = module.def_submodule(
      "irradiance", "SH projection of environments, the seven constants, irradiance maps and batches.");
  vs11::python::BindIrradiance(irradiance);
}
