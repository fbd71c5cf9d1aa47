// NumPy arrays and Python mappings to the machine's inputs and constants, and its outputs back to
// NumPy. Every problem with what the caller passed is a ValueError naming the argument and key.
#pragma once

#include <memory>
#include <vector>

#include "python/bindings.h"
#include "vm/core/machine.h"

namespace vs11::python {

struct RunInputs {
  VertexArrays arrays;
  std::vector<int> registers;  // the v# supplied
  std::vector<py::array> borrowed;  // the arrays `arrays` reads in place, kept alive with it
};

// `inputs` maps "v3" or a dcl usage name ("position", "texcoord1") to an (n, 4) or (n, 3) float32
// or float64 array (w = 1 for (n, 3), as D3D's FLOAT3); every array must have the same n.
// A float32 array whose strides are whole floats (C-contiguous (n, 4) and (n, 3), slices, Fortran
// order, reversed rows) is not copied: `arrays` borrows it (VertexArrays::Borrow) and the engines
// read it in place, a batch of vertices at a time. Other arrays (float64, odd byte strides) are
// converted once, straight from the caller's buffer with its strides, into lanes of their own.
RunInputs InputsFromPython(const Program& program, const py::dict& inputs);

// None, a mapping of "c4" / "c[4]" / 4 to four numbers, or a (k, 4) array of c0..c(k-1).
// `given` receives every register set.
ConstantBank ConstantsFromPython(const py::object& constants, int constant_count, std::vector<int>& given);

// One (n, 4) float32 array per written output register, keyed by name ("oPos", "oD0"), in output
// order. The arrays are views of `outputs` (no copy), which they keep alive together.
py::dict OutputsToPython(std::unique_ptr<VertexArrays> outputs);

}  // namespace vs11::python
