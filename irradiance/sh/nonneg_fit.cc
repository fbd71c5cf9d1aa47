// The non-negative nine-term fit. See nonneg_fit.h.
#include "irradiance/sh/nonneg_fit.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

#include <nlopt.hpp>

#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {
namespace {

using Row = std::array<double, kSh9Coefficients>;

// Irradiance this far below zero, relative to the largest |E|, counts as zero when deciding whether
// a channel needs the fit at all or another round: float-sized crumbs where E touches zero.
constexpr double kNegativeTolerance = 1e-12;
// Descent along the sphere: steps, and the gradient size (relative to the largest |E|) at which a
// point counts as a minimum.
constexpr int kDescentSteps = 80;
constexpr double kDescentStop = 1e-13;
// Stopping rules of SLSQP: x is of order 1 (scaled by the largest irradiance coefficient).
constexpr double kSolverXTolerance = 1e-12;
constexpr int kSolverMaxEvaluations = 1000;
constexpr double kConstraintTolerance = 1e-14;
// Descents per round looking for negative minima between the directions, and for the final lift
// (from the lowest of kLiftNormals directions).
constexpr int kRoundStarts = 16;
constexpr int kLiftNormals = 8000;
constexpr int kLiftStarts = 32;

// Eq. (7) of one channel only (the fit's descents evaluate it hundreds of thousands of times).
double ChannelIrradiance(const Sh9Rgb& sh, int c, glm::dvec3 n) {
  auto L = [&](int l, int m) { return sh.at(l, m)[c]; };
  return kShC0 * L(0, 0) - kShC3 * L(2, 0) + kShC1 * (L(1, -1) * n.y + L(1, 0) * n.z + L(1, 1) * n.x) +
         kShC2 * (L(2, -2) * n.x * n.y + L(2, -1) * n.y * n.z + L(2, 1) * n.x * n.z) +
         3.0 * kShC3 * L(2, 0) * n.z * n.z + kShC4 * L(2, 2) * (n.x * n.x - n.y * n.y);
}

// Gradient of eq. (7) of one channel with respect to (x, y, z).
glm::dvec3 ChannelGradient(const Sh9Rgb& sh, int c, glm::dvec3 n) {
  auto L = [&](int l, int m) { return sh.at(l, m)[c]; };
  return {kShC1 * L(1, 1) + kShC2 * (L(2, -2) * n.y + L(2, 1) * n.z) + 2.0 * kShC4 * L(2, 2) * n.x,
          kShC1 * L(1, -1) + kShC2 * (L(2, -2) * n.x + L(2, -1) * n.z) - 2.0 * kShC4 * L(2, 2) * n.y,
          kShC1 * L(1, 0) + kShC2 * (L(2, -1) * n.y + L(2, 1) * n.x) + 6.0 * kShC3 * L(2, 0) * n.z};
}

// Descent along the unit sphere from `n` with a step that grows on success and halves on failure.
glm::dvec3 Descend(const Sh9Rgb& sh, int c, glm::dvec3 n, double scale) {
  double value = ChannelIrradiance(sh, c, n);
  double step = 0.05;  // radians
  for (int i = 0; i < kDescentSteps && step > 1e-12; ++i) {
    glm::dvec3 g = ChannelGradient(sh, c, n);
    g -= glm::dot(g, n) * n;  // tangent part
    const double length = glm::length(g);
    if (length <= kDescentStop * scale) break;
    const glm::dvec3 next = glm::normalize(n - (step / length) * g);
    const double next_value = ChannelIrradiance(sh, c, next);
    if (next_value < value) {
      n = next;
      value = next_value;
      step *= 1.5;
    } else {
      step *= 0.5;
    }
  }
  return n;
}

// The `count` lowest of `normals`, lowest first.
std::vector<glm::dvec3> LowestPoints(const Sh9Rgb& sh, int c, std::span<const glm::dvec3> normals, int count) {
  std::vector<double> values(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) values[i] = ChannelIrradiance(sh, c, normals[i]);
  std::vector<std::size_t> order(normals.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(count), normals.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order.end(),
                    [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<glm::dvec3> lowest;
  for (std::size_t i = 0; i < k; ++i) lowest.push_back(normals[order[i]]);
  return lowest;
}

// The local minima reached from the `starts` lowest of `normals`.
std::vector<glm::dvec3> LocalMinima(const Sh9Rgb& sh, int c, std::span<const glm::dvec3> normals, int starts,
                                    double scale) {
  std::vector<glm::dvec3> minima;
  for (const glm::dvec3& n : LowestPoints(sh, c, normals, starts)) minima.push_back(Descend(sh, c, n, scale));
  return minima;
}

double LargestIrradiance(const Sh9Rgb& sh, int c, std::span<const glm::dvec3> normals) {
  double largest = 0.0;
  for (const glm::dvec3& n : normals) largest = std::max(largest, std::abs(ChannelIrradiance(sh, c, n)));
  return largest;
}

// The quadratic program of one channel in the scaled irradiance coefficients x = A_l L_lm / scale.
struct ChannelProblem {
  Row target{};
  std::vector<Row> rows;  // y_lm(n) of each constrained direction
  double margin = 0.0;    // x . row >= margin
};

double Objective(unsigned n, const double* x, double* grad, void* data) {
  const ChannelProblem& p = *static_cast<const ChannelProblem*>(data);
  double sum = 0.0;
  for (unsigned i = 0; i < n; ++i) {
    const double d = x[i] - p.target[i];
    sum += d * d;
    if (grad) grad[i] = 2.0 * d;
  }
  return sum;
}

// NLopt's vector constraint, result <= 0: margin - x . row per direction.
void Constraints(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  const ChannelProblem& p = *static_cast<const ChannelProblem*>(data);
  for (unsigned j = 0; j < m; ++j) {
    const Row& row = p.rows[j];
    double dot = 0.0;
    for (unsigned i = 0; i < n; ++i) dot += row[i] * x[i];
    result[j] = p.margin - dot;
    if (grad) {
      for (unsigned i = 0; i < n; ++i) grad[j * n + i] = -row[i];
    }
  }
}

// Solves one channel's program; writes the fitted coefficients into `sh` (channel c). False when
// NLopt reports a failure (the best point it reached is still written).
bool SolveChannel(Sh9Rgb& sh, int c, std::span<const glm::dvec3> directions, double margin) {
  double scale = 0.0;
  for (int l = 0; l < kSh9Bands; ++l) {
    for (int m = -l; m <= l; ++m) scale = std::max(scale, std::abs(kShBandFactor[l] * sh.at(l, m)[c]));
  }
  if (!(scale > 0.0)) return true;
  ChannelProblem problem;
  for (int l = 0; l < kSh9Bands; ++l) {
    for (int m = -l; m <= l; ++m) problem.target[ShIndex(l, m)] = kShBandFactor[l] * sh.at(l, m)[c] / scale;
  }
  for (const glm::dvec3& n : directions) problem.rows.push_back(ShBasis(n));
  problem.margin = margin / scale;

  nlopt::opt solver(nlopt::LD_SLSQP, kSh9Coefficients);
  solver.set_min_objective(Objective, &problem);
  solver.add_inequality_mconstraint(Constraints, &problem,
                                    std::vector<double>(problem.rows.size(), kConstraintTolerance));
  solver.set_xtol_rel(kSolverXTolerance);
  solver.set_maxeval(kSolverMaxEvaluations);
  std::vector<double> x(problem.target.begin(), problem.target.end());
  bool ok = true;
  try {
    double value = 0.0;
    ok = solver.optimize(x, value) > 0;
  } catch (const nlopt::roundoff_limited&) {
    // Converged as far as doubles allow: x is the best point.
  } catch (const std::exception&) {
    ok = false;
  }
  for (int l = 0; l < kSh9Bands; ++l) {
    for (int m = -l; m <= l; ++m) sh.at(l, m)[c] = x[ShIndex(l, m)] * scale / kShBandFactor[l];
  }
  return ok;
}

}  // namespace

glm::dvec3 LowestDirection(const Sh9Rgb& sh, int channel, std::span<const glm::dvec3> normals, int starts) {
  const double scale = std::max(LargestIrradiance(sh, channel, normals), 1e-300);
  glm::dvec3 best = normals.empty() ? glm::dvec3(0.0, 0.0, 1.0) : normals[0];
  for (const glm::dvec3& n : LocalMinima(sh, channel, normals, starts, scale)) {
    if (ChannelIrradiance(sh, channel, n) < ChannelIrradiance(sh, channel, best)) best = n;
  }
  return best;
}

NonNegativeFit FitNonNegative(const Sh9Rgb& sh, std::span<const glm::dvec3> normals) {
  NonNegativeFit fit;
  fit.coefficients = sh;
  for (int c = 0; c < 3; ++c) {
    const double largest = LargestIrradiance(sh, c, normals);
    // An exchange method: only a few constraints are active at the optimum (at most nine), so
    // instead of all of `normals` each round adds the lowest negative directions of the current fit
    // and the minima below them; a round that finds none ends the fit.
    std::vector<glm::dvec3> directions;
    for (int round = 0; round < kNonNegativeFitMaxRounds; ++round) {
      const std::size_t before = directions.size();
      for (const glm::dvec3& n : LowestPoints(fit.coefficients, c, normals, kRoundStarts)) {
        if (ChannelIrradiance(fit.coefficients, c, n) < -kNegativeTolerance * largest) directions.push_back(n);
      }
      for (const glm::dvec3& n : LocalMinima(fit.coefficients, c, normals, kRoundStarts, largest)) {
        if (ChannelIrradiance(fit.coefficients, c, n) < -kNegativeTolerance * largest) directions.push_back(n);
      }
      if (directions.size() == before) break;
      Sh9Rgb channel = sh;  // each round fits the original coefficients with more constraints
      fit.solver_ok = SolveChannel(channel, c, directions, kNonNegativeMargin * largest) && fit.solver_ok;
      for (int i = 0; i < kSh9Coefficients; ++i) fit.coefficients.coefficients[i][c] = channel.coefficients[i][c];
      fit.rounds[c] = round + 1;
      fit.constraints[c] = static_cast<int>(directions.size());
    }
    if (fit.rounds[c] == 0) continue;
    // SLSQP meets its constraints to about 1e-7 of the peak, not to the last bit: lift the constant
    // term by what is left below zero at the directions and the minima between them (a shift of the
    // whole irradiance by that much, which adds at most as much error).
    // Where the fit touches zero it has many shallow dips between the constraints: search them all
    // from the lowest points of a denser set.
    static const std::vector<glm::dvec3> dense = SphereNormals(kLiftNormals);
    double lowest = 0.0;
    for (const glm::dvec3& n : dense) lowest = std::min(lowest, ChannelIrradiance(fit.coefficients, c, n));
    for (const glm::dvec3& n : LocalMinima(fit.coefficients, c, dense, kLiftStarts, largest)) {
      lowest = std::min(lowest, ChannelIrradiance(fit.coefficients, c, n));
    }
    fit.lift[c] = -lowest + kNonNegativeMargin * largest;
    fit.coefficients.at(0, 0)[c] += fit.lift[c] / kShC0;
  }
  return fit;
}

Sh9Rgb FitNonNegativeAt(const Sh9Rgb& sh, std::span<const glm::dvec3> directions) {
  Sh9Rgb fit = sh;
  for (int c = 0; c < 3; ++c) SolveChannel(fit, c, directions, 0.0);
  return fit;
}

Sh9Rgb FitNonNegative(const Sh9Rgb& sh) {
  static const std::vector<glm::dvec3> normals = SphereNormals(kNonNegativeFitNormals);
  return FitNonNegative(sh, normals).coefficients;
}

}  // namespace vs11::irradiance
