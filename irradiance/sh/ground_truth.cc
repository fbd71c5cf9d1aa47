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

// `error` / `scale`, with 0 / 0 = 0 and x / 0 = infinity.
double Ratio(double error, double scale) {
  if (scale > 0.0) return error / scale;
  return error == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

// Fills the peak and RMS figures of `stats`: per channel, then on the luminance (the fourth lane).
void AddLiteratureErrors(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth, ErrorStats& stats) {
  std::array<double, 4> peak{}, mean{}, largest_error{}, sum_squares{};
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const std::array<double, 4> t = {truth[i].x, truth[i].y, truth[i].z, Luminance(truth[i])};
    const std::array<double, 4> e = {estimate[i].x, estimate[i].y, estimate[i].z, Luminance(estimate[i])};
    for (std::size_t c = 0; c < 4; ++c) {
      const double error = std::abs(e[c] - t[c]);
      peak[c] = std::max(peak[c], std::abs(t[c]));
      mean[c] += std::abs(t[c]);
      sum_squares[c] += error * error;
      largest_error[c] = std::max(largest_error[c], error);
    }
  }
  const double count = static_cast<double>(truth.size());
  std::array<double, 4> peak_figure{}, rms_figure{};
  for (std::size_t c = 0; c < 4; ++c) {
    peak_figure[c] = Ratio(largest_error[c], peak[c]);
    rms_figure[c] = Ratio(std::sqrt(sum_squares[c] / count), mean[c] / count);
  }
  stats.peak_rgb = glm::dvec3(peak_figure[0], peak_figure[1], peak_figure[2]);
  stats.rms_rgb = glm::dvec3(rms_figure[0], rms_figure[1], rms_figure[2]);
  stats.peak_luminance = peak_figure[3];
  stats.rms_luminance = rms_figure[3];
  stats.max_peak = std::max({peak_figure[0], peak_figure[1], peak_figure[2]});
  stats.max_rms = std::max({rms_figure[0], rms_figure[1], rms_figure[2]});
  // The sample of max_peak: the first whose error in the worst channel reaches that channel's largest.
  const int worst_channel =
      static_cast<int>(std::max_element(peak_figure.begin(), peak_figure.begin() + 3) - peak_figure.begin());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (std::abs(estimate[i][worst_channel] - truth[i][worst_channel]) ==
        largest_error[static_cast<std::size_t>(worst_channel)]) {
      stats.worst_peak_index = i;
      break;
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
  AddLiteratureErrors(estimate, truth, stats);
  return stats;
}

ErrorStats CompareIrradiance(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth,
                             std::span<const glm::dvec3> normals, double floor_fraction) {
  assert(normals.size() == truth.size());
  ErrorStats stats = CompareIrradiance(estimate, truth, floor_fraction);
  if (!normals.empty()) stats.worst_normal = normals[stats.worst_index];
  return stats;
}

double ErrorFigure(const ErrorStats& stats, ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::kRelative: return stats.max_relative;
    case ErrorMetric::kPeak: return stats.max_peak;
    case ErrorMetric::kRms: return stats.max_rms;
  }
  return stats.max_relative;
}

std::string_view ErrorMetricDescription(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::kRelative: return "max relative error (per normal, floor 1 % of the peak)";
    case ErrorMetric::kPeak: return "peak error (max |E - E*| / max E*)";
    case ErrorMetric::kRms: return "RMS error / mean irradiance";
  }
  return "?";
}

double SampleError(glm::dvec3 estimate, glm::dvec3 truth, glm::dvec3 scale, ErrorMetric metric) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double error = std::abs(estimate[c] - truth[c]);
    const double denominator = metric == ErrorMetric::kRelative ? std::max(std::abs(truth[c]), scale[c]) : scale[c];
    worst = std::max(worst, Ratio(error, denominator));
  }
  return worst;
}

glm::dvec3 SampleErrorScale(std::span<const glm::dvec3> truth, ErrorMetric metric, double floor_fraction) {
  glm::dvec3 peak(0.0), sum(0.0);
  for (const glm::dvec3& t : truth) {
    peak = glm::max(peak, glm::abs(t));
    sum += glm::abs(t);
  }
  switch (metric) {
    case ErrorMetric::kRelative: return glm::dvec3(floor_fraction * std::max({peak.x, peak.y, peak.z}));
    case ErrorMetric::kPeak: return peak;
    case ErrorMetric::kRms: return truth.empty() ? glm::dvec3(0.0) : sum / static_cast<double>(truth.size());
  }
  return peak;
}

}  // namespace vs11::irradiance
