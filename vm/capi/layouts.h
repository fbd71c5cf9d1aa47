// Where a shader's inputs come from and its outputs go, in the C library's terms: D3D8 declaration
// tokens, D3D9 vertex declarations (D3DVERTEXELEMENT9 arrays) and FVF codes, each turned into a
// list of elements at byte offsets. The token and flag layouts are d3d8types.h's and d3d9types.h's;
// this file is the only one of the library that shifts their bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <vs11/vs11_c.h>

#include "vm/capi/vertex_formats.h"
#include "vm/core/program.h"

namespace vs11::capi {

// What is wrong with a layout, and the status the C call returns for it.
struct LayoutError {
  vs11c_status status = VS11C_BAD_DECLARATION;
  std::string message;
  long token = -1;  // the D3D8 declaration token at fault, or the D3D9 element's index
};
template <class T>
using LayoutResult = std::variant<T, LayoutError>;

// One input: register v`reg` reads `type` at `offset` bytes into each vertex of stream `stream`.
struct InputElement {
  int stream = 0;
  std::size_t offset = 0;
  DeclType type = DeclType::kFloat4;
  int reg = 0;
};

// A D3D8 declaration: the inputs, and the constants its D3DVSD_CONST tokens load.
struct D3d8Declaration {
  std::vector<InputElement> inputs;
  std::vector<std::pair<int, Vec4f>> constants;  // register, value
};
// Reads D3DVSD_STREAM, D3DVSD_REG (D3DVSDT_FLOAT1..SHORT4), D3DVSD_SKIP, D3DVSD_CONST, D3DVSD_NOP,
// extension tokens (skipped with their data) and D3DVSD_END, which must come within `tokens`. The
// tessellator tokens are VS11C_UNSUPPORTED; constants must lie below `constant_count`.
LayoutResult<D3d8Declaration> ParseD3d8Declaration(std::span<const std::uint32_t> tokens, int constant_count);

// The elements of a D3D9 declaration up to D3DDECL_END (at most MAXD3DDECLLENGTH = 64 before it):
// each with a valid type, the default method, a known usage and usage index, no usage twice.
LayoutResult<std::vector<vs11c_vertex_element>> ReadD3d9Declaration(const vs11c_vertex_element* declaration);
// The inputs of a D3D9 shader: each dcl_ of `program` bound to the element of its usage and index.
// A dcl_ no element names gets none (it reads (0, 0, 0, 1)); elements no dcl_ names are not read.
std::vector<InputElement> BindD3d9Inputs(const Program& program, std::span<const vs11c_vertex_element> elements);

// One output: output slot `slot` (vm/core/machine.h's OutputSlot numbering) written as `type` at
// `offset`; `transformed` for XYZRHW and POSITIONT, which a viewport turns into screen positions.
struct OutputElement {
  int slot = 0;
  std::size_t offset = 0;
  DeclType type = DeclType::kFloat4;
  bool transformed = false;
};
// An FVF code of a destination buffer, or a D3D9 output declaration; every element ends within
// `stride` bytes.
LayoutResult<std::vector<OutputElement>> OutputsFromFvf(std::uint32_t fvf, std::size_t stride);
LayoutResult<std::vector<OutputElement>> OutputsFromDeclaration(const vs11c_vertex_element* declaration,
                                                                 std::size_t stride);

}  // namespace vs11::capi
