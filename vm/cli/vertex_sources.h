// `vs11 run`'s vertex data beyond CSV: meshes (Assimp), .npy arrays and raw interleaved buffers in;
// .npy files, a raw buffer and a mesh with the outputs as attributes out.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/core/machine.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/vertex_binding.h"

namespace vs11::cli {

struct VertexSourceFlags {
  std::string mesh;
  std::vector<std::string> binds;
  bool compute_normals = false;
  bool compute_tangents = false;
  double mesh_timeout = 0;  // seconds; 0 = the loader's default
  float blend_index_scale = 1.0f;
  std::string bone_palette;  // "c6"
  std::vector<std::string> npy_inputs;  // v#=FILE.npy
  std::string buffer;
  std::size_t stride = 0;
  std::vector<std::string> elements;  // v#=OFFSET:COUNT
  std::string out_npy_dir;
  std::string out_buffer;
  std::string out_mesh;

  void AddTo(CLI::App& command);
  // True when an output file other than --out's CSV is asked for (the CSV then is not printed).
  bool WritesOutputFiles() const { return !out_npy_dir.empty() || !out_buffer.empty() || !out_mesh.empty(); }
};

struct VertexSources {
  std::optional<mesh::Mesh> mesh;
};

// Appends the registers read from --mesh, --npy and --buffer to `supplied` (a later source replaces
// an earlier one's register) and writes --bone-palette into `constants`. Fails with a message.
VertexSources CollectVertexSources(const VertexSourceFlags& flags, const Program& program, ConstantBank& constants,
                                   mesh::RegisterData& supplied);

// --out-npy and --out-buffer, written all or none (a failure leaves none of them), then --out-mesh.
void WriteVertexOutputs(const VertexSourceFlags& flags, const VertexSources& sources, const Program& program,
                        const VertexArrays& outputs);

}  // namespace vs11::cli
