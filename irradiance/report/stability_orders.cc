// The stability report's sections on the non-negative fit and on the (program, level) choice. See
// stability_report.h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/report/stability_report.h"
#include "irradiance/sh/nonneg_fit.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

using Clock = std::chrono::steady_clock;

// Runs of FitNonNegative whose median is reported as its cost per environment change.
constexpr int kFitTimingRuns = 7;
// Lat-long probes: a built-in written as a 4N x 2N lat-long image and resampled back, the way a
// captured probe arrives.
constexpr std::array<const char*, 2> kLatLongProbes = {"sky", "studio"};
// Targets of the hit-rate table, and the factors tried for kOrderErrorEstimateFactor.
constexpr std::array<double, 5> kTargets = {0.001, 0.0025, 0.005, 0.01, 0.02};
constexpr std::array<double, 6> kFactors = {0.5, 0.8, 1.0, 1.1, 1.25, 1.5};

double MedianFitMs(const Sh9Rgb& sh) {
  std::vector<double> ms;
  for (int i = 0; i < kFitTimingRuns; ++i) {
    const Clock::time_point start = Clock::now();
    FitNonNegative(sh);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::nth_element(ms.begin(), ms.begin() + kFitTimingRuns / 2, ms.end());
  return ms[kFitTimingRuns / 2];
}

// The cheapest pair that truly meets `target` (fewest slots, then coarsest level): what a perfect
// estimate would pick.
int IdealSlots(const LevelStudy& s, double target) {
  for (ShOrder order : kAllShOrders) {
    for (std::size_t i = 0; i < s.pairs.size(); ++i) {
      if (s.pairs[i].order == order && s.pair_errors[i] <= target) return Info(order).slots;
    }
  }
  return Info(ShOrder::kOrder2).slots;
}

}  // namespace

void RunWindowCases(StabilityReport& report, std::span<const glm::dvec3> normals) {
  const int face_size = report.options.face_size;
  std::vector<std::pair<std::string, CubeMap>> environments;
  for (const std::string& name : BuiltinEnvironmentNames()) {
    environments.emplace_back(name, *MakeBuiltinEnvironment(name, face_size));
  }
  for (const char* name : kLatLongProbes) {
    const Image latlong = CubeMapToImage(*MakeBuiltinEnvironment(name, face_size), EnvironmentLayout::kLatLong);
    environments.emplace_back(fmt::format("{} via lat-long {}x{}", name, latlong.width, latlong.height),
                              ResampleLatLong(latlong, face_size));
  }
  for (const auto& [name, env] : environments) {
    const Sh9Rgb sh = ProjectDirect(env);
    StabilityReport::WindowCase row;
    row.environment = name;
    row.windows = MeasureWindows(sh, normals, GroundTruthIrradiance(env, normals, report.threads), report.variants);
    row.fit_ms = MedianFitMs(sh);
    report.window_cases.push_back(std::move(row));
  }
}

std::string NonNegativeSection(const StabilityReport& r) {
  const auto& none = [](const SpotSweepRow& row) -> const WindowedError& { return row.windows.front(); };
  int ringing = 0, wins = 0, never_negative = 0, worse_than_none = 0;
  std::string losses;
  double worst_lowest = 0.0;
  for (const SpotSweepRow& row : r.sweep) {
    if (none(row).lowest_over_peak >= 0.0) continue;  // nothing to fix: no ringing
    ++ringing;
    const WindowedError& dering = row.windows[kDeringVariant];
    const WindowedError& fit = row.windows[kNonNegativeVariant];
    worst_lowest = std::min(worst_lowest, fit.lowest_over_peak);
    never_negative += fit.lowest_over_peak >= 0.0;
    worse_than_none += fit.error.max_relative > none(row).error.max_relative;
    if (fit.error.max_relative < dering.error.max_relative) {
      ++wins;
    } else {
      losses += fmt::format(" {:g} deg ({} against {});", row.radius_degrees, ReportPercent(fit.error.max_relative),
                            ReportPercent(dering.error.max_relative));
    }
  }
  std::string out = fmt::format(
      "### The non-negative fit (`--window nonneg`)\n\n"
      "Not a window: per channel, the nine coefficients nearest (in squared irradiance over the sphere) to the "
      "unwindowed ones among those whose irradiance is >= 0 everywhere (negatives searched at {} directions and "
      "the minima between them; irradiance/sh/nonneg_fit.h, NLopt SLSQP). It is the *nonneg* column of the "
      "tables above. Of the {} radii that ring, the fit is never negative on {} (its lowest value over the "
      "error normals: {}), and its max error is below dering's on {}.{}\n\n"
      "Where it loses: its max error is above the unwindowed terms' on {} of those radii. It is the nearest "
      "non-negative fit in the squared sense, not in the max, and lifting the far side, where the truth is 0, "
      "costs most in a relative error whose floor is 1 % of the peak; the large lights (80 to 60 degrees), "
      "whose ringing is shallow, it fits better than the unwindowed terms. Against dering it loses on none of "
      "these lights: dering scales whole bands and blurs the peak, the fit moves each coefficient and keeps "
      "it. Both leave environments without ringing alone.\n\n"
      "The built-ins and lat-long probes (max relative error / lowest irradiance over peak, and the fit's time "
      "per environment change, median of {} runs on this machine):\n\n| environment |",
      kNonNegativeFitNormals, ringing, never_negative, ReportPercent(worst_lowest), wins,
      losses.empty() ? std::string() : " It loses at:" + losses, worse_than_none, kFitTimingRuns);
  std::string rule = "|---|";
  for (const WindowVariant& v : r.variants) {
    out += fmt::format(" {} |", v.Label());
    rule += "---|";
  }
  out += " fit ms |\n" + rule + "---|\n";
  for (const StabilityReport::WindowCase& c : r.window_cases) {
    out += fmt::format("| {} |", c.environment);
    for (const WindowedError& w : c.windows) {
      out += fmt::format(" {} / {} |", ReportPercent(w.error.max_relative), ReportPercent(w.lowest_over_peak));
    }
    out += fmt::format(" {:.2f} |\n", c.fit_ms);
  }
  double slowest = 0.0;
  for (const StabilityReport::WindowCase& c : r.window_cases) slowest = std::max(slowest, c.fit_ms);
  out += fmt::format(
      "\nThe fit costs a fraction of a millisecond where the irradiance is already non-negative (the search "
      "for negative directions finds none); where it rings it runs a few rounds of one small quadratic program "
      "per channel, up to {:.1f} ms here (wall time on a shared, loaded 2-core machine; `vs11_bench "
      "--benchmark_filter=NonNegativeFit` measures it alone). That is fine for a static environment or one "
      "that changes now and then; for a dynamic one it is a large part of a frame, where dering or a fit every "
      "few frames would do.\n\n",
      slowest);
  return out;
}

