// Cube maps in Direct3D's frame: +y up, the six faces in D3DCUBEMAP_FACES order, and each texel's
// direction exactly from D3D's face table (the same table OpenGL uses), with no extra rotation.
//
//   face      direction of texel (s, t), s = 2 (x + 0.5) / size - 1 (left to right),
//                                        t = 2 (y + 0.5) / size - 1 (top row to bottom row)
//   +x (0)    ( 1, -t, -s)
//   -x (1)    (-1, -t,  s)
//   +y (2)    ( s,  1,  t)
//   -y (3)    ( s, -1, -t)
//   +z (4)    ( s, -t,  1)
//   -z (5)    (-s, -t, -1)
//
// Laid out as a horizontal cross (the way cross files are read and written):
//            +y
//        -x  +z  +x  -z
//            -y
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace vs11::irradiance {

enum class CubeFace : int { kPositiveX = 0, kNegativeX, kPositiveY, kNegativeY, kPositiveZ, kNegativeZ };
inline constexpr int kCubeFaceCount = 6;

// Whether `n` is a power of two (1, 2, 4, ...): the face sizes a mip pyramid halves down to 1x1.
constexpr bool IsPowerOfTwo(int n) { return n > 0 && std::has_single_bit(static_cast<unsigned>(n)); }
inline constexpr std::array<CubeFace, kCubeFaceCount> kAllCubeFaces = {
    CubeFace::kPositiveX, CubeFace::kNegativeX, CubeFace::kPositiveY,
    CubeFace::kNegativeY, CubeFace::kPositiveZ, CubeFace::kNegativeZ};
std::string_view CubeFaceName(CubeFace face);  // "+x", "-x", ...

// Linear RGB radiance, row-major, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;

  Image() = default;
  Image(int w, int h, glm::vec3 fill = glm::vec3(0.0f))
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}
  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

struct CubeMap {
  int face_size = 0;
  std::array<Image, kCubeFaceCount> faces;

  CubeMap() = default;
  explicit CubeMap(int size, glm::vec3 fill = glm::vec3(0.0f));
  Image& face(CubeFace f) { return faces[static_cast<int>(f)]; }
  const Image& face(CubeFace f) const { return faces[static_cast<int>(f)]; }
};

struct TexelCoord {
  CubeFace face;
  int x;
  int y;
};

// Unnormalised direction for face coordinates s, t in [-1, 1] (the table above).
glm::dvec3 FaceDirection(CubeFace face, double s, double t);
// Unit direction through the centre of texel (x, y) of a face of `size` texels.
glm::dvec3 TexelDirection(CubeFace face, int x, int y, int size);
// TexelDirection of every texel of a size^3 cube map, in CubeFace, row, column order.
std::vector<glm::dvec3> CubeTexelDirections(int size);
// Exact solid angle of texel (x, y) (the same for every face), closed form
//   A(u, v) = atan2(u v, sqrt(u^2 + v^2 + 1)) summed over the texel's corners; the six faces add to 4 pi.
double TexelSolidAngle(int x, int y, int size);
// A(u, v) at corner (i, j) of a face of `size` (0 <= i, j <= size: u, v = 2 i / size - 1, 2 j / size - 1).
// TexelSolidAngle(x, y, size) is exactly
//   TexelCornerArea(x + 1, y + 1) - TexelCornerArea(x, y + 1) - TexelCornerArea(x + 1, y) + TexelCornerArea(x, y)
// added in that order, so a table of corner areas gives its bits with one atan2 per texel instead of four.
double TexelCornerArea(int i, int j, int size);
// The face a direction lands on and its (s, t) there; the inverse of FaceDirection.
struct FacePoint {
  CubeFace face;
  double s;
  double t;
};
FacePoint DirectionToFace(glm::dvec3 direction);

}  // namespace vs11::irradiance
