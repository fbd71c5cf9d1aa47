// Brute-force irradiance and error statistics. See ground_truth.h.
#include "irradiance/sh/ground_truth.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "irradiance/sh/row_sum_kernels.h"

namespace vs11::irradiance {
namespace {

// The texels are processed in chunks of whole face rows, at most this many texels per chunk, so
// the precomputed table (7 doubles per texel, 56 bytes) stays near 56 MB even for 2048 faces.
constexpr std::size_t kChunkTexels = std::size_t{1} << 20;
// Normals are handed to threads in blocks of this many (one atomic increment per block).
constexpr int kNormalsPerBlock = 8;

// Structure-of-arrays table of one chunk: per texel, dir * dOmega and radiance.
struct TexelTable {
  int size = 0;  // texels per row
  int rows = 0;
  std::vector<double> wx, wy, wz, r, g, b;

  void Reset(int row_size, int row_count) {
    size = row_size;
    rows = row_count;
    const std::size_t n = static_cast<std::size_t>(row_size) * row_count;
    for (auto* v : {&wx, &wy, &wz, &r, &g, &b}) v->resize(n);
  }

  kernels::CosineTable View() const {
    return {wx.data(), wy.data(), wz.data(), {r.data(), g.data(), b.data()}, size, rows};
  }
};

// Fills `table` with face rows [first_row, first_row + rows) of the 6 x size rows ordered face-major.
void FillTable(const CubeMap& env, int first_row, int rows, TexelTable& table) {
  const int size = env.face_size;
  table.Reset(size, rows);
  for (int i = 0; i < rows; ++i) {
    const int face_index = (first_row + i) / size;
    const int y = (first_row + i) % size;
    const CubeFace face = kAllCubeFaces[face_index];
    const Image& image = env.faces[face_index];
    for (int x = 0; x < size; ++x) {
      const std::size_t k = static_cast<std::size_t>(i) * size + x;
      const glm::dvec3 w = TexelDirection(face, x, y, size) * TexelSolidAngle(x, y, size);
      const glm::vec3 radiance = image.at(x, y);
      table.wx[k] = w.x;
      table.wy[k] = w.y;
      table.wz[k] = w.z;
      table.r[k] = radiance.x;
      table.g[k] = radiance.y;
      table.b[k] = radiance.z;
    }
  }
}

}  // namespace

std::vector<glm::dvec3> GroundTruthIrradiance(const CubeMap& env,
                                              std::span<const glm::dvec3> normals, int threads,
                                              std::function<void(double fraction)> progress, ThreadPool* pool) {
  assert(threads >= 1);
  std::vector<glm::dvec3> result(normals.size(), glm::dvec3(0.0));
  const int size = env.face_size;
  const int total_rows = kCubeFaceCount * size;
  const int normal_count = static_cast<int>(normals.size());
  if (size <= 0 || normal_count == 0) {
    if (progress) progress(1.0);
    return result;
  }
  const int rows_per_chunk =
      std::max(1, static_cast<int>(kChunkTexels / static_cast<std::size_t>(size)));
  const int chunk_count = (total_rows + rows_per_chunk - 1) / rows_per_chunk;
  const int block_count = (normal_count + kNormalsPerBlock - 1) / kNormalsPerBlock;
  const int worker_count = std::max(1, std::min(threads, block_count));

  TexelTable table;
  std::atomic<int> next_block{0};
  std::atomic<int> done_blocks{0};
  double last_reported = 0.0;
  ThreadPool& workers = pool != nullptr ? *pool : ThreadPool::Default();
  auto work = [&](bool reporter, int chunk) {
    for (int block; (block = next_block.fetch_add(1)) < block_count;) {
      // Rows outside, normals inside: one row's table (56 bytes a texel) stays in cache for the
      // block's normals. Each normal still adds its rows in order.
      const int begin = block * kNormalsPerBlock;
      const int end = std::min(normal_count, begin + kNormalsPerBlock);
      std::array<kernels::ChannelSums, kNormalsPerBlock> block_normals, sums;
      for (int i = begin; i < end; ++i) {
        block_normals[i - begin] = {normals[i].x, normals[i].y, normals[i].z};
        sums[i - begin] = {result[i].x, result[i].y, result[i].z};
      }
      kernels::AddClampedCosineSums(table.View(), block_normals.data(), end - begin, sums.data());
      for (int i = begin; i < end; ++i) result[i] = glm::dvec3(sums[i - begin][0], sums[i - begin][1], sums[i - begin][2]);
      const int done = done_blocks.fetch_add(1) + 1;
      if (reporter && progress) {
        const double fraction =
            (chunk + static_cast<double>(done) / block_count) / static_cast<double>(chunk_count);
        last_reported = std::max(last_reported, std::min(fraction, 1.0));
        progress(last_reported);
      }
    }
  };

  for (int chunk = 0; chunk < chunk_count; ++chunk) {
    const int first_row = chunk * rows_per_chunk;
    FillTable(env, first_row, std::min(rows_per_chunk, total_rows - first_row), table);
    next_block = 0;
    done_blocks = 0;
    // One task per thread, each taking blocks until none are left; the caller's (slot 0) reports.
    workers.Run(static_cast<std::size_t>(worker_count), worker_count,
                [&](std::size_t, int slot) { work(slot == 0, chunk); });
  }
  if (progress) progress(1.0);
  return result;
}

ErrorStats CompareIrradiance(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth,
                             double floor_fraction) {
  assert(estimate.size() == truth.size());
  assert(floor_fraction >= 0.0);
  ErrorStats stats;
  if (truth.empty()) return stats;
  double largest = 0.0;
  for (const glm::dvec3& t : truth) {
    largest = std::max({largest, std::abs(t.x), std::abs(t.y), std::abs(t.z)});
  }
  const double floor = floor_fraction * largest;
  double sum = 0.0;
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    double relative = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double absolute = std::abs(estimate[i][c] - truth[i][c]);
      const double denominator = std::max(std::abs(truth[i][c]), floor);
      stats.max_absolute = std::max(stats.max_absolute, absolute);
      const double channel_relative =
          denominator > 0.0 ? absolute / denominator
                            : (absolute == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
      relative = std::max(relative, channel_relative);
    }
    sum += relative;
    sum_squares += relative * relative;
    if (relative > stats.max_relative || i == 0) {
      stats.max_relative = relative;
      stats.worst_index = i;
    }
  }
  const double count = static_cast<double>(truth.size());
  stats.mean_relative = sum / count;
  stats.rms_relative = std::sqrt(sum_squares / count);
  return stats;
}

ErrorStats CompareIrradiance(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth,
                             std::span<const glm::dvec3> normals, double floor_fraction) {
  assert(normals.size() == truth.size());
  ErrorStats stats = CompareIrradiance(estimate, truth, floor_fraction);
  if (!normals.empty()) stats.worst_normal = normals[stats.worst_index];
  return stats;
}

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

}  // namespace vs11::irradiance
