// The resamplers and direction conventions of environment_io.h: lat-long and angular maps to a
// cube map with their energy kept, and bilinear cube lookups.
#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "vm/core/thread_pool.h"

namespace vs11::irradiance {
namespace {

// (See the header: cubic B-spline reconstruction, widened in azimuth near the lat-long poles.)

// Cubic B-spline: support (-2, 2), integral 1, and its integer shifts sum to 1.
double CubicBSpline(double x) {
  x = std::abs(x);
  if (x < 1.0) return (4.0 - 6.0 * x * x + 3.0 * x * x * x) / 6.0;
  if (x < 2.0) return (2.0 - x) * (2.0 - x) * (2.0 - x) / 6.0;
  return 0.0;
}

// Weights of the taps floor(f) - 1 .. floor(f) + 2 for t = f - floor(f).
std::array<double, 4> CubicBSplineWeights(double t) {
  const double u = 1.0 - t;
  const double t2 = t * t;
  const double t3 = t2 * t;
  return {u * u * u / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
          (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, t3 / 6.0};
}

// The azimuthal kernel's scale (a quarter of its support) is at least this many point spacings.
constexpr double kKernelScalePerSampleSpacing = 2.0;

// Reconstructs a lat-long map at any direction: cubic B-spline in both axes, wrapping in azimuth
// and continuing over the poles (row -1 is row 0 half a turn round), widened in azimuth where the
// points a texel is sampled with (`sample_step` radians apart) are sparser than the pixels.
class LatLongSampler {
 public:
  LatLongSampler(const Image& image, double sample_step)
      : image_(image), sample_step_(sample_step) {
    row_means_.resize(image.height, glm::dvec3(0.0));
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) row_means_[y] += glm::dvec3(image.at(x, y));
      row_means_[y] /= image.width;
    }
  }

  // `direction` is a unit vector.
  glm::dvec3 operator()(glm::dvec3 direction) const {
    const int width = image_.width;
    const int height = image_.height;
    const double sin_theta = std::sqrt(direction.x * direction.x + direction.z * direction.z);
    const double u = std::atan2(direction.x, direction.z) / (2.0 * std::numbers::pi) + 0.5;
    const double v = std::acos(std::clamp(direction.y, -1.0, 1.0)) / std::numbers::pi;
    const double fx = u * width - 0.5;
    const double fy = v * height - 0.5;
    const double row_floor = std::floor(fy);
    const std::array<double, 4> row_weights = CubicBSplineWeights(fy - row_floor);

    // Azimuthal spacing of the points in pixels, and the kernel scale it asks for. A scale between
    // two integers blends their kernels, so that the reconstruction stays continuous in theta; an
    // integer scale keeps the partition of unity and every scale keeps each pixel's mass.
    const double spacing =
        sample_step_ * width / (2.0 * std::numbers::pi * std::max(sin_theta, 1e-12));
    const double wanted_scale = std::max(1.0, kKernelScalePerSampleSpacing * spacing);
    const bool whole_row = 4.0 * (std::floor(wanted_scale) + 1.0) >= width;
    std::vector<std::pair<int, double>>& columns = ColumnScratch();
    columns.clear();
    if (!whole_row && wanted_scale == 1.0) {
      const double column_floor = std::floor(fx);
      const std::array<double, 4> weights = CubicBSplineWeights(fx - column_floor);
      for (int k = 0; k < 4; ++k)
        columns.emplace_back(static_cast<int>(column_floor) - 1 + k, weights[k]);
    } else if (!whole_row) {
      const int scale = static_cast<int>(wanted_scale);
      const double blend = wanted_scale - scale;
      const int first = static_cast<int>(std::floor(fx - 2.0 * (scale + 1))) + 1;
      const int last = static_cast<int>(std::ceil(fx + 2.0 * (scale + 1))) - 1;
      for (int x = first; x <= last; ++x) {
        const double weight = (1.0 - blend) * CubicBSpline((fx - x) / scale) / scale +
                              blend * CubicBSpline((fx - x) / (scale + 1)) / (scale + 1);
        columns.emplace_back(x, weight);
      }
    }
    // Wrap once: the taps lie within (-width / 2, 3 width / 2) since 4 scale < width.
    for (auto& [column, weight] : columns) {
      if (column < 0) column += width;
      if (column >= width) column -= width;
    }

    glm::dvec3 sum(0.0);
    for (int k = 0; k < 4; ++k) {
      int row = static_cast<int>(row_floor) - 1 + k;
      int shift = 0;
      if (row < 0) {
        row = -row - 1;
        shift = width / 2;
      } else if (row >= height) {
        row = 2 * height - row - 1;
        shift = width / 2;
      }
      row = std::clamp(row, 0, height - 1);  // only for maps under two rows high
      glm::dvec3 row_value(0.0);
      if (whole_row) {
        row_value = row_means_[row];
      } else {
        const glm::vec3* pixels = &image_.pixels[static_cast<std::size_t>(row) * width];
        for (const auto& [column, weight] : columns) {
          int x = column + shift;
          if (x >= width) x -= width;
          row_value += weight * glm::dvec3(pixels[x]);
        }
      }
      sum += row_weights[k] * row_value;
    }
    return sum;
  }

