// libFuzzer target: arbitrary bytes as a mesh file through mesh::LoadMeshFromMemory (Assimp's
// ReadFileFromMemory with no format hint, so every importer whose signature check accepts the bytes
// gets them), with normals and tangents generated so that those post-processing steps run too.
#include <cstddef>
#include <cstdint>

#include "vm/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vs11::mesh::MeshLoadOptions options;
  options.compute_normals = (size & 1) != 0;
  options.compute_tangents = (size & 2) != 0;
  vs11::mesh::MeshLoadResult result = vs11::mesh::LoadMeshFromMemory({data, size}, "", options);
  if (result.ok()) {
    // Every index must name a vertex of the joined arrays.
    for (std::uint32_t index : result.mesh->indices) {
      if (index >= result.mesh->vertex_count) __builtin_trap();
    }
  }
  return 0;
}
