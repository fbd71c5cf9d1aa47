// The Fig. 3-like preview picture. See preview.h.
#include "irradiance/render/preview.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/image_io_module.h"

namespace vs11::irradiance {
namespace {

// Layout, in pixels (see the sketch in preview.h).
constexpr int kMargin = 16;
constexpr int kRowGap = 12;            // between the sphere row and the error row
constexpr int kLabelPad = 8;           // label height = font size + this
constexpr int kRampWidth = 20;         // the colour bar of the error scale
constexpr int kTickLength = 4;
constexpr float kTextValue = 0.9f;     // label grey (linear)
constexpr float kOutlineValue = 0.03f;  // the least value of the thumbnail's cell borders (linear)

// Viridis at t = 0, 1/4, 1/2, 3/4, 1 (sRGB 8-bit: #440154 #3b528b #21918c #5ec962 #fde725).
constexpr std::array<std::array<int, 3>, 5> kViridisSrgb = {
    {{0x44, 0x01, 0x54}, {0x3b, 0x52, 0x8b}, {0x21, 0x91, 0x8c}, {0x5e, 0xc9, 0x62}, {0xfd, 0xe7, 0x25}}};
constexpr double kByteMax = 255.0;

// Rec. 709 luminance weights (linear RGB).
constexpr glm::dvec3 kLuminance{0.2126, 0.7152, 0.0722};

constexpr int kMinFontSize = 8;         // a label too wide for its column shrinks down to this

struct Label {
  int x = 0;
  int y = 0;  // baseline
  std::string text;
  bool centred = false;
  int max_width = 0;  // > 0: the text is drawn smaller until it fits (its column's width)
};

int LabelHeight(const PreviewOptions& options) { return options.font_size + kLabelPad; }

// The smallest divisor-friendly face size for the thumbnail: a whole fraction of the face size (box
// filtered) when the face is larger than `target`, a whole multiple (repeated) when smaller.
int CrossFaceFor(int face_size, int target) {
  if (face_size <= 0) return std::max(target, 1);
  if (face_size <= target) return face_size * (target / face_size);
  for (int factor = (face_size + target - 1) / target; factor <= face_size; ++factor) {
    if (face_size % factor == 0) return face_size / factor;
  }
  return 1;
}

std::string Percent(double fraction) {
  const double percent = fraction * 100.0;
  return percent >= 100.0 ? fmt::format("{:.0f}%", percent) : fmt::format("{:.3g}%", percent);
}

void Blit(const Image& source, Image& target, int x0, int y0) {
  for (int y = 0; y < source.height; ++y) {
    for (int x = 0; x < source.width; ++x) {
      if (x0 + x >= 0 && x0 + x < target.width && y0 + y >= 0 && y0 + y < target.height) {
        target.at(x0 + x, y0 + y) = source.at(x, y);
      }
    }
  }
}

// Lifts the border pixels of the six face cells of a horizontal cross at (x0, y0) to at least
// kOutlineValue, so that the layout shows even where the environment is black.
void OutlineCrossCells(Image& image, int x0, int y0, int cell) {
  constexpr std::array<glm::ivec2, kCubeFaceCount> kCells = {
      {{1, 0}, {0, 1}, {1, 1}, {2, 1}, {3, 1}, {1, 2}}};  // column, row of each face cell
  auto lift = [&](int x, int y) {
    if (x < 0 || x >= image.width || y < 0 || y >= image.height) return;
    image.at(x, y) = glm::max(image.at(x, y), glm::vec3(kOutlineValue));
  };
  for (const glm::ivec2& c : kCells) {
    const int left = x0 + c.x * cell;
    const int top = y0 + c.y * cell;
    for (int i = 0; i < cell; ++i) {
      lift(left + i, top);
      lift(left + i, top + cell - 1);
      lift(left, top + i);
      lift(left + cell - 1, top + i);
    }
  }
}

// Draws the labels with OpenImageIO (its module, image_io_module.h), each shrunk to its max_width,
// and records where they went; returns a warning when that is not possible.
std::optional<std::string> DrawLabels(Image& image, const std::vector<Label>& labels,
                                      const PreviewOptions& options,
                                      std::vector<PreviewResult::PlacedLabel>& placed) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.font, ec)) {
    return fmt::format("preview: font {} not found, labels left out (install fonts-dejavu-core)",
                       options.font.string());
  }
  const Result<const ImageIoApi*> module = ImageIo();
  if (!module) return fmt::format("preview: {}; labels left out", module.message());
  const ImageIoApi* image_io = *module;
  const std::string font = options.font.string();
  Image canvas = image;  // a failed label leaves the image without any
  for (const Label& label : labels) {
    int size = options.font_size;
    std::string text = label.text;
    std::optional<TextBox> box = image_io->text_size(text, size, font);
    auto too_wide = [&] { return label.max_width > 0 && box && box->width() > label.max_width; };
    while (too_wide() && size > kMinFontSize) box = image_io->text_size(text, --size, font);
    // Still too wide at the smallest size (tiny spheres): shortened with "..", keeping a trailing
    // " *" (the chosen level's mark).
    const std::string mark = text.ends_with(" *") ? " *" : "";
    std::string stem = text.substr(0, text.size() - mark.size());
    while (too_wide() && !stem.empty()) {
      stem.pop_back();
      text = stem + ".." + mark;
      box = image_io->text_size(text, size, font);
    }
    const std::optional<std::string> failure =
        image_io->render_text(canvas, label.x, label.y, text, size, font, kTextValue, label.centred);
    if (box) {
      const int left = label.centred ? label.x - box->width() / 2 : label.x + box->xbegin;
      placed.push_back({text, left, left + box->width(), label.y + box->ybegin, label.y + box->yend, size});
    }
    if (failure) {
      return fmt::format("preview: cannot draw text with font {} ({}), labels left out", font, *failure);
    }
  }
  image = std::move(canvas);
  return std::nullopt;
}

}  // namespace

