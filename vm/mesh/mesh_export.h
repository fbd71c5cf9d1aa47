// Writes a loaded mesh back out with a program's outputs as vertex attributes (Assimp's exporters).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/result.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::mesh {

struct ExportAttributes {
  // RGBA vertex colour (colour set 0), e.g. oD0. GLB keeps the floats; PLY (Assimp's exporter writes
  // 8-bit channels) gets them clamped to [0, 1] first, and says so in its header.
  const std::vector<Vec4f>* color = nullptr;
  // UV sets 0-7, e.g. oT0-oT7. The formats keep (u, v) only: glTF's TEXCOORD_n is VEC2, and
  // Assimp's PLY exporter writes s, t.
  std::array<const std::vector<Vec4f>*, kMaxTexCoordSets> texcoords{};
  // Recorded in the file where the format has room: a "comment" line in the PLY header, the
  // asset's "extras" (key "vs11") in glTF.
  std::string note;
};

// The format comes from the extension: .ply (ASCII PLY: Assimp 5.2's binary PLY exporter writes
// float colours under a uchar header, a file no reader can read) or .glb (binary glTF 2.0).
// Positions, normals and triangles are the mesh's own (root space, joined: one mesh, one node with
// the identity transform). Each array in `attributes` must hold mesh.vertex_count values. The file
// is written atomically. An error (kCannotWriteFile) names the file and what went wrong.
Status ExportMesh(const Mesh& mesh, const ExportAttributes& attributes, const std::filesystem::path& path);

}  // namespace vs11::mesh