 private:
  const Image& image_;
  double sample_step_;
  std::vector<glm::dvec3> row_means_;

  // The taps of one lookup: scratch reused between calls, one per thread (GatherCube runs lookups
  // on every core).
  static std::vector<std::pair<int, double>>& ColumnScratch() {
    thread_local std::vector<std::pair<int, double>> columns;
    return columns;
  }
};

constexpr int kMinHalvedHeight = 128;

// Halves a lat-long map, each new pixel the solid-angle-weighted mean of its 2 x 2 pixels (row
// weights cos(theta_top) - cos(theta_bottom)), so that the map's integral does not change.
Image HalveLatLong(const Image& image) {
  Image half(image.width / 2, image.height / 2);
  const auto row_weight = [&](int y) {
    return std::cos(std::numbers::pi * y / image.height) -
           std::cos(std::numbers::pi * (y + 1) / image.height);
  };
  for (int y = 0; y < half.height; ++y) {
    const double top = row_weight(2 * y);
    const double bottom = row_weight(2 * y + 1);
    const double norm = 1.0 / (2.0 * (top + bottom));
    for (int x = 0; x < half.width; ++x) {
      const glm::dvec3 sum =
          top * (glm::dvec3(image.at(2 * x, 2 * y)) + glm::dvec3(image.at(2 * x + 1, 2 * y))) +
          bottom *
              (glm::dvec3(image.at(2 * x, 2 * y + 1)) + glm::dvec3(image.at(2 * x + 1, 2 * y + 1)));
      half.at(x, y) = glm::vec3(sum * norm);
    }
  }
  return half;
}

// Pixel (x, y) of an n x n angular map has its centre inside the unit disk.
bool InsideDisk(int x, int y, int n) {
  const double a = 2.0 * (x + 0.5) / n - 1.0;
  const double b = 1.0 - 2.0 * (y + 0.5) / n;
  return a * a + b * b <= 1.0;
}

// Cubic B-spline lookup of an angular map over the taps whose centre lies in the disk (weights
// renormalised when some are left out, near the rim); if none does, the nearest pixel.
glm::dvec3 SampleAngular(const Image& image, glm::dvec3 direction) {
  const int n = image.width;
  const glm::dvec2 ab = DirectionToAngular(direction);
  const double fx = (ab.x + 1.0) * 0.5 * n - 0.5;
  const double fy = (1.0 - ab.y) * 0.5 * n - 0.5;
  const double x_floor = std::floor(fx);
  const double y_floor = std::floor(fy);
  const std::array<double, 4> wx = CubicBSplineWeights(fx - x_floor);
  const std::array<double, 4> wy = CubicBSplineWeights(fy - y_floor);
  glm::dvec3 sum(0.0);
  // Every tap is within 2 sqrt(2) pixels (4 sqrt(2) / n) of the point: inside the disk if the point
  // is that far from the rim.
  const double rim_margin = 1.0 - 4.0 * std::numbers::sqrt2 / n;
  if (rim_margin > 0.0 && ab.x * ab.x + ab.y * ab.y < rim_margin * rim_margin) {
    for (int j = 0; j < 4; ++j) {
      const glm::vec3* row = &image.pixels[static_cast<std::size_t>(y_floor - 1 + j) * n];
      glm::dvec3 row_sum(0.0);
      for (int i = 0; i < 4; ++i)
        row_sum += wx[i] * glm::dvec3(row[static_cast<int>(x_floor) - 1 + i]);
      sum += wy[j] * row_sum;
    }
    return sum;
  }
  double weight_sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int y = static_cast<int>(y_floor) - 1 + j;
    if (y < 0 || y >= n) continue;
    for (int i = 0; i < 4; ++i) {
      const int x = static_cast<int>(x_floor) - 1 + i;
      if (x < 0 || x >= n || !InsideDisk(x, y, n)) continue;
      sum += wx[i] * wy[j] * glm::dvec3(image.at(x, y));
      weight_sum += wx[i] * wy[j];
    }
  }
  constexpr double kFullWeight = 1.0 - 1e-12;
  if (weight_sum >= kFullWeight) return sum;
  if (weight_sum > 0.0) return sum / weight_sum;
  const int x = std::clamp(static_cast<int>(std::lround(fx)), 0, n - 1);
  const int y = std::clamp(static_cast<int>(std::lround(fy)), 0, n - 1);
  return glm::dvec3(image.at(x, y));
}

