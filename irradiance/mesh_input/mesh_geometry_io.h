// irrmap --mesh FILE: the mesh read through Assimp (mesh/mesh_io.h) into the irradiance library's
// MeshGeometry, with Assimp's exporter as its mesh.ply writer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "irradiance/jobs/mesh_lighting.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The mesh in root space (normals by the loader's inverse transpose, normalised), or the error
// (kCannotReadFile; kMeshAttributeMissing for a mesh without triangles, which says so). Vertices
// whose normal the file omits or gives as zero or not finite get computed smooth normals
// (MeshLoadOptions::repair_normals), with a warning: a picture is never black for want of normals. `compute_normals` replaces every normal
// (irrmap --compute-normals). Loader warnings go to `warnings`, each starting with the file.
// `timeout_seconds` is MeshLoadOptions::timeout_seconds (0 = the loader's default).
Status LoadMeshGeometry(const std::string& path, MeshGeometry& geometry, std::vector<std::string>& warnings,
                        double timeout_seconds = 0, bool compute_normals = false);

}  // namespace vs11::irradiance
