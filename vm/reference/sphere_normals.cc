// The Fibonacci sphere. See sphere_normals.h.
#include "vm/reference/sphere_normals.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vs11 {

std::vector<glm::dvec3> SphereNormals(int count) {
  std::vector<glm::dvec3> normals;
  if (count <= 0) return normals;
  normals.reserve(count);
  // The golden angle, pi (3 - sqrt 5): successive points turn by it around the y axis.
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - (2.0 * i + 1.0) / count;
    const double radius = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = golden_angle * i;
    normals.emplace_back(radius * std::cos(phi), y, radius * std::sin(phi));
  }
  return normals;
}

}  // namespace vs11
