// A picture like the paper's Fig. 3: a row of diffuse spheres lit by the same environment through
// different irradiance estimates, with a false-colour relative-error image under each estimate and
// the environment itself beside them.
//
//   exact          SH9 256x256     SH9 64x64       SH9 16x16       environment (tone-mapped)
//   ( sphere )     ( sphere )      ( sphere )      ( sphere )          +y
//   error scale    [error img]     [error img]     [error img]     -x  +z  +x  -z
//   |ramp| 0..5%   max, mean       max, mean       max, mean           -y
//
// Spheres: an orthographic view along -z (the camera sits on the +z axis and looks at the origin,
// +y up), one normal per pixel, albedo 1, so the displayed radiance is E(n) / pi. In the cube map's
// left-handed D3D frame (cube_map.h) the viewer then has +x on the left: the spheres show the side of
// the environment that lies behind the viewer, mirrored as a real sphere would be. One exposure for
// every sphere, scaled so that the brightest sphere pixel is kSphereWhite; sRGB-encoded on writing.
//
// This file only composes the image; the caller supplies the irradiance of every sphere pixel (the
// exact one may come from HemisphereGrid, which makes a brute-force integration affordable).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {

// The brightest sphere pixel is shown at this display value (linear, before sRGB encoding).
inline constexpr double kSphereWhite = 0.8;
// Smallest sphere the layout takes (smaller diameters are raised to it).
inline constexpr int kMinPreviewSphereDiameter = 16;
// Debian's fonts-dejavu-core; OpenImageIO's render_text needs a TrueType font.
inline constexpr const char* kDefaultPreviewFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// The pixels of a sphere of `diameter` pixels (>= 1) seen as described above. Pixel (x, y), row 0 at
// the top, has sx = 2 (x + 0.5) / D - 1, sy = 1 - 2 (y + 0.5) / D and, inside the disk,
//   normal = (-sx, sy, sqrt(1 - sx^2 - sy^2)).
// A pixel is covered when its centre is within half a pixel of the disk; `coverage` in [0, 1] is then
// an antialiasing weight from the distance to the rim, and its normal is taken on the rim's nearest
// point. Covered pixels are listed row by row.
struct SpherePixels {
  int diameter = 0;
  std::vector<glm::ivec2> pixels;    // (x, y) of each covered pixel
  std::vector<glm::dvec3> normals;   // unit normal of each covered pixel
  std::vector<float> coverage;       // in (0, 1]
};
SpherePixels MakeSpherePixels(int diameter);

// Irradiance tabulated on a grid of normals over the hemisphere facing +z (the half of the sphere the
// view above shows) and interpolated bilinearly: row i has polar angle i / (rows - 1) x 90 degrees
// from +z, column j azimuth j / columns x 360 degrees (wrapping), i.e. normals
//   (sin(theta) cos(phi), sin(theta) sin(phi), cos(theta)).
// Row 0 is the pole, where every column holds the same normal, so interpolation is continuous there.
// Normals below the equator read the equator. With the default 2 x 2.8 degree spacing the
// interpolation error of an irradiance map (a smooth function: the cosine lobe filters the
// environment) is ~1e-4 relative, far below the SH9 errors it is compared with.
class HemisphereGrid {
 public:
  static constexpr int kDefaultRows = 46;      // 2 degrees apart
  static constexpr int kDefaultColumns = 128;  // 2.8125 degrees apart
  // rows >= 2, columns >= 3 (asserted).
  explicit HemisphereGrid(int rows = kDefaultRows, int columns = kDefaultColumns);

  // The grid's normals, row by row: compute the irradiance at these and pass it to SetValues.
  const std::vector<glm::dvec3>& normals() const { return normals_; }
  // One value per normal (size asserted).
  void SetValues(std::vector<glm::dvec3> values);
  // Bilinear interpolation of the values at `normal` (need not be unit length, must not be zero).
  glm::dvec3 Sample(glm::dvec3 normal) const;

 private:
  int rows_;
  int columns_;
  std::vector<glm::dvec3> normals_;
  std::vector<glm::dvec3> values_;
};

// One sphere of the picture.
struct PreviewPanel {
  std::string label;                   // printed above the sphere
  std::vector<glm::dvec3> irradiance;  // E(n) per SpherePixels pixel, in the same order
};

struct PreviewOptions {
  int sphere_diameter = 192;  // pixels, >= kMinPreviewSphereDiameter
  std::filesystem::path font = kDefaultPreviewFont;
  int font_size = 15;  // pixels
};

// What the error row shows, computed by the report (report/preview_errors.h).
struct PreviewErrors {
  std::vector<std::vector<double>> per_pixel;  // per estimate, the error of each sphere pixel
  std::vector<std::string> captions;          // per estimate, printed under its error image
  std::string title = "relative error";       // printed above the colour ramp
  double scale = 0.0;  // the error shown at the top of the colour ramp, shared by every image
};

struct PreviewResult {
  Image image;  // linear display values in [0, 1]; WriteImage sRGB-encodes them for .png
  std::vector<std::string> warnings;  // e.g. the font is missing and labels were left out
  // Where each label was drawn (pixels, bottom and right exclusive), after a label too wide for its
  // column was drawn smaller: no two overlap. Empty when the labels were left out.
  struct PlacedLabel {
    std::string text;
    int left = 0, right = 0, top = 0, bottom = 0;
    int font_size = 0;
  };
  std::vector<PlacedLabel> labels;
};

// Image size for `panels` spheres (the truth included) with an environment thumbnail of `cross_face`
// pixels per face; `cross_face` is PreviewCrossFace(environment face size, options).
struct PreviewLayout {
  int width = 0;
  int height = 0;
  int cross_face = 0;
};
PreviewLayout ComputePreviewLayout(int panels, int environment_face_size, const PreviewOptions& options);

// Composes the picture. `sphere` comes from MakeSpherePixels(options.sphere_diameter); `truth` and
// each estimate hold one irradiance per sphere pixel, `errors` one entry per estimate (asserted).
// Label rendering failures (no font) are warnings, never errors.
PreviewResult RenderPreview(const SpherePixels& sphere, const PreviewPanel& truth,
                            std::span<const PreviewPanel> estimates, const PreviewErrors& errors,
                            const CubeMap& environment, const PreviewOptions& options = {});

// The colour ramp of the error images (viridis, 5 stops) at t in [0, 1] (clamped), linear RGB.
glm::vec3 ErrorRamp(double t);

// The environment as a horizontal cross of `cross_face` pixels per face: 2^k x 2^k box means when
// the cube is larger, pixel repetition when smaller (cross_face a multiple of the face size), tone
// mapped for display: exposure 1 / (mean luminance), then x / (1 + x) per channel.
Image EnvironmentThumbnail(const CubeMap& environment, int cross_face);

}  // namespace vs11::irradiance
