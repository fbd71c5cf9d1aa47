// Lat-long projection in place. See latlong_projection.h.
#include "irradiance/sh/latlong_projection.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "irradiance/sh/sh_projection.h"
#include "vm/core/thread_pool.h"

namespace vs11::irradiance {
namespace {

using kernels::kLatLongColumnFunctions;
using kernels::LatLongRowSums;
constexpr double kPi = std::numbers::pi;
// Rows per task: enough work per task that the pool's overhead does not show, small enough to share.
constexpr int kRowsPerTask = 8;
// The scale of a row's weights when its float sums overflow (see ProjectLatLongLevel): weights are at
// most pi, a float run adds 16 products, so 2^-8 keeps 16 x FLT_MAX x pi x 2^-8 below FLT_MAX.
constexpr int kOverflowShift = 8;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "rows of pixels are read as interleaved floats");

// cos a - cos b without the cancellation of subtracting two cosines near the poles.
double CosineDifference(double a, double b) { return 2.0 * std::sin(0.5 * (a + b)) * std::sin(0.5 * (b - a)); }

// The pieces of the source cells [i / from, (i + 1) / from) that lie in target cell
// [k / to, (k + 1) / to), in units of 1 / (from x to) so that every boundary is an exact integer.
struct Overlap {
  int source;
  std::int64_t begin;
  std::int64_t end;
};

std::vector<std::vector<Overlap>> Overlaps(int from, int to) {
  std::vector<std::vector<Overlap>> cells(static_cast<std::size_t>(to));
  for (int k = 0; k < to; ++k) {
    const std::int64_t begin = std::int64_t{k} * from, end = std::int64_t{k + 1} * from;
    for (int i = static_cast<int>(begin / to); i < from && std::int64_t{i} * to < end; ++i) {
      const std::int64_t b = std::max(begin, std::int64_t{i} * to), e = std::min(end, std::int64_t{i + 1} * to);
      if (e > b) cells[static_cast<std::size_t>(k)].push_back({i, b, e});
    }
  }
  return cells;
}

// f_j(phi) for the column functions, in kernels::kLatLongColumnFunctions order.
std::array<double, kLatLongColumnFunctions> ColumnFunctions(double phi) {
  return {1.0, std::cos(phi), std::sin(phi), std::cos(2.0 * phi), std::sin(2.0 * phi)};
}

// g_i(theta) for the row functions: 1, cos, sin, sin cos, sin^2, cos^2.
std::array<double, kLatLongRowFunctions> RowFunctions(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {1.0, c, s, s * c, s * s, c * c};
}

void SetColumn(LatLongTables& tables, int x, const std::array<double, kLatLongColumnFunctions>& values) {
  for (int j = 0; j < kLatLongColumnFunctions; ++j) {
    tables.column_sums[j][static_cast<std::size_t>(x)] = values[j];
    const float value = static_cast<float>(values[j]);
    for (int c = 0; c < 3; ++c) tables.columns[j][static_cast<std::size_t>(3 * x + c)] = value;
  }
}

LatLongTables TablesOfSize(int width, int height) {
  LatLongTables tables;
  for (std::vector<double>& table : tables.column_sums) table.assign(static_cast<std::size_t>(width), 0.0);
  for (std::vector<float>& table : tables.columns) table.assign(static_cast<std::size_t>(3) * width, 0.0f);
  for (std::vector<double>& table : tables.rows) table.assign(static_cast<std::size_t>(height), 0.0);
  return tables;
}

// The nine coefficients' share of one row: its five sums per channel times its six row factors.
void AddRow(const LatLongRowSums& s, const std::array<double, kLatLongRowFunctions>& g, double scale,
            std::array<glm::dvec3, kSh9Coefficients>& out) {
  for (int c = 0; c < 3; ++c) {
    const double s0 = s[0][c] * scale, s1 = s[1][c] * scale, s2 = s[2][c] * scale, s3 = s[3][c] * scale,
                 s4 = s[4][c] * scale;
    out[0][c] += kShN0 * g[0] * s0;
    out[1][c] += kShN1 * g[1] * s0;
    out[2][c] += kShN1 * g[2] * s1;
    out[3][c] += kShN1 * g[2] * s2;
    out[4][c] += kShN2 * g[3] * s2;
    out[5][c] += kShN2 * g[3] * s1;
    // 3 z^2 - 1 with z^2 = sin^2 theta cos^2 phi = sin^2 theta (1 + cos 2 phi) / 2.
    out[6][c] += kShN3 * (1.5 * g[4] * (s0 + s3) - g[0] * s0);
    out[7][c] += kShN2 * 0.5 * g[4] * s4;  // x z = sin^2 theta sin 2 phi / 2
    // x^2 - y^2 = sin^2 theta (1 - cos 2 phi) / 2 - cos^2 theta.
    out[8][c] += kShN4 * (0.5 * g[4] * (s0 - s3) - g[5] * s0);
  }
}

bool AllFinite(const LatLongRowSums& sums) {
  for (const auto& function : sums) {
    for (double value : function) {
      if (!std::isfinite(value)) return false;
    }
  }
  return true;
}

}  // namespace

