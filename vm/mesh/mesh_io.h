// Meshes read through Assimp into per-vertex attribute arrays, ready to bind to input registers.
//
// Coordinates: every part (one Assimp mesh under one node) is moved into the scene's root space by
// its node's global transform, unless MeshLoadOptions::transform_to_world is false:
//   position  -> M p (w = 1)
//   normal    -> normalize(inverse(transpose(M3)) n), M3 the upper 3x3 of M (w = 1)
//   tangent, binormal -> normalize(M3 t)
// computed in double precision, then rounded to float. Skinned parts (parts with bones) are NOT
// moved: glTF ignores the transform of a skinned mesh's node, and Assimp's bone offset matrices map
// from the mesh's own space; their bones' skin matrices (Mesh::bones) carry the vertices to root
// space instead. MeshPart::transform always holds the node's global transform, so a caller that
// loads with transform_to_world = false can apply it (or its inverse transpose) itself.
//
// Every attribute array holds one Vec4f per vertex, or is empty when no part of the mesh has it. The
// components a file does not supply are filled as a D3D vertex declaration expands a short element:
// (x, y, z) -> (x, y, z, 1), (u, v) -> (u, v, 0, 1). A part lacking an attribute that another part
// has reads kDefaultInput (0, 0, 0, 1) there.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::mesh {

inline constexpr int kMaxTexCoordSets = 8;  // Assimp's AI_MAX_NUMBER_OF_TEXTURECOORDS
inline constexpr int kMaxColorSets = 8;     // AI_MAX_NUMBER_OF_COLOR_SETS
inline constexpr int kMaxBonesPerVertex = 4;

// Refused before anything of the mesh is allocated by vs11: files over kMaxMeshFileBytes (checked
// before Assimp reads them), OFF and PLY headers declaring more vertices, faces or elements than the
// file has bytes (before Assimp reads them: its readers allocate from those counts), and scenes
// whose joined parts hold more than kMaxMeshVertices vertices or kMaxMeshTriangles triangles
// (after Assimp's parse, before vs11's arrays).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;  // 1 GiB
inline constexpr std::size_t kMaxMeshVertices = std::size_t{1} << 26;         // 67,108,864
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 27;

// Row-major 4x4 (m[row][column]); a column vector is transformed as m * v.
using Matrix4d = std::array<std::array<double, 4>, 4>;
Matrix4d IdentityMatrix();

struct MeshPart {
  std::string mesh_name;  // Assimp's aiMesh::mName
  std::string node_name;  // the node that places it
  Matrix4d transform;     // the node's global transform (root space <- mesh space)
  bool transformed = false;  // attributes were moved by `transform` (see above)
  bool skinned = false;
  std::size_t first_vertex = 0, vertex_count = 0;
  std::size_t first_index = 0, index_count = 0;  // into Mesh::indices (3 per triangle)
};

struct Bone {
  std::string name;
  // Root space <- mesh space at the scene's rest pose: the bone node's global transform times the
  // bone's offset (inverse bind) matrix. Skinned position = sum_i weight_i * skin[index_i] * p.
  Matrix4d skin;
};

enum class Attribute {
  kPosition, kNormal, kTangent, kBinormal, kTexCoord, kColor, kBlendWeight, kBlendIndices
};

struct Mesh {
  std::size_t vertex_count = 0;
  std::vector<Vec4f> positions;  // always present
  std::vector<Vec4f> normals;
  std::vector<Vec4f> tangents;
  std::vector<Vec4f> binormals;  // Assimp's bitangents
  std::array<std::vector<Vec4f>, kMaxTexCoordSets> texcoords;  // UV set n
  std::array<int, kMaxTexCoordSets> texcoord_components{};    // 1-3 as the file gives them, 0 = absent
  std::array<std::vector<Vec4f>, kMaxColorSets> colors;        // RGBA
  // The (up to) four largest bone influences of each vertex, largest first; unused slots weight 0,
  // index 0. Indices are into `bones`, as floats. Vertices with more than four influences keep
  // four, renormalised to sum 1 (a warning counts them).
  std::vector<Vec4f> blend_weights;
  std::vector<Vec4f> blend_indices;
  std::vector<Bone> bones;

