// A small z-buffered triangle rasterizer with Gouraud interpolation, for previews of lit meshes
// (irrmap --mesh). Orthographic: a preview of per-vertex irradiance needs depth order, not
// perspective. Pixel centres sit at (x + 0.5, y + 0.5), row 0 at the top; a pixel is covered when its
// centre is inside the triangle or on an edge (both windings are drawn: no back-face culling).
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

// World to screen: screen = scale * (rotation * (p - center)) + (width / 2, height / 2) with screen y
// flipped (up is up); the depth is the rotated z, larger = nearer the viewer.
struct MeshView {
  glm::dmat3 rotation{1.0};  // world to camera axes: rows are the camera's right, up and backward
  glm::dvec3 center{0.0};
  double scale = 1.0;        // pixels per world unit
  int width = 0;
  int height = 0;
};

// The camera of the preview: it looks at the bounding box's centre from the front-right and a little
// above (+z is the front, +y up), and the box's bounding sphere fills kFramedFraction of the shorter
// side of the image, so every vertex is in the picture.
inline constexpr double kFramedFraction = 0.92;
MeshView FrameBoundingBox(std::span<const glm::vec3> positions, int width, int height);

struct RasterImage {
  Image color;                   // background where not covered
  std::vector<std::uint8_t> covered;  // per pixel, 1 where a triangle was drawn
};

// Draws the triangles `indices` (three per triangle; indices must be < positions.size(), asserted)
// with colours interpolated from `colors` (one per vertex) over `background`.
RasterImage RasterizeMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> colors,
                          std::span<const std::uint32_t> indices, const MeshView& view, glm::vec3 background);

}  // namespace vs11::irradiance