// Gathers `lookup(direction)` over each texel's footprint with n x n points weighted by their solid
// angle, dw = ds dt / (1 + s^2 + t^2)^(3/2); n = samples(texel centre direction).
template <class Lookup, class Samples>
CubeMap GatherCube(int face_size, const Samples& samples_for, const Lookup& lookup) {
  CubeMap cube(face_size);
  const double texel = 2.0 / face_size;
  // Rows of all faces are independent: every thread of the process's pool (one per core) takes the
  // next row left (the result does not depend on the order).
  std::atomic<int> next_row = 0;
  const int rows = kCubeFaceCount * face_size;
  auto work = [&] {
    for (int row = next_row++; row < rows; row = next_row++) {
      const CubeFace face = kAllCubeFaces[static_cast<std::size_t>(row / face_size)];
      const int y = row % face_size;
      Image& out = cube.face(face);
      for (int x = 0; x < face_size; ++x) {
        const int samples = samples_for(TexelDirection(face, x, y, face_size));
        const double step = texel / samples;
        glm::dvec3 sum(0.0);
        double weight_sum = 0.0;
        for (int j = 0; j < samples; ++j) {
          const double t = -1.0 + texel * y + step * (j + 0.5);
          for (int i = 0; i < samples; ++i) {
            const double s = -1.0 + texel * x + step * (i + 0.5);
            const double d = 1.0 + s * s + t * t;
            const double inv_length = 1.0 / std::sqrt(d);
            const double weight = inv_length / d;
            sum += weight * lookup(FaceDirection(face, s, t) * inv_length);
            weight_sum += weight;
          }
        }
        out.at(x, y) = glm::vec3(sum / weight_sum);
      }
    }
  };
  ThreadPool& pool = ThreadPool::Default();
  const int threads = std::min(pool.threads(), rows);
  pool.Run(static_cast<std::size_t>(threads), threads, [&work](std::size_t, int) { work(); });
  return cube;
}

// Points per texel side so that there are kResampleSamplesPerSourcePixel per source pixel pitch
// (radians) across the largest texel, 2 / face_size radians wide at the face centre.
int SamplesPerTexel(int face_size, double source_pitch) {
  const double texel_angle = 2.0 / face_size;
  const double wanted = std::ceil(kResampleSamplesPerSourcePixel * texel_angle / source_pitch);
  return static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(kMaxResampleSamples)));
}

}  // namespace

glm::dvec3 LatLongDirection(double u, double v) {
  const double phi = 2.0 * std::numbers::pi * (u - 0.5);
  const double theta = std::numbers::pi * v;
  return {std::sin(phi) * std::sin(theta), std::cos(theta), std::cos(phi) * std::sin(theta)};
}

glm::dvec2 DirectionToLatLong(glm::dvec3 direction) {
  const double length = glm::length(direction);
  if (!(length > 0.0)) return {0.5, 0.5};
  const double theta = std::acos(std::clamp(direction.y / length, -1.0, 1.0));
  double u = std::atan2(direction.x, direction.z) / (2.0 * std::numbers::pi) + 0.5;
  if (u >= 1.0) u -= 1.0;
  return {u, theta / std::numbers::pi};
}