SpherePixels MakeSpherePixels(int diameter) {
  assert(diameter >= 1);
  SpherePixels sphere;
  sphere.diameter = diameter;
  const double half = 0.5 * diameter;
  for (int y = 0; y < diameter; ++y) {
    for (int x = 0; x < diameter; ++x) {
      const double sx = 2.0 * (x + 0.5) / diameter - 1.0;
      const double sy = 1.0 - 2.0 * (y + 0.5) / diameter;
      const double r = std::sqrt(sx * sx + sy * sy);
      // Signed distance from the rim in pixels (positive inside); a pixel is one unit wide.
      const double inside = (1.0 - r) * half;
      if (inside <= -0.5) continue;
      const double coverage = std::clamp(inside + 0.5, 0.0, 1.0);
      const double scale = r > 1.0 ? 1.0 / r : 1.0;
      const double nx = sx * scale;
      const double ny = sy * scale;
      const double nz = std::sqrt(std::max(0.0, 1.0 - nx * nx - ny * ny));
      sphere.pixels.emplace_back(x, y);
      sphere.normals.push_back(glm::normalize(glm::dvec3(-nx, ny, nz)));
      sphere.coverage.push_back(static_cast<float>(coverage));
    }
  }
  return sphere;
}

HemisphereGrid::HemisphereGrid(int rows, int columns) : rows_(rows), columns_(columns) {
  assert(rows >= 2 && columns >= 3);
  normals_.reserve(static_cast<std::size_t>(rows) * columns);
  for (int i = 0; i < rows; ++i) {
    const double theta = 0.5 * std::numbers::pi * i / (rows - 1);
    for (int j = 0; j < columns; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / columns;
      normals_.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                            std::cos(theta));
    }
  }
}

void HemisphereGrid::SetValues(std::vector<glm::dvec3> values) {
  assert(values.size() == normals_.size());
  values_ = std::move(values);
}

glm::dvec3 HemisphereGrid::Sample(glm::dvec3 normal) const {
  assert(values_.size() == normals_.size());
  const glm::dvec3 n = glm::normalize(normal);
  const double theta = std::acos(std::clamp(n.z, 0.0, 1.0));
  double phi = std::atan2(n.y, n.x);
  if (phi < 0.0) phi += 2.0 * std::numbers::pi;
  const double fi = std::min(theta / (0.5 * std::numbers::pi) * (rows_ - 1), rows_ - 1.0);
  const double fj = phi / (2.0 * std::numbers::pi) * columns_;
  const int i0 = std::min(static_cast<int>(fi), rows_ - 2);
  const int j0 = static_cast<int>(fj) % columns_;
  const int j1 = (j0 + 1) % columns_;
  const double a = fi - i0;
  const double b = fj - std::floor(fj);
  auto value = [&](int i, int j) { return values_[static_cast<std::size_t>(i) * columns_ + j]; };
  const glm::dvec3 upper = value(i0, j0) * (1.0 - b) + value(i0, j1) * b;
  const glm::dvec3 lower = value(i0 + 1, j0) * (1.0 - b) + value(i0 + 1, j1) * b;
  return upper * (1.0 - a) + lower * a;
}

