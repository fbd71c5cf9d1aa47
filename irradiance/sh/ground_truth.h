// Reference irradiance by brute-force integration of eq. (1) over every texel of a cube map, and
// error statistics for comparing an estimate (SH9, the vertex program) against it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "vm/core/name_table.h"
#include "vm/core/thread_pool.h"
#include "vm/reference/sphere_normals.h"

namespace vs11::irradiance {

// E(n) = sum over every texel of radiance * max(0, n . dir) * dOmega, with dir the unit texel-centre
// direction and dOmega its exact solid angle: eq. (1) without the k_d / pi, so a constant radiance L
// gives pi L. Normals are used as given (pass unit vectors). Cost: O(normals x 6 size^2).
// Sums are formed per face row in double, then in double over rows; every normal is computed by one
// thread in a fixed order, so the result does not depend on `threads`.
// `threads` >= 1 (asserted) worker threads, the calling thread being one of them. `progress`, when
// set, is called from the calling thread only, with a fraction in [0, 1] that never decreases, a
// few times during the work and with 1.0 at the end. The threads are the caller and workers of
// `pool` (null: ThreadPool::Default()).
std::vector<glm::dvec3> GroundTruthIrradiance(const CubeMap& env,
                                              std::span<const glm::dvec3> normals, int threads,
                                              std::function<void(double fraction)> progress = {},
                                              ThreadPool* pool = nullptr);

// Normals of the error table (SphereNormals): dense enough that the max error is found to a few %.
inline constexpr int kDefaultErrorNormals = 2000;

// Luminance of linear RGB with the Rec. 709 (sRGB) primaries: Y = 0.2126 R + 0.7152 G + 0.0722 B.
inline constexpr glm::dvec3 kRec709Luminance{0.2126, 0.7152, 0.0722};
inline double Luminance(glm::dvec3 rgb) { return glm::dot(rgb, kRec709Luminance); }

struct ErrorStats {
  // Per sample relative: |e - t| / max(|t|, floor), the worst channel of each sample.
  double max_relative = 0.0;   // over samples of the per-sample relative error
  double mean_relative = 0.0;  // mean over samples
  double rms_relative = 0.0;   // root of the mean square over samples
  double max_absolute = 0.0;   // max over samples and channels of |e - t|
  glm::dvec3 worst_normal{0.0};  // the normal of the max_relative sample; zero if no normals given
  std::size_t worst_index = 0;   // index of the max_relative sample

  // The errors as Ramamoorthi & Hanrahan (2001) and Probulator state them, for each channel (r, g, b)
  // and for the luminance (kRec709Luminance) of estimate and truth. A channel whose denominator is 0
  // gives 0 when its estimate is exact there, else infinity.
  glm::dvec3 peak_rgb{0.0};      // max over samples |e - t| / max over samples |t|
  double peak_luminance = 0.0;
  glm::dvec3 rms_rgb{0.0};       // sqrt(mean over samples (e - t)^2) / mean over samples |t|
  double rms_luminance = 0.0;
  double max_peak = 0.0;         // the worst channel of peak_rgb: the "peak" figure
  double max_rms = 0.0;          // the worst channel of rms_rgb: the "rms" figure
  std::size_t worst_peak_index = 0;  // the sample and channel of max_peak
};

// The figure each error metric states for a set of samples (ErrorFigure):
//   kRelative  max_relative: the worst per-normal |E - E*| / max(E*, 1 % of the peak)
//   kPeak      max_peak: max |E - E*| / max E*, the worst channel
//   kRms       max_rms: RMS of E - E* over the sphere / mean E*, the worst channel
enum class ErrorMetric { kRelative, kPeak, kRms };
inline constexpr ErrorMetric kAllErrorMetrics[] = {ErrorMetric::kRelative, ErrorMetric::kPeak, ErrorMetric::kRms};
// What --max-error bounds unless --error-metric says otherwise. Peak: bounded where the truth is
// black (the relative error is not: behind a single light it measures the darkest normals), and
// unlike RMS it bounds every normal, so a small light's lobe cannot hide in an average.
inline constexpr ErrorMetric kDefaultErrorMetric = ErrorMetric::kPeak;
inline constexpr NameTable kErrorMetricNames("error metric", {
    Choice(ErrorMetric::kRelative, "relative", "the worst |E - E*| / E* per normal, floor 1 % of the peak"),
    Choice(ErrorMetric::kPeak, "peak", "max |E - E*| / max E*"),
    Choice(ErrorMetric::kRms, "rms", "RMS of E - E* / mean E*")});
inline std::string_view ErrorMetricName(ErrorMetric metric) { return kErrorMetricNames.Name(metric); }
double ErrorFigure(const ErrorStats& stats, ErrorMetric metric);
// What the figure is, for labels: "max relative error", "peak error (max |E - E*| / max E*)", ...
std::string_view ErrorMetricDescription(ErrorMetric metric);

// Compares per-sample RGB estimates with the truth. The relative error of a sample is the max over
// its three channels of |e - t| / max(|t|, floor), where floor = floor_fraction x the largest |t|
// over all samples and channels; the floor keeps nearly black samples (shadowed normals) from
// dominating. floor_fraction >= 0; with 0, a zero truth yields an infinite (or NaN for 0/0)
// relative error. `estimate` and `truth` must have the same length (asserted); empty inputs give
// all-zero stats.
ErrorStats CompareIrradiance(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth,
                             double floor_fraction = 0.01);
// The same, also reporting worst_normal = normals[worst_index]; `normals` has the same length.
ErrorStats CompareIrradiance(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> truth,
                             std::span<const glm::dvec3> normals, double floor_fraction = 0.01);

// The error of one sample in `metric`, of which ErrorFigure is the max over the samples (kRelative,
// kPeak) or the root mean square (kRms): the worst channel of |e - t| / max(|t|, floor) (kRelative),
// |e - t| / peak (kPeak) or |e - t| / mean (kRms), where `scale` holds, per channel, the floor
// (kRelative), max |t| (kPeak) or mean |t| (kRms) over every sample (SampleErrorScale). A zero
// denominator gives 0 for an exact channel, else infinity.
double SampleError(glm::dvec3 estimate, glm::dvec3 truth, glm::dvec3 scale, ErrorMetric metric);
// The per-channel `scale` of SampleError for these truths (floor_fraction as CompareIrradiance's).
glm::dvec3 SampleErrorScale(std::span<const glm::dvec3> truth, ErrorMetric metric, double floor_fraction = 0.01);

}  // namespace vs11::irradiance
