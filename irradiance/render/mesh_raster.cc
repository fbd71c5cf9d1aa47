#include "irradiance/render/mesh_raster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace vs11::irradiance {
namespace {

// Camera direction (from the model towards the viewer) of the preview: front, right, above.
constexpr glm::dvec3 kViewFrom{0.45, 0.35, 1.0};

glm::dvec3 Project(const MeshView& view, const glm::vec3& p) {
  glm::dvec3 camera = view.rotation * (glm::dvec3(p) - view.center);
  return {view.scale * camera.x + 0.5 * view.width, 0.5 * view.height - view.scale * camera.y, camera.z};
}

// Twice the signed area of (a, b, p) in screen space.
double Edge(const glm::dvec3& a, const glm::dvec3& b, double px, double py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

}  // namespace

MeshView FrameBoundingBox(std::span<const glm::vec3> positions, int width, int height) {
  MeshView view;
  view.width = width;
  view.height = height;
  const glm::dvec3 backward = glm::normalize(kViewFrom);
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), backward));
  const glm::dvec3 up = glm::cross(backward, right);
  view.rotation = glm::transpose(glm::dmat3(right, up, backward));  // rows: right, up, backward
  if (positions.empty()) return view;
  glm::dvec3 low(std::numeric_limits<double>::max()), high(-std::numeric_limits<double>::max());
  for (const glm::vec3& p : positions) {
    low = glm::min(low, glm::dvec3(p));
    high = glm::max(high, glm::dvec3(p));
  }
  view.center = 0.5 * (low + high);
  const double radius = 0.5 * glm::length(high - low);
  view.scale = radius > 0.0 ? kFramedFraction * 0.5 * std::min(width, height) / radius : 1.0;
  return view;
}

RasterImage RasterizeMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> colors,
                          std::span<const std::uint32_t> indices, const MeshView& view, glm::vec3 background) {
  assert(colors.size() == positions.size());
  RasterImage out{Image(view.width, view.height, background),
                  std::vector<std::uint8_t>(static_cast<std::size_t>(view.width) * view.height, 0)};
  std::vector<double> depth(out.covered.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
    assert(i0 < positions.size() && i1 < positions.size() && i2 < positions.size());
    const glm::dvec3 a = Project(view, positions[i0]), b = Project(view, positions[i1]), c = Project(view, positions[i2]);
    const double area = Edge(a, b, c.x, c.y);
    if (area == 0.0 || !std::isfinite(area)) continue;  // degenerate or edge-on
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(view.width - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(view.height - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Barycentric weights, each >= 0 inside for either winding.
        const double w0 = Edge(b, c, px, py) / area, w1 = Edge(c, a, px, py) / area, w2 = Edge(a, b, px, py) / area;
        if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
        const double z = w0 * a.z + w1 * b.z + w2 * c.z;
        const std::size_t pixel = static_cast<std::size_t>(y) * view.width + x;
        if (z <= depth[pixel]) continue;
        depth[pixel] = z;
        out.covered[pixel] = 1;
        out.color.pixels[pixel] = glm::vec3(w0 * glm::dvec3(colors[i0]) + w1 * glm::dvec3(colors[i1]) +
                                            w2 * glm::dvec3(colors[i2]));
      }
    }
  }
  return out;
}

}  // namespace vs11::irradiance
