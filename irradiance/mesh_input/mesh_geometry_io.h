// irrmap --mesh FILE: the mesh read through Assimp (mesh/mesh_io.h) into the irradiance library's
// MeshGeometry, with Assimp's exporter as its mesh.ply writer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "irradiance/jobs/mesh_lighting.h"

namespace vs11::irradiance {

// The mesh in root space (normals by the loader's inverse transpose, normalised), or an error
// message. A mesh without normals or without triangles is an error that says so. Loader warnings go to `warnings`.
// `timeout_seconds` is MeshLoadOptions::timeout_seconds (0 = the loader's default).
std::optional<std::string> LoadMeshGeometry(const std::string& path, MeshGeometry& geometry,
                                            std::vector<std::string>& warnings, double timeout_seconds = 0);

}  // namespace vs11::irradiance