  std::vector<std::uint32_t> indices;  // triangles, 3 indices each, into the joined vertex arrays
  std::vector<MeshPart> parts;         // in scene-graph order (depth first), vertices in file order
  std::vector<std::string> warnings;   // e.g. "3 vertices have NaN or infinite attributes"
  std::size_t nonfinite_vertex_count = 0;

  // The array for an attribute (set = UV or colour set); nullptr when the mesh has none.
  const std::vector<Vec4f>* Find(Attribute attribute, int set = 0) const;
};

struct MeshLoadOptions {
  bool transform_to_world = true;
  // Replace the normals of every part with triangles by computed smooth ones (AreaWeightedNormals in
  // smooth_normals.h: vs11's own, from the triangles after triangulation, each face weighted by its
  // area), whatever the file holds. A vertex in no triangle with area keeps the file's normal.
  bool compute_normals = false;
  // Compute smooth normals (as above) only where the file gives none, or gives a zero or non-finite
  // one: parts without normals get them all; in a part with some unusable normals only those
  // vertices get computed ones, and the file's usable normals keep their bits. A warning counts the
  // vertices. Points and lines have no normal to compute.
  bool repair_normals = false;
  // Generate tangents and binormals from UV set 0 for parts without them (aiProcess_CalcTangentSpace).
  // Assimp derives them from the normals it holds before vs11 computes any: the file's, and with
  // compute_normals its own smooth ones (aiProcess_GenSmoothNormals) for parts without normals. So a
  // tangent need not be exactly orthogonal to a normal vs11 computed, and a part whose file normals
  // are zero gets no usable tangents.
  bool compute_tangents = false;
  // Assimp runs in a child process (mesh_sandbox.h) stopped after this many seconds; 0 = 60 s plus
  // 1 s per MiB of input. The tools' --mesh-timeout sets it.
  double timeout_seconds = 0;
  // The child's address-space budget; 0 = 8 GiB plus 32 bytes per byte of input. Not applied in
  // AddressSanitizer builds.
  std::uintmax_t memory_limit_bytes = 0;
};

// Loads any format Assimp 5.2 reads (OBJ, PLY, glTF/GLB, FBX, Collada, 3DS, STL, ...). Polygons are
// triangulated; points and lines keep their vertices but add no triangles. Vertices are not merged
// or reordered: each part's vertices appear in the order Assimp gives them (the file's order for
// indexed formats), and a mesh placed by several nodes appears once per node. Errors (never thrown):
// unreadable or oversized files, Assimp's parse errors, face indices or bone weights naming a
// vertex the mesh does not have, scenes without a vertex, limits above. Assimp's own warnings
// (triangles it dropped, ...) come first in Mesh::warnings. LoadMesh and LoadMeshFromMemory may be
// called from several threads.
// Assimp 5.2's readers crash and hang on some corrupt files (tests/fuzz/fuzz_mesh found a SEGV in
// the compressed DirectX .x and in the Collada reader, and a Collada file that loops for minutes),
// so Assimp reads in a child process (mesh_sandbox.h): a crash is the error "Assimp crashed reading
// FILE (SIGSEGV); the file is corrupt or unsupported", a hang is stopped at the time limit. Faces
// and headers that crashed or hung Assimp elsewhere are checked first (CheckSceneIndices, the OFF
// and PLY header checks in mesh_io.cc), which gives those files a precise error.
// Every error names the file and says what is wrong. Codes: kOutOfMemory when the reading process
// ran out of memory, kMeshWire when it sent bytes that are no mesh, kMeshConverterCrashed when it
// died in vs11's own checks or conversion rather than in Assimp (a bug in vs11: the fuzz target fails
// on it), kCannotReadFile for the rest (missing, unreadable, oversized, corrupt or unsupported files,
// Assimp's errors, crashes and time-outs).
Result<Mesh> LoadMesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

// Whether Assimp has an importer for files with this extension (".obj", "glb"; case-insensitive).
bool IsMeshFileExtension(const std::string& extension);

// The same from memory (the fuzz target's entry); `format_hint` is an extension such as "obj" or
// "glb" (Assimp's pHint), or empty to let Assimp guess from the content.
Result<Mesh> LoadMeshFromMemory(std::span<const std::uint8_t> bytes, const std::string& format_hint,
                                const MeshLoadOptions& options = {});

}  // namespace vs11::mesh