glm::dvec3 AngularDirection(double a, double b) {
  const double r = std::sqrt(a * a + b * b);
  if (r == 0.0) return {0.0, 0.0, 1.0};
  const double theta = std::numbers::pi * r;
  const double scale = std::sin(theta) / r;
  return {a * scale, b * scale, std::cos(theta)};
}

glm::dvec2 DirectionToAngular(glm::dvec3 direction) {
  const double length = glm::length(direction);
  if (!(length > 0.0)) return {0.0, 0.0};
  const glm::dvec3 d = direction / length;
  const double r = std::acos(std::clamp(d.z, -1.0, 1.0)) / std::numbers::pi;
  const double side = std::sqrt(d.x * d.x + d.y * d.y);
  if (side == 0.0) return d.z > 0.0 ? glm::dvec2(0.0, 0.0) : glm::dvec2(1.0, 0.0);
  return {r * d.x / side, r * d.y / side};
}

CubeMap ResampleLatLong(const Image& latlong, int face_size) {
  assert(latlong.height > 0 && latlong.width == 2 * latlong.height);
  assert(face_size >= 1 && face_size <= kMaxFaceSize);
  // Halve the map (keeping its integral) while its pixels stay under half a texel across, so that
  // a texel needs at most 4 kResampleSamplesPerSourcePixel points per side, but not below
  // kMinHalvedHeight rows, where the B-spline's bias (pi / H)^2 / 8 would exceed 7.5e-5.
  const double texel_angle = 2.0 / face_size;
  const Image* source = &latlong;
  Image reduced;
  while (source->height % 2 == 0 && source->height / 2 >= kMinHalvedHeight &&
         2.0 * std::numbers::pi / source->height <= 0.5 * texel_angle) {
    reduced = HalveLatLong(*source);
    source = &reduced;
  }
  const int samples = SamplesPerTexel(face_size, std::numbers::pi / source->height);
  const LatLongSampler sampler(*source, texel_angle / samples);
  return GatherCube(
      face_size, [samples](glm::dvec3) { return samples; }, sampler);
}

CubeMap ResampleAngular(const Image& angular, int face_size) {
  assert(angular.width > 0 && angular.width == angular.height);
  assert(face_size >= 1 && face_size <= kMaxFaceSize);
  // A pixel is 2 / N wide and theta = pi r, so the radial pitch is 2 pi / N radians; across the
  // radius a pixel spans only sin(pi r) / (pi r) of that, so texels towards -z take more points
  // (kResampleSamplesPerSourcePixel per pixel in both directions).
  const double radial_pitch = 2.0 * std::numbers::pi / angular.width;
  const auto samples = [&](glm::dvec3 direction) {
    const double theta = std::acos(std::clamp(direction.z, -1.0, 1.0));
    const double compression = theta > 0.0 ? std::sin(theta) / theta : 1.0;
    return SamplesPerTexel(face_size, radial_pitch * std::clamp(compression, 1e-9, 1.0));
  };
  return GatherCube(face_size, samples,
                    [&](glm::dvec3 direction) { return SampleAngular(angular, direction); });
}

glm::vec3 SampleCubeMap(const CubeMap& cube, glm::dvec3 direction) {
  const FacePoint point = DirectionToFace(direction);
  const Image& face = cube.face(point.face);
  const int n = cube.face_size;
  const double fx = std::clamp((point.s + 1.0) * 0.5 * n - 0.5, 0.0, n - 1.0);
  const double fy = std::clamp((point.t + 1.0) * 0.5 * n - 0.5, 0.0, n - 1.0);
  const int x0 = static_cast<int>(fx);
  const int y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, n - 1);
  const int y1 = std::min(y0 + 1, n - 1);
  const float ax = static_cast<float>(fx - x0);
  const float ay = static_cast<float>(fy - y0);
  const glm::vec3 top = face.at(x0, y0) * (1.0f - ax) + face.at(x1, y0) * ax;
  const glm::vec3 bottom = face.at(x0, y1) * (1.0f - ax) + face.at(x1, y1) * ax;
  return top * (1.0f - ay) + bottom * ay;
}

}  // namespace vs11::irradiance
