// Reference irradiance by brute-force integration of eq. (1) over every texel of a cube map, and
// error statistics for comparing an estimate (SH9, the vertex program) against it.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "vm/core/thread_pool.h"

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

struct ErrorStats {
  double max_relative = 0.0;   // over samples of the per-sample relative error
  double mean_relative = 0.0;  // mean over samples
  double rms_relative = 0.0;   // root of the mean square over samples
  double max_absolute = 0.0;   // max over samples and channels of |e - t|
  glm::dvec3 worst_normal{0.0};  // the normal of the max_relative sample; zero if no normals given
  std::size_t worst_index = 0;   // index of the max_relative sample
};

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

// `count` unit normals spread evenly over the sphere by the Fibonacci (golden-angle) spiral: normal i
// has y = 1 - (2 i + 1) / count (+y is up) and azimuth i x the golden angle. Deterministic; empty for
// count <= 0.
std::vector<glm::dvec3> SphereNormals(int count);

}  // namespace vs11::irradiance
