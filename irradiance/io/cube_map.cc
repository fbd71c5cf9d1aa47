// Cube-map geometry: the D3D face table, texel directions, exact texel solid angles, and the
// inverse mapping from a direction to a face point. See cube_map.h for the table and the layout.
#include "irradiance/io/cube_map.h"

#include <cassert>
#include <cmath>

namespace vs11::irradiance {
namespace {

// Face coordinate (s or t) of the point `index` texels from the left (top) edge: maps [0, size]
// onto [-1, 1]. Texel x spans [x, x + 1]; its centre is x + 0.5.
double FaceCoordinate(double index, int size) { return 2.0 * index / size - 1.0; }

// Solid angle subtended, seen from the cube centre, by the rectangle of the face plane (distance 1)
// between the face centre and the corner (u, v): A(u, v) = atan2(u v, sqrt(u^2 + v^2 + 1)).
// Signed, so that the texel's solid angle is an inclusion-exclusion over its four corners.
double CornerArea(double u, double v) { return std::atan2(u * v, std::sqrt(u * u + v * v + 1.0)); }

}  // namespace

std::string_view CubeFaceName(CubeFace face) {
  switch (face) {
    case CubeFace::kPositiveX: return "+x";
    case CubeFace::kNegativeX: return "-x";
    case CubeFace::kPositiveY: return "+y";
    case CubeFace::kNegativeY: return "-y";
    case CubeFace::kPositiveZ: return "+z";
    case CubeFace::kNegativeZ: return "-z";
  }
  return "?";
}

CubeMap::CubeMap(int size, glm::vec3 fill) : face_size(size) {
  assert(size >= 0);
  for (Image& image : faces) image = Image(size, size, fill);
}

glm::dvec3 FaceDirection(CubeFace face, double s, double t) {
  switch (face) {
    case CubeFace::kPositiveX: return {1.0, -t, -s};
    case CubeFace::kNegativeX: return {-1.0, -t, s};
    case CubeFace::kPositiveY: return {s, 1.0, t};
    case CubeFace::kNegativeY: return {s, -1.0, -t};
    case CubeFace::kPositiveZ: return {s, -t, 1.0};
    case CubeFace::kNegativeZ: return {-s, -t, -1.0};
  }
  assert(false && "invalid CubeFace");
  return {0.0, 0.0, 0.0};
}

glm::dvec3 TexelDirection(CubeFace face, int x, int y, int size) {
  assert(size > 0 && x >= 0 && x < size && y >= 0 && y < size);
  const double s = FaceCoordinate(x + 0.5, size);
  const double t = FaceCoordinate(y + 0.5, size);
  return glm::normalize(FaceDirection(face, s, t));
}

std::vector<glm::dvec3> CubeTexelDirections(int size) {
  std::vector<glm::dvec3> directions;
  directions.reserve(static_cast<std::size_t>(kCubeFaceCount) * size * size);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) directions.push_back(TexelDirection(face, x, y, size));
    }
  }
  return directions;
}

double TexelCornerArea(int i, int j, int size) {
  assert(size > 0 && i >= 0 && i <= size && j >= 0 && j <= size);
  return CornerArea(FaceCoordinate(i, size), FaceCoordinate(j, size));
}

double TexelSolidAngle(int x, int y, int size) {
  assert(size > 0 && x >= 0 && x < size && y >= 0 && y < size);
  return TexelCornerArea(x + 1, y + 1, size) - TexelCornerArea(x, y + 1, size) - TexelCornerArea(x + 1, y, size) +
         TexelCornerArea(x, y, size);
}

FacePoint DirectionToFace(glm::dvec3 d) {
  const double ax = std::abs(d.x);
  const double ay = std::abs(d.y);
  const double az = std::abs(d.z);
  // Ties go to x, then y, then z (the order of the D3D face table). A zero (or NaN) direction has
  // no face; it lands on +x at the centre rather than dividing by zero.
  if (ax >= ay && ax >= az) {
    if (!(ax > 0.0)) return {CubeFace::kPositiveX, 0.0, 0.0};
    return d.x > 0.0 ? FacePoint{CubeFace::kPositiveX, -d.z / ax, -d.y / ax}
                     : FacePoint{CubeFace::kNegativeX, d.z / ax, -d.y / ax};
  }
  if (ay >= az) {
    return d.y > 0.0 ? FacePoint{CubeFace::kPositiveY, d.x / ay, d.z / ay}
                     : FacePoint{CubeFace::kNegativeY, d.x / ay, -d.z / ay};
  }
  return d.z > 0.0 ? FacePoint{CubeFace::kPositiveZ, d.x / az, -d.y / az}
                   : FacePoint{CubeFace::kNegativeZ, -d.x / az, -d.y / az};
}

}  // namespace vs11::irradiance