glm::vec3 ErrorRamp(double t) {
  const double position = std::clamp(t, 0.0, 1.0) * (kViridisSrgb.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(position), kViridisSrgb.size() - 2);
  const double f = position - static_cast<double>(i);
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const double a = kViridisSrgb[i][c] / kByteMax;
    const double b = kViridisSrgb[i + 1][c] / kByteMax;
    out[c] = static_cast<float>(SrgbToLinear(a + (b - a) * f));  // interpolated in sRGB
  }
  return out;
}

Image EnvironmentThumbnail(const CubeMap& environment, int cross_face) {
  const int n = environment.face_size;
  assert(n > 0 && cross_face > 0);
  assert(cross_face % n == 0 || n % cross_face == 0);
  CubeMap small(cross_face);
  for (CubeFace face : kAllCubeFaces) {
    const Image& source = environment.face(face);
    Image& target = small.face(face);
    if (cross_face <= n) {
      const int block = n / cross_face;
      for (int y = 0; y < cross_face; ++y) {
        for (int x = 0; x < cross_face; ++x) {
          glm::dvec3 sum(0.0);
          for (int dy = 0; dy < block; ++dy) {
            for (int dx = 0; dx < block; ++dx) sum += glm::dvec3(source.at(x * block + dx, y * block + dy));
          }
          target.at(x, y) = glm::vec3(sum / static_cast<double>(block * block));
        }
      }
    } else {
      const int repeat = cross_face / n;
      for (int y = 0; y < cross_face; ++y) {
        for (int x = 0; x < cross_face; ++x) target.at(x, y) = source.at(x / repeat, y / repeat);
      }
    }
  }
  double luminance_sum = 0.0;
  std::size_t count = 0;
  for (const Image& face : small.faces) {
    for (const glm::vec3& p : face.pixels) {
      luminance_sum += glm::dot(glm::dvec3(p), kLuminance);
      ++count;
    }
  }
  const double mean = count > 0 ? luminance_sum / static_cast<double>(count) : 0.0;
  const double exposure = mean > 0.0 ? 1.0 / mean : 1.0;
  for (Image& face : small.faces) {
    for (glm::vec3& p : face.pixels) {
      const glm::dvec3 x = glm::dvec3(p) * exposure;
      p = glm::vec3(x / (1.0 + x));
    }
  }
  return CubeMapToImage(small, EnvironmentLayout::kHorizontalCross);
}

PreviewLayout ComputePreviewLayout(int panels, int environment_face_size, const PreviewOptions& options) {
  const int s = std::max(options.sphere_diameter, kMinPreviewSphereDiameter);
  const int label = LabelHeight(options);
  PreviewLayout layout;
  // The cross spans the height of both rows below the first label row.
  layout.cross_face = CrossFaceFor(environment_face_size, (2 * s + kRowGap + label) / 3);
  layout.width = kMargin + panels * (s + kMargin) + 4 * layout.cross_face + kMargin;
  layout.height = kMargin + 2 * label + 2 * s + kRowGap + kMargin;
  return layout;
}

namespace {

// The factor from radiance to the preview's pixel values: E / pi is the radiance of a white diffuse
// surface, and the brightest pixel of any sphere is shown at kSphereWhite.
double SphereExposure(const PreviewPanel& truth, std::span<const PreviewPanel> estimates) {
  double brightest = 0.0;
  auto note_brightest = [&](const std::vector<glm::dvec3>& irradiance) {
    for (const glm::dvec3& e : irradiance) brightest = std::max({brightest, e.x, e.y, e.z});
  };
  note_brightest(truth.irradiance);
  for (const PreviewPanel& panel : estimates) {
    assert(panel.irradiance.size() == truth.irradiance.size());
    note_brightest(panel.irradiance);
  }
  const double radiance_max = brightest / std::numbers::pi;
  return radiance_max > 0.0 ? kSphereWhite / radiance_max : 1.0;
}

}  // namespace

