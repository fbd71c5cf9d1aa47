// The paper's Fig. 3 on a real mesh (irrmap ENV --mesh FILE): every vertex lit by the paper's
// vs_1_1 program from its normal, compared with the exact irradiance (brute-force convolution of the
// environment for that normal), and drawn.
//
// Normals: the mesh loader (mesh/mesh_io.h) moves each part into the scene's root space with the
// inverse transpose of its node's global transform and normalises there, in double; LightMesh
// normalises once more in double before rounding to the program's float input (a no-op for unit
// normals; a zero normal stays zero). Skinned parts keep their bind pose (the loader does not move
// them).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

class PaperProgram;

// Above this many vertices the exact irradiance is skipped by default: it costs about 0.2 ms per
// vertex at 256x256 faces on one core. The picture then shows the lit mesh alone.
inline constexpr std::size_t kDefaultMeshTruthVertexLimit = 50000;
inline constexpr int kMeshPanelSize = 384;  // pixels, each of the picture's three panels

// A mesh in root space, ready to light: one normal per position, triangles as index triples.
struct MeshGeometry {
  std::string name;  // the file, for messages
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;
  // Writes the mesh with the given per-vertex colours (8-bit RGBA in [0, 1]) to `path` (mesh.ply).
  // The caller supplies it: the writer is Assimp's, which the irradiance library does not link.
  std::function<Status(const std::filesystem::path&, std::span<const Vec4f>)> write;
};

struct MeshLightingOptions {
  std::string engine = "batch";
  EngineOptions engine_options;
  int threads = 1;  // ground truth
  std::size_t truth_vertex_limit = kDefaultMeshTruthVertexLimit;  // 0: always compute it
  int panel_size = kMeshPanelSize;
};

struct MeshLighting {
  std::vector<glm::dvec3> irradiance;  // per vertex, by the paper's program on the vs_1_1 machine
  std::vector<glm::dvec3> truth;       // per vertex, exact; empty when skipped
  std::vector<double> relative_error;  // per vertex (RelativeError with kPreviewErrorFloor); empty when skipped
  ErrorStats error;                    // over the vertices; zero when skipped
  std::size_t unusable_normals = 0;     // zero or non-finite: drawn black, not in `error`
  double ms_per_evaluation = 0.0;      // the engine's run over every vertex (median of several)
  double truth_ms = 0.0;
  double exposure = 0.0;               // display value = exposure x E (before sRGB encoding)
  std::vector<Vec4f> display_colors;   // per vertex: exposure x E clamped to [0, 1], sRGB-encoded, alpha 1
  Image picture;                       // program | exact | relative error (or the program alone)
  double error_scale = 0.0;            // the relative error at the top of the error panel's ramp
  std::vector<std::string> warnings;
};

// Lights `mesh` (normals.size() == positions.size(), asserted) with the seven constants. Fails only
// where the engine cannot be built or run (the gl engine's driver): degenerate meshes give an empty
// picture area.
Result<MeshLighting> LightMesh(const MeshGeometry& mesh, const PaperProgram& program, const SevenConstants& constants,
                               const CubeMap& environment, const MeshLightingOptions& options);

}  // namespace vs11::irradiance
