// The preview rasterizer on cases worked out by hand.
#include "irradiance/render/mesh_raster.h"

#include <vector>

#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

// Looking down -z with one world unit per pixel: screen (x, y) = (8 + wx, 8 - wy), depth = wz.
MeshView StraightView() {
  MeshView view;
  view.width = 16;
  view.height = 16;
  return view;
}

TEST(MeshRaster, InterpolatesVertexColoursAndCoversTheInside) {
  // A right triangle with corners at pixels (0, 16), (16, 16), (0, 0) on screen: pixel centres with
  // x + y < 16 (0-based, centre at +0.5) on the lower-left side are inside.
  const std::vector<glm::vec3> positions = {{-8, -8, 0}, {8, -8, 0}, {-8, 8, 0}};
  const std::vector<glm::vec3> colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  RasterImage image = RasterizeMesh(positions, colors, indices, StraightView(), glm::vec3(0.25f));
  int covered = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const bool inside = (x + 0.5) <= (y + 0.5);  // below the diagonal from (0, 0) to (16, 16)
      EXPECT_EQ(image.covered[y * 16 + x], inside ? 1 : 0) << x << "," << y;
      covered += inside;
      if (!inside) {
        EXPECT_EQ(image.color.at(x, y), glm::vec3(0.25f));
      }
    }
  }
  EXPECT_EQ(covered, 136);
  // Pixel (2, 13): centre (2.5, 13.5) = world (-5.5, -5.5): weights red 0.6875 - ..., by hand:
  // world = r0 + s (r1 - r0) + t (r2 - r0) with s = 2.5 / 16, t = 2.5 / 16.
  const glm::vec3 c = image.color.at(2, 13);
  EXPECT_NEAR(c.g, 2.5 / 16, 1e-6);
  EXPECT_NEAR(c.b, 2.5 / 16, 1e-6);
  EXPECT_NEAR(c.r, 1 - 5.0 / 16, 1e-6);
}

TEST(MeshRaster, NearerTriangleWinsWhateverTheDrawOrder) {
  const std::vector<glm::vec3> positions = {{-8, -8, 1}, {8, -8, 1}, {0, 8, 1}, {-8, -8, -1}, {8, -8, -1}, {0, 8, -1}};
  const std::vector<glm::vec3> colors = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  for (const std::vector<std::uint32_t>& indices : {std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5},
                                                    std::vector<std::uint32_t>{3, 4, 5, 0, 1, 2}}) {
    RasterImage image = RasterizeMesh(positions, colors, indices, StraightView(), glm::vec3(0.0f));
    EXPECT_EQ(image.color.at(8, 10), glm::vec3(1, 0, 0));  // z = 1 is nearer the viewer at +z
  }
}

TEST(MeshRaster, FramingKeepsEveryVertexInThePicture) {
  const std::vector<glm::vec3> positions = {{100, 5, -3}, {140, 60, 7}, {90, -20, 30}, {120, 0, 0}};
  MeshView view = FrameBoundingBox(positions, 64, 48);
  for (const glm::vec3& p : positions) {
    glm::dvec3 camera = view.rotation * (glm::dvec3(p) - view.center);
    const double x = view.scale * camera.x + 32, y = 24 - view.scale * camera.y;
    EXPECT_GT(x, 0);
    EXPECT_LT(x, 64);
    EXPECT_GT(y, 0);
    EXPECT_LT(y, 48);
  }
}

}  // namespace
}  // namespace vs11::irradiance