PreviewResult RenderPreview(const SpherePixels& sphere, const PreviewPanel& truth,
                            std::span<const PreviewPanel> estimates, const PreviewErrors& errors,
                            const CubeMap& environment, const PreviewOptions& options) {
  assert(sphere.diameter == std::max(options.sphere_diameter, kMinPreviewSphereDiameter));
  assert(errors.per_pixel.size() == estimates.size() && errors.captions.size() == estimates.size());
  assert(truth.irradiance.size() == sphere.normals.size());
  const int s = sphere.diameter;
  const int label_height = LabelHeight(options);
  const int panels = 1 + static_cast<int>(estimates.size());
  const PreviewLayout layout = ComputePreviewLayout(panels, environment.face_size, options);
  PreviewResult result;
  result.image = Image(layout.width, layout.height);
  Image& image = result.image;
  std::vector<Label> labels;

  const int sphere_top = kMargin + label_height;
  const int error_top = sphere_top + s + kRowGap + label_height;
  auto column_left = [&](int panel) { return kMargin + panel * (s + kMargin); };
  auto label_baseline = [&](int top) { return top - kLabelPad / 2 - 2; };
  const int column_width = s + kMargin - 2;  // a label's room: its sphere and the gap, less a little

  const double exposure = SphereExposure(truth, estimates);

  auto draw_sphere = [&](const PreviewPanel& panel, int panel_index) {
    const int left = column_left(panel_index);
    for (std::size_t k = 0; k < sphere.pixels.size(); ++k) {
      const glm::dvec3 radiance = glm::max(panel.irradiance[k], glm::dvec3(0.0)) / std::numbers::pi;
      image.at(left + sphere.pixels[k].x, sphere_top + sphere.pixels[k].y) =
          glm::vec3(radiance * exposure * static_cast<double>(sphere.coverage[k]));
    }
    labels.push_back({left + s / 2, label_baseline(sphere_top), panel.label, true, column_width});
  };
  draw_sphere(truth, 0);
  for (std::size_t p = 0; p < estimates.size(); ++p) draw_sphere(estimates[p], static_cast<int>(p) + 1);

  for (std::size_t p = 0; p < estimates.size(); ++p) {
    const int left = column_left(static_cast<int>(p) + 1);
    for (std::size_t k = 0; k < sphere.pixels.size(); ++k) {
      image.at(left + sphere.pixels[k].x, error_top + sphere.pixels[k].y) =
          ErrorRamp(errors.per_pixel[p][k] / errors.scale) * sphere.coverage[k];
    }
    labels.push_back({left + s / 2, label_baseline(error_top), errors.captions[p], true, column_width});
  }

  // The colour ramp of the error scale, under the exact sphere: top = the scale, bottom = 0.
  if (!estimates.empty()) {
    const int ramp_left = column_left(0) + s / 4;
    for (int y = 0; y < s; ++y) {
      const glm::vec3 colour = ErrorRamp(1.0 - (y + 0.5) / s);
      for (int x = 0; x < kRampWidth; ++x) image.at(ramp_left + x, error_top + y) = colour;
    }
    const int tick_left = ramp_left + kRampWidth;
    const std::array<double, 3> ticks = {0.0, 0.5, 1.0};
    for (double tick : ticks) {
      const int y = std::min(error_top + static_cast<int>(std::lround((1.0 - tick) * s)), error_top + s - 1);
      for (int x = 0; x < kTickLength; ++x) image.at(tick_left + x, y) = glm::vec3(kTextValue);
      // The top tick's text stays below the ramp's top, clear of the "relative error" title.
      const int baseline = std::max(y + options.font_size / 3, error_top + options.font_size);
      labels.push_back({tick_left + kTickLength + 4, baseline, Percent(tick * errors.scale), false,
                        column_left(1) - (tick_left + kTickLength + 4) - 2});
    }
    labels.push_back({column_left(0) + s / 2, label_baseline(error_top), errors.title, true, column_width});
  }

  // The environment.
  const int cross_left = column_left(panels);
  Blit(EnvironmentThumbnail(environment, layout.cross_face), image, cross_left, sphere_top);
  OutlineCrossCells(image, cross_left, sphere_top, layout.cross_face);
  labels.push_back({cross_left, label_baseline(sphere_top), "environment (tone-mapped)", false,
                    4 * layout.cross_face});

  if (std::optional<std::string> warning = DrawLabels(image, labels, options, result.labels)) {
    result.warnings.push_back(std::move(*warning));
    result.labels.clear();
  }
  return result;
}

}  // namespace vs11::irradiance