LatLongTables FinestLatLongTables(int width) {
  assert(width > 0 && width % 2 == 0);
  const int height = width / 2;
  LatLongTables tables = TablesOfSize(width, height);
  const double dphi = 2.0 * kPi / width;
  for (int x = 0; x < width; ++x) {
    std::array<double, kLatLongColumnFunctions> values = ColumnFunctions(2.0 * kPi * ((x + 0.5) / width - 0.5));
    for (double& value : values) value *= dphi;
    SetColumn(tables, x, values);
  }
  for (int y = 0; y < height; ++y) {
    const double band = CosineDifference(kPi * y / height, kPi * (y + 1) / height);
    const std::array<double, kLatLongRowFunctions> g = RowFunctions(kPi * (y + 0.5) / height);
    for (int i = 0; i < kLatLongRowFunctions; ++i) tables.rows[i][static_cast<std::size_t>(y)] = g[i] * band;
  }
  return tables;
}

LatLongLevel MakeLatLongLevel(Image latlong) {
  assert(latlong.height > 0 && latlong.width == 2 * latlong.height);
  LatLongLevel level;
  level.tables = FinestLatLongTables(latlong.width);
  level.image = std::move(latlong);
  return level;
}

LatLongLevel ReduceLatLongLevel(const LatLongLevel& from, int width, int threads) {
  const int from_width = from.image.width, from_height = from.image.height;
  assert(width >= 2 && width % 2 == 0 && width < from_width);
  const int height = width / 2;
  LatLongLevel level;
  level.tables = TablesOfSize(width, height);
  const std::vector<std::vector<Overlap>> columns = Overlaps(from_width, width);
  const std::vector<std::vector<Overlap>> rows = Overlaps(from_height, height);
  // Column weights: the fraction of the target column each source piece is (radiance), and the
  // fraction of the source column it is (basis sums).
  const double column_units = static_cast<double>(from_width);  // a target column, in overlap units
  for (int x = 0; x < width; ++x) {
    std::array<double, kLatLongColumnFunctions> sums{};
    for (const Overlap& piece : columns[static_cast<std::size_t>(x)]) {
      const double share = static_cast<double>(piece.end - piece.begin) / width;  // of the source column
      for (int j = 0; j < kLatLongColumnFunctions; ++j) {
        sums[j] += share * from.tables.column_sums[j][static_cast<std::size_t>(piece.source)];
      }
    }
    SetColumn(level.tables, x, sums);
  }
  // Row weights in cos theta: the piece's band over the target's (radiance), and over the source
  // row's (basis sums).
  const double row_unit = kPi / (static_cast<double>(from_height) * height);
  std::vector<std::vector<double>> row_weights(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const double target_band = CosineDifference(kPi * y / height, kPi * (y + 1) / height);
    for (const Overlap& piece : rows[static_cast<std::size_t>(y)]) {
      const double band = CosineDifference(row_unit * piece.begin, row_unit * piece.end);
      const int s = piece.source;
      const double source_band = CosineDifference(kPi * s / from_height, kPi * (s + 1) / from_height);
      row_weights[static_cast<std::size_t>(y)].push_back(band / target_band);
      for (int i = 0; i < kLatLongRowFunctions; ++i) {
        level.tables.rows[i][static_cast<std::size_t>(y)] +=
            band / source_band * from.tables.rows[i][static_cast<std::size_t>(s)];
      }
    }
  }
  level.image = Image(width, height);
  const std::size_t tasks = static_cast<std::size_t>((height + kRowsPerTask - 1) / kRowsPerTask);
  ThreadPool::Default().Run(tasks, std::max(threads, 1), [&](std::size_t task, int) {
    std::vector<glm::dvec3> reduced(static_cast<std::size_t>(from_width));
    const int y_end = std::min(height, static_cast<int>(task + 1) * kRowsPerTask);
    for (int y = static_cast<int>(task) * kRowsPerTask; y < y_end; ++y) {
      const std::vector<Overlap>& pieces = rows[static_cast<std::size_t>(y)];
      std::fill(reduced.begin(), reduced.end(), glm::dvec3(0.0));
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        const double weight = row_weights[static_cast<std::size_t>(y)][p];
        const glm::vec3* source = &from.image.pixels[static_cast<std::size_t>(pieces[p].source) * from_width];
        for (int x = 0; x < from_width; ++x) reduced[static_cast<std::size_t>(x)] += weight * glm::dvec3(source[x]);
      }
      for (int x = 0; x < width; ++x) {
        glm::dvec3 mean(0.0);
        for (const Overlap& piece : columns[static_cast<std::size_t>(x)]) {
          mean += static_cast<double>(piece.end - piece.begin) / column_units * reduced[static_cast<std::size_t>(piece.source)];
        }
        level.image.at(x, y) = glm::vec3(mean);
      }
    }
  });
  return level;
}