std::string OrderChoiceSection(const StabilityReport& r) {
  std::string out = fmt::format(
      "## 2b. Order choice\n\n"
      "`irrmap --max-error E` picks the program too (irradiance/sh/sh_order.h): order0 (1 slot, the constant), "
      "order1 (3 slots, bands 0-1), zh3 (6 slots, bands 0-1 plus band 2's zonal part around the linear band's "
      "luminance axis: ZH3, Roughton et al. 2024) or order2 (the paper's 11 slots), with the level: the "
      "fewest slots, then the coarsest level, whose estimate stays under E. The estimate of a pair is the "
      "level's estimate plus {:g} x the reduced order's difference from the nine terms at that level (computed "
      "from the coefficients alone, at irrmap's {} normals). The truth here is order 2 at level 0 "
      "({}x{} faces, {} normals); *truth max* is the pick against the brute-force ground truth.\n\n"
      "| environment | pick | slots | estimate | error vs order 2, level 0 | meets E | order2's level | "
      "truth max, pick | truth max, order 2 level 0 |\n|---|---|---|---|---|---|---|---|---|\n",
      kOrderErrorEstimateFactor, kLevelErrorNormals, r.options.face_size, r.options.face_size,
      r.options.error_normals);
  for (const LevelStudy& s : r.levels) {
    const int size = s.rows[static_cast<std::size_t>(s.program.level)].size;
    out += fmt::format("| {} | {} from {}x{} | {} | {} | {} | {} | {}x{} | {} | {} |\n", s.environment,
                       ShOrderName(s.program.order), size, size, Info(s.program.order).slots,
                       ReportPercent(s.program.estimated), ReportPercent(s.program_error),
                       s.program_meets ? "yes" : "**no**", s.rows[s.picked].size, s.rows[s.picked].size,
                       ReportPercent(s.program_vs_truth.max_relative), ReportPercent(s.rows[0].max_vs_truth));
  }
  out += "\nWhich program each environment gets, by target E:\n\n| environment |";
  std::string rule = "|---|";
  for (double target : kTargets) {
    out += fmt::format(" E = {} |", ReportPercent(target));
    rule += "---|";
  }
  out += "\n" + rule + "\n";
  for (const LevelStudy& s : r.levels) {
    out += fmt::format("| {} |", s.environment);
    for (double target : kTargets) {
      const ProgramPick pick = PickProgram(s, target);
      const int size = s.rows[static_cast<std::size_t>(pick.choice.level)].size;
      out += fmt::format(" {} {}x{}{} |", ShOrderName(pick.choice.order), size, size,
                         pick.error <= target ? "" : " **miss**");
    }
    out += "\n";
  }
  out += fmt::format(
      "\nThe safety factor, fitted as the level's 1.4 was: for each factor, over the {} environments x {} targets, "
      "how often the pick met E against order 2 at level 0 (*hit rate*), and how often it used more slots than "
      "the cheapest pair that truly meets E (*too costly*):\n\n| factor | hit rate | too costly |\n|---|---|---|\n",
      r.levels.size(), kTargets.size());
  for (double factor : kFactors) {
    int hits = 0, costly = 0, cases = 0;
    for (const LevelStudy& s : r.levels) {
      for (double target : kTargets) {
        const ProgramPick pick = PickProgram(s, target, factor);
        ++cases;
        hits += pick.error <= target;
        costly += Info(pick.choice.order).slots > IdealSlots(s, target);
      }
    }
    out += fmt::format("| {:g}{} | {} of {} | {} |\n", factor, factor == kOrderErrorEstimateFactor ? " (irrmap)" : "",
                       hits, cases, costly);
  }
  out += "\nThe order's part of the estimate is exact at its level (the reduced irradiance is computed, not "
         "extrapolated); what the factor covers is the level's part and how the two errors add (they partly "
         "cancel or add up depending on the direction).\n\n";
  return out;
}

}  // namespace vs11::irradiance
