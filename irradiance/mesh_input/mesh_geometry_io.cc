#include "irradiance/mesh_input/mesh_geometry_io.h"

#include <memory>

#include <fmt/format.h>

#include "vm/mesh/mesh_export.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::irradiance {

Status LoadMeshGeometry(const std::string& path, MeshGeometry& geometry, std::vector<std::string>& warnings,
                        double timeout_seconds, bool compute_normals) {
  mesh::MeshLoadOptions options;
  options.timeout_seconds = timeout_seconds;
  options.repair_normals = true;
  options.compute_normals = compute_normals;
  Result<mesh::Mesh> loaded = mesh::LoadMesh(path, options);
  if (!loaded) return loaded.error();
  auto source = std::make_shared<const mesh::Mesh>(std::move(loaded).value());
  for (const std::string& warning : source->warnings) warnings.push_back(fmt::format("{}: {}", path, warning));
  if (source->indices.empty()) {
    return Failure(DiagnosticCode::kMeshAttributeMissing,
                   fmt::format("{}: the mesh has no triangles (points or lines only): nothing to light and draw",
                               path));
  }
  // Not reached with repair_normals: a mesh with triangles gets computed normals where it has none.
  if (source->normals.empty()) {
    return Failure(DiagnosticCode::kMeshAttributeMissing,
                   fmt::format("{}: the mesh has no normals, and the irradiance is a function of the normal", path));
  }
  geometry = MeshGeometry{};
  geometry.name = path;
  for (std::size_t i = 0; i < source->vertex_count; ++i) {
    const Vec4f& p = source->positions[i];
    const Vec4f& n = source->normals[i];
    geometry.positions.emplace_back(p[0], p[1], p[2]);
    geometry.normals.emplace_back(n[0], n[1], n[2]);
  }
  geometry.indices = source->indices;
  geometry.write = [source](const std::filesystem::path& target, std::span<const Vec4f> colors) {
    std::vector<Vec4f> color(colors.begin(), colors.end());
    mesh::ExportAttributes attributes;
    attributes.color = &color;
    attributes.note = "vs11 irrmap: vertex colour = irradiance by the paper's vs_1_1 program, tone mapped as "
                      "mesh.png (brightest vertex 0.8, sRGB), 8-bit";
    return mesh::ExportMesh(*source, attributes, target);
  };
  return {};
}

}  // namespace vs11::irradiance