Sh9Rgb ProjectLatLongLevel(const Image& image, const LatLongTables& weights, int threads) {
  assert(image.height > 0 && image.width == 2 * image.height &&
         weights.columns[0].size() == static_cast<std::size_t>(3) * image.width);
  const int width = image.width, height = image.height;
  std::array<const float*, kLatLongColumnFunctions> tables;
  for (int j = 0; j < kLatLongColumnFunctions; ++j) tables[j] = weights.columns[j].data();
  std::vector<LatLongRowSums> row_sums(static_cast<std::size_t>(height));
  std::vector<char> scaled(static_cast<std::size_t>(height), 0);
  const std::size_t tasks = static_cast<std::size_t>((height + kRowsPerTask - 1) / kRowsPerTask);
  ThreadPool::Default().Run(tasks, std::max(threads, 1), [&](std::size_t task, int) {
    std::array<std::vector<float>, kLatLongColumnFunctions> scaled_tables;  // made only where a row overflows
    const int y_end = std::min(height, static_cast<int>(task + 1) * kRowsPerTask);
    for (int y = static_cast<int>(task) * kRowsPerTask; y < y_end; ++y) {
      const float* row = &image.pixels[static_cast<std::size_t>(y) * width].x;
      LatLongRowSums& sums = row_sums[static_cast<std::size_t>(y)];
      sums = kernels::SumLatLongRow(row, tables, 3 * width);
      if (AllFinite(sums)) continue;
      std::array<const float*, kLatLongColumnFunctions> smaller;
      for (int j = 0; j < kLatLongColumnFunctions; ++j) {
        if (scaled_tables[j].empty()) {
          scaled_tables[j] = weights.columns[j];
          for (float& w : scaled_tables[j]) w = std::ldexp(w, -kOverflowShift);
        }
        smaller[j] = scaled_tables[j].data();
      }
      sums = kernels::SumLatLongRow(row, smaller, 3 * width);
      scaled[static_cast<std::size_t>(y)] = 1;
    }
  });
  Sh9Rgb sh;
  for (int y = 0; y < height; ++y) {
    std::array<double, kLatLongRowFunctions> g;
    for (int i = 0; i < kLatLongRowFunctions; ++i) g[i] = weights.rows[i][static_cast<std::size_t>(y)];
    const double scale = scaled[static_cast<std::size_t>(y)] ? std::ldexp(1.0, kOverflowShift) : 1.0;
    AddRow(row_sums[static_cast<std::size_t>(y)], g, scale, sh.coefficients);
  }
  return sh;
}

Sh9Rgb ProjectLatLong(const Image& latlong, int threads) {
  return ProjectLatLongLevel(latlong, FinestLatLongTables(latlong.width), threads);
}

LatLongPyramid BuildLatLongPyramid(Image latlong, int face_size, int threads) {
  assert(IsPowerOfTwo(face_size));
  LatLongPyramid pyramid;
  pyramid.face_size = face_size;
  pyramid.distinct.push_back(MakeLatLongLevel(std::move(latlong)));
  const int count = LevelCount(face_size);
  pyramid.levels.push_back(0);
  for (int k = 1; k < count; ++k) {
    const int width = 4 * (face_size >> k);
    if (width < pyramid.distinct.back().image.width) {
      pyramid.distinct.push_back(ReduceLatLongLevel(pyramid.distinct.back(), width, threads));
    }
    pyramid.levels.push_back(static_cast<int>(pyramid.distinct.size()) - 1);
  }
  return pyramid;
}

}  // namespace vs11::irradiance
