// Which mesh attribute feeds which input register: from the program's dcl_* instructions, or from
// an explicit binding list for DX8 programs (no dcl) or to override them.
//
// Binding syntax (the --bind flag; the same `v#=` form as --input v1=FILE.csv):
//   v0=position,v3=normal,v7=texcoord0
// Attribute names: position, normal, tangent, binormal, texcoord0-7 (texcoord = texcoord0),
// color0-7 (color = color0), blendweight, blendindices. Several --bind flags add up; a register
// bound twice takes the last.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/core/result.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::mesh {

struct AttributeRef {
  Attribute attribute = Attribute::kPosition;
  int set = 0;  // UV or colour set
  friend bool operator==(const AttributeRef&, const AttributeRef&) = default;
};
std::optional<AttributeRef> AttributeFromName(std::string_view name);
std::string AttributeName(const AttributeRef& attribute);  // "texcoord1", "normal"

struct RegisterBinding {
  int reg = 0;  // v#
  AttributeRef attribute;
  std::string origin;  // "dcl_normal v3" or "--bind v3=normal", for messages
};

// Parses one --bind value into `bindings` (appended); an error (kBinding) on failure.
Status ParseBindings(std::string_view text, std::vector<RegisterBinding>& bindings);

// One binding per dcl_* instruction. Usages a mesh cannot supply (psize, fog, tessfactor, ...) are
// an error (kBinding) naming the instruction. `overrides` (from --bind) replace the declaration of
// the same register and may add registers the program does not declare.
Status ResolveBindings(const Program& program, const std::vector<RegisterBinding>& overrides,
                       std::vector<RegisterBinding>& bindings);

struct BindOptions {
  // blendindices are multiplied by this: a DX8 palette program addresses c[a0.x + base] with the
  // index premultiplied by the registers per bone (3 for 4x3 matrices, as programs/skinning.vsh).
  float blend_index_scale = 1.0f;
  std::string mesh_name;  // for messages
};

using RegisterData = std::vector<std::pair<int, std::vector<Vec4f>>>;

// The arrays for each binding. An attribute the mesh lacks is an error (kMeshAttributeMissing)
// naming the attribute, the binding that wants it and the mesh, with a hint (--compute-normals,
// --compute-tangents, --bind).
Status BindMesh(const Mesh& mesh, const std::vector<RegisterBinding>& bindings, const BindOptions& options,
                RegisterData& registers);

// Writes each bone's skin matrix (rows 0-2, a 4x3 matrix as m4x3 reads it) into constants
// c[base + 3b] .. c[base + 3b + 2]. An error (kBonePalette) when the palette does not fit the bank.
Status WriteBonePalette(const Mesh& mesh, int base, ConstantBank& constants);

}  // namespace vs11::mesh
