// Vertex normals computed from a mesh's own triangles, for files that give none or unusable ones
// (MeshLoadOptions::compute_normals and repair_normals in mesh_io.h). vs11 computes them itself,
// from the triangles as Assimp hands them over after post-processing, rather than through Assimp's
// aiProcess_GenSmoothNormals: that step can only fill meshes with no normals at all (not a zero
// normal among good ones), weighs every face alike, and with aiProcess_ForceGenNormals Assimp 5.2
// frees a point or line mesh's normals without clearing the pointer (a use after free, found by
// tests/fuzz/fuzz_mesh).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vs11::mesh {

using Vec3f = std::array<float, 3>;
using Vec3d = std::array<double, 3>;

// Whether `n` can light a vertex: finite and not zero.
bool IsUsableNormal(const Vec3f& n);

// The area-weighted smooth normal of every vertex, unit length in double precision: the sum of the
// cross products (b - a) x (c - a), whose length is twice the triangle's area, of every triangle
// (a, b, c) with a corner at the vertex's position, normalised. Vertices at equal positions (by
// value, so +0 equals -0) share one normal, so a file that repeats each corner per triangle (STL)
// is smoothed as if the corners were shared. The winding gives the side: counter-clockwise seen
// from the front. A triangle with a non-finite corner adds nothing; a vertex touched by no triangle
// with area gets (0, 0, 0), which IsUsableNormal refuses.
// `triangles` holds three indices per triangle, each below positions.size(). The same input gives
// the same bits: each position's triangles are summed in vertex order, in double precision.
std::vector<Vec3d> AreaWeightedNormals(std::span<const Vec3f> positions, std::span<const std::uint32_t> triangles);

}  // namespace vs11::mesh
