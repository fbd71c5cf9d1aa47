// The stability report. See stability_report.h.
#include "irradiance/report/stability_report.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <system_error>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/render/gnuplot.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::string_view kMarkdownFile = "stability.md";
constexpr std::string_view kSweepChart = "sweep.png";
constexpr std::string_view kRingingChart = "ringing.png";
constexpr std::string_view kLevelsChart = "levels.png";
// A light "rings" past 10 % (a level's 1 % threshold is stability.cc's kOnePercent).
constexpr double kSweepThreshold = 0.10;
// Largest face the report accepts, below the loaders' kMaxFaceSize: the report builds and projects many
// synthetic environments at this size (a 4096 face is 100M texels, 1.2 GB of float RGB per cube).
constexpr int kMaxStabilityFaceSize = 4096;
// Spots of other sizes in the level study, and the sun of a sky variant.
constexpr std::array<double, 3> kLevelSpotRadii = {10.0, 1.0, 0.5};
constexpr double kSmallSunRadiusDegrees = 0.5;
constexpr std::array<float, 4> kFaintLightPowers = {0.005f, 0.01f, 0.02f, 0.05f};
constexpr std::array<double, 9> kNormalLengths = {0.5, 0.9, 0.99, 0.999, 1.0, 1.001, 1.01, 1.1, 2.0};
constexpr std::array<double, 7> kScales = {1.0, 1e-20, 1e-30, 1e-36, 1e-38, 1e-40, 1e-43};
constexpr std::array<double, 2> kHdrSunRadiances = {1e3, 1e6};
constexpr std::array<double, 6> kHanningWidths = {2, 3, 4, 5, 6, 8};
constexpr std::array<double, 5> kLanczosWidths = {3, 4, 5, 6, 8};
constexpr std::array<double, 5> kReliabilityTargets = {0.001, 0.0025, 0.005, 0.01, 0.02};


std::string Percent(double fraction) { return ReportPercent(fraction); }

std::string Factors(const std::array<double, kSh9Bands>& f) { return fmt::format("{:.3f}, {:.3f}", f[1], f[2]); }

std::vector<WindowVariant> WidthVariants() {
  std::vector<WindowVariant> variants = {{ShWindow::kNone, 0.0}};
  for (double w : kHanningWidths) variants.push_back({ShWindow::kHanning, w});
  for (double w : kLanczosWidths) variants.push_back({ShWindow::kLanczos, w});
  variants.push_back({ShWindow::kDering, 0.0});
  return variants;
}

// Timing of one section into report.seconds.
template <class F>
void Section(StabilityReport& report, std::string name, F&& work) {
  const Clock::time_point start = Clock::now();
  work();
  report.seconds.emplace_back(std::move(name), std::chrono::duration<double>(Clock::now() - start).count());
}

void RunSweep(StabilityReport& report, std::span<const glm::dvec3> normals, const StabilityProgress& progress) {
  const StabilityOptions& o = report.options;
  report.variants = ReportWindowVariants();
  for (std::size_t i = 0; i < o.radii.size(); ++i) {
    if (progress) progress("light sweep", static_cast<double>(i) / o.radii.size());
    report.sweep.push_back(MeasureSpot(o.radii[i], o.face_size, normals, report.variants, report.threads));
  }
  if (progress) progress("light sweep", 1.0);
  const std::vector<WindowVariant> widths = WidthVariants();
  report.widths_spot = MeasureSpot(report.widths_radius_degrees, o.face_size, normals, widths, report.threads).windows;
  const CubeMap sky = MakeSky(o.face_size);
  report.widths_sky =
      MeasureWindows(ProjectDirect(sky), normals, GroundTruthIrradiance(sky, normals, report.threads), widths);
}

void RunLevels(StabilityReport& report, std::span<const glm::dvec3> normals, const StabilityProgress& progress) {
  const StabilityOptions& o = report.options;
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(o.face_size);
  std::vector<std::pair<std::string, CubeMap>> environments;
  for (const std::string& name : BuiltinEnvironmentNames()) {
    environments.emplace_back(name, *MakeBuiltinEnvironment(name, o.face_size));
  }
  for (double radius : kLevelSpotRadii) {
    SpotParams params;
    params.angular_radius_degrees = radius;
    environments.emplace_back(fmt::format("spot {:g} deg", radius), MakeSpot(o.face_size, params));
  }
  SkyParams sky;
  sky.sun_angular_radius_degrees = kSmallSunRadiusDegrees;
  environments.emplace_back(fmt::format("sky, sun {:g} deg", kSmallSunRadiusDegrees), MakeSky(o.face_size, sky));
  // Where the order choice is close: the gradient (order 1 exact) with a faint light whose band 2
  // makes order 1's error pass the targets one after the other.
  for (float power : kFaintLightPowers) {
    SpotParams light;
    light.angular_radius_degrees = 10.0;
    light.irradiance = glm::vec3(power);
    CubeMap env = MakeGradient(o.face_size);
    const CubeMap spot = MakeSpot(o.face_size, light);
    for (int f = 0; f < kCubeFaceCount; ++f) {
      for (std::size_t i = 0; i < env.faces[f].pixels.size(); ++i) env.faces[f].pixels[i] += spot.faces[f].pixels[i];
    }
    environments.emplace_back(fmt::format("gradient + light {:g}", power), std::move(env));
  }
  const double steps = static_cast<double>(environments.size()) + 1.0;
  for (std::size_t i = 0; i < environments.size(); ++i) {
    if (progress) progress("mip levels", i / steps);
    report.levels.push_back(
        MeasureLevels(environments[i].first, environments[i].second, *basis, normals, o.max_error, report.threads,
                      o.error_metric));
  }
  if (progress) progress("mip levels", environments.size() / steps);
  report.placement = MeasureSpotPlacement(report.placement_radius_degrees, *basis, normals);
  if (progress) progress("mip levels", 1.0);
}

Status RunPrecision(StabilityReport& report, std::span<const glm::dvec3> normals, const StabilityProgress& progress) {
  const StabilityOptions& o = report.options;
  if (progress) progress("precision", 0.0);
  report.accumulation.push_back(MeasureFloatAccumulation(MakeSky(o.face_size), normals));
  report.accumulation.push_back(MeasureFloatAccumulation(MakeHdrSky(o.face_size, 1e6), normals));
  report.accumulation.push_back(MeasureFloatAccumulation(MakeSky(o.precision_face_size), normals));
  if (progress) progress("precision", 0.35);
  report.accumulation.push_back(MeasureFloatAccumulation(MakeHdrSky(o.precision_face_size, 1e6), normals));
  if (progress) progress("precision", 0.7);
  const Sh9Rgb sky = ProjectDirect(MakeSky(o.face_size));
  Result<ProgramPrecision> programs = MeasureNormalLengths(sky, normals, kNormalLengths);
  if (!programs) return programs.error();
  report.programs = std::move(programs).value();
  Result<std::vector<ScaledRun>> scaled = MeasureScaledRuns(sky, normals, kScales);
  if (!scaled) return scaled.error();
  report.scaled = std::move(scaled).value();
  for (double radiance : kHdrSunRadiances) {
    const Result<HdrResult> hdr = MeasureHdrSky(o.face_size, radiance, normals, report.threads);
    if (!hdr) return hdr.error();
    report.hdr.push_back(*hdr);
  }
  const Result<ZeroEnvironmentResult> zero = MeasureZeroEnvironment(std::min(o.face_size, 64), normals);
  if (!zero) return zero.error();
  report.zero = *zero;
  if (progress) progress("precision", 1.0);
  return {};
}

// ---- Markdown ----------------------------------------------------------------------------------------

// The sweep's tables, one per error measure: a row per light radius, a column per window.
std::string SweepTables(const StabilityReport& r) {
  std::string out;
  struct Metric {
    const char* title;
    double (*value)(const WindowedError&);
  };
  const std::array<Metric, 6> metrics = {{
      {"max relative error", [](const WindowedError& w) { return w.error.max_relative; }},
      {"mean relative error", [](const WindowedError& w) { return w.error.mean_relative; }},
      {"peak error, max |E - E*| / max E* (worst of r, g, b)", [](const WindowedError& w) { return w.error.max_peak; }},
      {"RMS error / mean irradiance (worst of r, g, b)", [](const WindowedError& w) { return w.error.max_rms; }},
      {"max absolute error / peak", [](const WindowedError& w) { return w.absolute_over_peak; }},
      {"lowest irradiance / peak", [](const WindowedError& w) { return w.lowest_over_peak; }},
  }};
  for (const Metric& metric : metrics) {
    out += fmt::format("{}:\n\n| radius | captured |", metric.title);
    std::string rule = "|---|---|";
    for (const WindowVariant& v : r.variants) {
      out += fmt::format(" {} |", v.Label());
      rule += "---|";
    }
    out += "\n" + rule + "\n";
    for (const SpotSweepRow& row : r.sweep) {
      out += fmt::format("| {:g} | {:.3f} |", row.radius_degrees, row.captured_irradiance);
      for (const WindowedError& w : row.windows) out += fmt::format(" {} |", Percent(metric.value(w)));
      out += "\n";
    }
    out += "\n";
  }
  return out;
}

// One finding per window: where its max error passes 10 % and where it rings below zero.
std::string SweepFindings(const StabilityReport& r) {
  std::string out = "Findings:\n\n";
  for (std::size_t v = 0; v < r.variants.size(); ++v) {
    const WindowedError& smallest = r.sweep.back().windows[v];
    const double ten = RadiusWhereErrorExceeds(r.sweep, v, kSweepThreshold);
    const double negative = RadiusWhereNegative(r.sweep, v);
    out += fmt::format(
        "* **{}** (w1, w2 = {}): max error past 10 % {}; negative irradiance {}; at {:g} deg: max {}, mean {}, "
        "max absolute {} of the peak, lowest {}.\n",
        r.variants[v].Label(), Factors(smallest.factors),
        ten > 0.0 ? fmt::format("from radius {:g} deg down", ten) : "nowhere in the sweep",
        negative > 0.0 ? fmt::format("from radius {:g} deg down", negative) : "nowhere",
        r.sweep.back().radius_degrees, Percent(smallest.error.max_relative), Percent(smallest.error.mean_relative),
        Percent(smallest.absolute_over_peak), Percent(smallest.lowest_over_peak));
  }
  return out;
}

std::string SweepSection(const StabilityReport& r) {
  std::string out = fmt::format(
      "## 1. Small bright lights\n\n"
      "One round light (the built-in spot: azimuth -30, elevation 50, irradiance 5 facing it) on black, its "
      "angular radius swept from 90 to {:g} degrees at constant power, {}x{} faces, coefficients from full "
      "resolution (ProjectDirect), irradiance by eq. 7 in double, against brute-force integration at {} "
      "normals. *max* and *mean* are relative errors (floor 1 % of the peak); *peak* is max |E - E*| / max E* "
      "and *RMS* the root mean square of E - E* over the mean E*, as Ramamoorthi & Hanrahan and Probulator state "
      "errors (irrmap's --error-metric); "
      "*lowest* is the lowest irradiance over the sphere divided by the peak (negative: ringing). "
      "*captured* is the irradiance facing the light as the texels hold it (nominal 5).\n\n",
      r.options.radii.back(), r.options.face_size, r.options.face_size, r.options.error_normals);
  out += SweepTables(r);
  out += fmt::format("\n![max and mean error against light size]({})\n\n![lowest irradiance]({})\n\n",
                     kSweepChart, kRingingChart);
  out += SweepFindings(r);
  out += fmt::format(
      "\nWhy: nine terms hold the clamped cosine only up to band 2; for a point light the truncated kernel is\n"
      "E(t) / P = 1/4 + t/2 + 5/32 (3t^2 - 1) (t the cosine to the light), whose minimum is -0.0396 at t = -8/15\n"
      "(122 deg from the light), -3.96 % of the true peak (SH9's own peak is 1.0625), where the truth is 0.\n"
      "Lights of 20 degrees and less are already that point light for nine terms. Larger ones smooth their own\n"
      "coefficients and dip less (0.6 to 2 % between 80 and 45 degrees); a 90-degree light (a hemisphere) has an\n"
      "irradiance linear in the normal, which nine terms hold exactly.\n"
      "Hanning and Lanczos windows of the usual widths do not remove the dip for three bands (they shrink\n"
      "band 1 too, deepening the far side); only a width of 2 (band 2 dropped) or the deringing window does.\n"
      "No window lowers the error against the ground truth in any measure above: the unwindowed nine terms are\n"
      "already the least-squares fit, so a window buys a non-negative (or less negative) far side with blur,\n"
      "and its cost is the growth of the absolute error (at {:g} deg: {} of the peak unwindowed, {} deringed).\n"
      "Deringing picks, per environment, the smallest Laplacian penalty that makes the irradiance non-negative,\n"
      "so it leaves environments without ringing untouched (the sky below: lambda = 0).\n\n"
      "Window widths, spot of radius {:g} deg and the default sky (factors w1, w2):\n\n"
      "| window | w1, w2 | spot max | spot mean | spot abs / peak | spot lowest | sky max | sky mean | "
      "sky abs / peak | sky lowest |\n|---|---|---|---|---|---|---|---|---|---|\n",
      r.sweep.back().radius_degrees, Percent(r.sweep.back().windows.front().absolute_over_peak),
      Percent(r.sweep.back().windows[kDeringVariant].absolute_over_peak), r.widths_radius_degrees);
  for (std::size_t i = 0; i < r.widths_spot.size(); ++i) {
    const WindowedError& s = r.widths_spot[i];
    const WindowedError& k = r.widths_sky[i];
    out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", s.variant.Label(), Factors(s.factors),
                       Percent(s.error.max_relative), Percent(s.error.mean_relative), Percent(s.absolute_over_peak),
                       Percent(s.lowest_over_peak), Percent(k.error.max_relative), Percent(k.error.mean_relative),
                       Percent(k.absolute_over_peak), Percent(k.lowest_over_peak));
  }
  out += "\n(dering's factors differ per environment: the spot row shows the spot's, the sky's are 1, 1 when its "
         "lambda is 0.)\n\n";
  return out;
}

std::string LevelsSection(const StabilityReport& r) {
  std::string out = fmt::format(
      "## 2. Coarse mip levels\n\n"
      "The {3} of each level's irradiance against level 0's (full resolution, {0}x{0} faces), at {1} "
      "normals. `irrmap --max-error E --error-metric {4}` picks the coarsest level whose *estimated* error ({2:g} x the difference "
      "between the level and the next finer one; no level 0, no ground truth) stays under E, every finer level "
      "included.\n\n| environment |",
      r.options.face_size, r.options.error_normals, kLevelErrorEstimateFactor,
      ErrorMetricDescription(r.options.error_metric), ErrorMetricName(r.options.error_metric));
  std::string rule = "|---|";
  for (const LevelRow& row : r.levels.front().rows) {
    out += fmt::format(" {0}x{0} |", row.size);
    rule += "---|";
  }
  out += "\n" + rule + "\n";
  for (const LevelStudy& study : r.levels) {
    out += fmt::format("| {} |", study.environment);
    for (const LevelRow& row : study.rows) out += fmt::format(" {} |", Percent(row.error_vs_full));
    out += "\n";
  }
  out += fmt::format("\n![error of each level]({})\n\n", kLevelsChart);
  out += fmt::format(
      "The pick for E = {}: the level chosen, its true error against level 0, the next coarser level's, "
      "the estimate at both, the first level past 1 %, and the error against the ground truth at level 0 "
      "and at the pick (the nine-term truncation, which no level choice changes): max relative, then peak and RMS "
      "(as irrmap's level table).\n\n"
      "| environment | first > 1 % | pick | error at pick | estimate | next coarser | its estimate | meets E | "
      "coarser fails | truth max, level 0 | truth max, pick | truth peak, pick | truth rms, pick |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      Percent(r.options.max_error));
  for (const LevelStudy& s : r.levels) {
    const LevelRow& pick = s.rows[s.picked];
    const bool has_coarser = static_cast<std::size_t>(s.picked) + 1 < s.rows.size();
    const LevelRow& coarser = has_coarser ? s.rows[s.picked + 1] : pick;
    out += fmt::format("| {} | {} | {} ({}x{}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", s.environment,
                       s.first_over_one_percent < 0 ? std::string("none")
                                                    : fmt::format("{0}x{0}", s.rows[s.first_over_one_percent].size),
                       s.picked, pick.size, pick.size, Percent(pick.error_vs_full), Percent(pick.estimated),
                       has_coarser ? Percent(coarser.error_vs_full) : "-", has_coarser ? Percent(coarser.estimated) : "-",
                       s.pick_meets ? "yes" : "**no**", s.coarser_fails ? "yes" : "**no**",
                       Percent(s.rows[0].max_vs_truth), Percent(pick.max_vs_truth), Percent(pick.peak_vs_truth),
                       Percent(pick.rms_vs_truth));
  }
  out += "\nThe same pick for other targets E (every environment above): how often the pick meets E, and how often "
         "the next coarser level would not (the pick is as coarse as it may be):\n\n"
         "| E | meets E | next coarser fails |\n|---|---|---|\n";
  for (double target : kReliabilityTargets) {
    int meets = 0;
    int tight = 0;
    for (const LevelStudy& s : r.levels) {
      std::vector<double> estimated;
      for (const LevelRow& row : s.rows) estimated.push_back(row.estimated);
      const std::size_t pick = static_cast<std::size_t>(CoarsestLevelWithin(estimated, target));
      meets += s.rows[pick].error_vs_full <= target;
      tight += pick + 1 == s.rows.size() || s.rows[pick + 1].error_vs_full > target;
    }
    out += fmt::format("| {} | {} of {} | {} of {} |\n", Percent(target), meets, r.levels.size(), tight,
                       r.levels.size());
  }
  out += fmt::format(
      "\nWhy coarse levels fail: a level-k texel stores the mean radiance of its 2^k x 2^k block and the summed\n"
      "basis weight (y_lm x solid angle) of the block, so its contribution is exact only when radiance or weight\n"
      "is constant over the block; the error is the covariance of the two inside each block. Smooth radiance\n"
      "(the sky without its sun, the constant) costs almost nothing; what passes 1 % is a bright feature a few\n"
      "blocks wide, whose power is moved to the block's weighted mean direction (at 256x256 faces: the sky's\n"
      "2-degree sun at 8x8, blocks of 11 degrees; the 3-degree spot and the studio's lights, 12 to 50 degrees\n"
      "across, at 32x32; the 1-degree spot at 64x64). Where the light sits matters in two opposite ways. While blocks are small, a\n"
      "light at a face centre is worse: texels there subtend 5.2 times the solid angle of corner texels, so the\n"
      "light covers fewer of them. Once a block spans a large part of a face, the weight varies most across\n"
      "blocks at face edges and corners (texel solid angles falling to 1/5.2, the basis turning fastest in texel\n"
      "units), and lights there are misplaced most. The same {:g}-degree spot at three places:\n\n"
      "| level | size | face centre | face edge | cube corner |\n|---|---|---|---|---|\n",
      r.placement_radius_degrees);
  for (const SpotPlacementRow& p : r.placement) {
    out += fmt::format("| {} | {}x{} | {} | {} | {} |\n", p.level, p.size, p.size, Percent(p.face_centre),
                       Percent(p.face_edge), Percent(p.cube_corner));
  }
  return out + "\n";
}

std::string PrecisionSection(const StabilityReport& r) {
  std::string out =
      "## 3. Precision\n\n"
      "Float against double accumulation of the projection (ProjectDirect sums each face row in double and the "
      "rows in double; the float variant adds every texel to one float sum per coefficient). A float sum stops "
      "taking increments below half an ulp of itself: a 2048 face adds 25 million texels of ~1/25e6 of the total "
      "each, at float's 6e-8 resolution, so most of the sky is lost; a sun of radiance 1e6 does the same at "
      "small sizes, the sky then being a tiny increment on the sun's large sum:\n\n"
      "| environment | face size | max coefficient error / L00 | irradiance error |\n|---|---|---|---|\n";
  for (std::size_t i = 0; i < r.accumulation.size(); ++i) {
    const AccumulationPrecision& a = r.accumulation[i];
    out += fmt::format("| {} | {}x{} | {} | {} |\n", i % 2 == 0 ? "sky" : "sky, sun radiance 1e6", a.face_size, a.face_size, Percent(a.coefficient_error),
                       Percent(a.irradiance_error));
  }
  out +=
      "\nThe two programs on normals of length L (the sky's coefficients; the paper's 11-slot program packs Table "
      "1, exact for any vector as eq. 7; the 10-slot program folds z^2 = 1 - x^2 - y^2, exact on unit normals "
      "only). Errors are max |program(L n) - E(n)| over the normals, divided by the peak irradiance:\n\n"
      "| length | paper (11 slots) | unit10 (10 slots) | paper - unit10 |\n|---|---|---|---|\n";
  for (const NormalLengthRow& row : r.programs.lengths) {
    out += fmt::format("| {:g} | {} | {} | {} |\n", row.length, Percent(row.paper_error), Percent(row.unit10_error),
                       Percent(row.programs_difference));
  }
  const ZeroNormalResult& z = r.programs.zero_normal;
  out += fmt::format(
      "\nNeither program normalises: both are wrong off the unit sphere, the paper's by a quadratic in L (constant\n"
      "term right, linear term scaled by L, quadratic by L^2), unit10 by that plus 3 c3 L20 (L^2 - 1). Near L = 1\n"
      "each loses about 0.7 % of the peak per 1 % of length error, and they differ by a tenth of that: renormalise\n"
      "interpolated normals before either program. The zero vector gives the constant term only, finite ({}):\n"
      "paper c0 L00 - c3 L20 = ({:.3f}, {:.3f}, {:.3f}), unit10 c0 L00 + 2 c3 L20 = ({:.3f}, {:.3f}, {:.3f}) times the\n"
      "mean irradiance c0 L00.\n\n",
      z.finite ? "yes" : "no", z.paper.x, z.paper.y, z.paper.z, z.unit10.x, z.unit10.y, z.unit10.z);
  out +=
      "Denormals: the sky's coefficients scaled down until the seven constants are denormal floats, run through "
      "the paper's program on both engines, against the scaled double polynomial (max relative, floor 1 %):\n\n"
      "| scale | constants denormal | reference engine | batch engine | engines bit-identical |\n|---|---|---|---|---|\n";
  for (const ScaledRun& s : r.scaled) {
    out += fmt::format("| {:g} | {} | {} | {} | {} |\n", s.scale, s.constants_denormal ? "yes" : "no",
                       Percent(s.reference_error), Percent(s.batch_error), s.engines_identical ? "yes" : "**no**");
  }
  out += fmt::format(
      "\nNeither engine flushes denormals to zero: precision falls off gradually as mantissa bits run out, and both\n"
      "engines agree bit for bit.\n\nHDR: the sky with a {:g}-degree sun of radiance up to 1e6 ({}x{} faces):\n\n"
      "| sun radiance | peak irradiance | program vs double eq. 7 (/ peak) | SH9 vs truth, max |\n|---|---|---|---|\n",
      kHdrSunRadiusDegrees, r.options.face_size, r.options.face_size);
  for (const HdrResult& h : r.hdr) {
    out += fmt::format("| {:g} | {:.4g} | {:.2e} | {} |\n", h.sun_radiance, h.peak_irradiance, h.program_error,
                       Percent(h.relative_to_truth_max));
  }
  const ZeroEnvironmentResult& e = r.zero;
  out += fmt::format(
      "\nZero environment: coefficients all zero: {}; the program gives exactly 0 at every normal and the zero "
      "vector: {}; error statistics finite: {}; deringing lambda {:g}; level pick {} (the coarsest: nothing to "
      "lose).\n\n",
      e.coefficients_zero ? "yes" : "no", e.program_zero ? "yes" : "no", e.error_stats_finite ? "yes" : "no",
      e.dering_lambda, e.picked_level);
  return out;
}

// ---- Charts ------------------------------------------------------------------------------------------

GnuplotChart SweepChart(const StabilityReport& r, bool ringing) {
  GnuplotChart chart;
  std::string plots;
  for (std::size_t v = 0; v < r.variants.size(); ++v) {
    chart.data += fmt::format("# {}\n", r.variants[v].Label());
    for (const SpotSweepRow& row : r.sweep) {
      const WindowedError& w = row.windows[v];
      chart.data += fmt::format("{:g} {:.6g} {:.6g} {:.6g}\n", row.radius_degrees, 100.0 * w.error.max_relative,
                                100.0 * w.error.mean_relative, 100.0 * w.lowest_over_peak);
    }
    chart.data += "\n\n";
    const std::string title = GnuplotQuote(r.variants[v].Label());
    if (ringing) {
      plots += fmt::format("{}datafile index {} using 1:4 with linespoints lw 2 title {}", plots.empty() ? "" : ", ",
                           v, title);
    } else {
      plots += fmt::format(
          "{0}datafile index {1} using 1:2 with linespoints lw 2 lc {2} title {3}, datafile index {1} using 1:3 with "
          "lines dt 2 lc {2} title {4}",
          plots.empty() ? "" : ", ", v, v + 1, GnuplotQuote(r.variants[v].Label() + " max"),
          GnuplotQuote(r.variants[v].Label() + " mean"));
    }
  }
  chart.script = "set logscale x\nset xrange [*:*] reverse\nset grid\nset key outside right\n"
                 "set xlabel 'angular radius of the light (degrees, constant power)'\n";
  if (ringing) {
    chart.script += "set ylabel 'lowest irradiance / peak (%)'\nset title 'Ringing below zero opposite the light'\n";
  } else {
    chart.script += "set logscale y\nset ylabel 'relative error against ground truth (%)'\n"
                    "set title 'SH9 error against light size (solid: max, dashed: mean; dotted: 10 %)'\n";
    plots += ", 10 with lines dt 3 lc 'black' notitle";
  }
  chart.script += "plot " + plots + "\n";
  return chart;
}

GnuplotChart LevelsChart(const StabilityReport& r) {
  GnuplotChart chart;
  std::string plots;
  int block = 0;
  for (const LevelStudy& s : r.levels) {
    chart.data += fmt::format("# {}\n", s.environment);
    for (const LevelRow& row : s.rows) {
      if (row.level > 0) chart.data += fmt::format("{} {:.6g}\n", row.size, 100.0 * row.error_vs_full);
    }
    chart.data += "\n\n";
    plots += fmt::format("{}datafile index {} using 1:2 with linespoints lw 2 title {}", plots.empty() ? "" : ", ",
                         block++, GnuplotQuote(s.environment));
  }
  chart.script =
      "set logscale x 2\nset logscale y 10\nset xrange [*:*] reverse\nset grid\nset key outside right\n"
      "set format y '%g'\nset xlabel 'face size of the level'\nset ylabel " +
      GnuplotQuote(fmt::format("{} error against level 0 (%)", ErrorMetricName(r.options.error_metric))) + "\n"
      "set title 'Error added by coarse mip levels (dotted: 1 %, dashed: 0.5 %)'\nplot " + plots +
      ", 1 with lines dt 3 lc 'black' notitle, 0.5 with lines dt 2 lc 'black' notitle\n";
  return chart;
}

}  // namespace

std::string ReportPercent(double fraction) {
  if (!std::isfinite(fraction)) return "inf";
  const double p = 100.0 * fraction;
  if (p != 0.0 && std::abs(p) < 0.001) return fmt::format("{:.1e} %", p);
  if (std::abs(p) >= 100.0) return fmt::format("{:.0f} %", p);
  return fmt::format("{:.3g} %", p);
}

Status CheckStabilityOptions(const StabilityOptions& options) {
  if (Status size = CheckFaceSizeOption("--face-size", options.face_size, kMaxStabilityFaceSize); !size.ok()) {
    return size;
  }
  if (Status size = CheckFaceSizeOption("--precision-face-size", options.precision_face_size, kMaxStabilityFaceSize);
      !size.ok()) {
    return size;
  }
  const auto usage = [](std::string message) { return Failure(DiagnosticCode::kOptionValue, std::move(message)); };
  if (options.error_normals < 16) {
    return usage(fmt::format("--error-normals {} is too few (>= 16)", options.error_normals));
  }
  if (!(options.max_error > 0.0)) return usage(fmt::format("--max-error {} must be > 0", options.max_error));
  if (options.radii.empty() || !std::is_sorted(options.radii.rbegin(), options.radii.rend()) ||
      options.radii.back() <= 0.0 || options.radii.front() > 90.0) {
    return usage("the radii must lie in (0, 90] degrees, largest first");
  }
  if (options.threads < 0) return usage(fmt::format("--threads {} must be >= 0", options.threads));
  if (options.out_dir.empty()) return usage("the output directory is empty");
  return {};
}

Status RunStability(const StabilityOptions& options, StabilityReport& report, const StabilityProgress& progress) {
  report = StabilityReport{};
  if (Status error = CheckStabilityOptions(options); !error.ok()) return error;
  report.options = options;
  report.threads = options.threads > 0 ? options.threads
                                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::vector<glm::dvec3> normals = SphereNormals(options.error_normals);
  Section(report, "light sweep and windows", [&] { RunSweep(report, normals, progress); });
  Section(report, "windows and the non-negative fit on the built-ins", [&] {
    if (progress) progress("built-ins", 0.0);
    RunWindowCases(report, normals);
    if (progress) progress("built-ins", 1.0);
  });
  Section(report, "mip levels", [&] { RunLevels(report, normals, progress); });
  Status error;
  Section(report, "precision", [&] { error = RunPrecision(report, normals, progress); });
  return error;
}

std::string FormatStabilityMarkdown(const StabilityReport& r) {
  std::string out = fmt::format(
      "# Where the nine-coefficient method fails\n\n"
      "Generated by `irrmap stability --out DIR --face-size {} --precision-face-size {} --error-normals {} "
      "--max-error {:g} --error-metric {}` ({} threads). Every number below is recomputed by that command; the "
      "regression tests (tests/irradiance/report/stability_test.cc) check each finding at smaller sizes.\n\n",
      r.options.face_size, r.options.precision_face_size, r.options.error_normals, r.options.max_error,
      ErrorMetricName(r.options.error_metric), r.threads);
  out += SweepSection(r) + NonNegativeSection(r) + LevelsSection(r) + OrderChoiceSection(r) + PrecisionSection(r);
  out += "Time per section:";
  for (const auto& [name, seconds] : r.seconds) out += fmt::format(" {} {:.1f} s;", name, seconds);
  return out + "\n";
}

Status WriteStabilityReport(const StabilityReport& report, std::vector<fs::path>& written) {
  const fs::path& dir = report.options.out_dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot create the output directory {} ({})", dir.string(), ec.message()));
  }
  auto fail = [&](const Status& failed) {
    for (const fs::path& path : written) fs::remove(path, ec);
    written.clear();
    return failed;
  };
  const std::array<std::pair<std::string_view, GnuplotChart>, 3> charts = {{
      {kSweepChart, SweepChart(report, false)},
      {kRingingChart, SweepChart(report, true)},
      {kLevelsChart, LevelsChart(report)},
  }};
  for (const auto& [name, chart] : charts) {
    if (const Status rendered = RenderGnuplotChart(chart, {dir / name}); !rendered.ok()) return fail(rendered);
    written.push_back(dir / name);
  }
  if (const Status markdown = WriteFileAtomically(dir / kMarkdownFile, FormatStabilityMarkdown(report));
      !markdown.ok()) {
    return fail(markdown);
  }
  written.push_back(dir / kMarkdownFile);
  return {};
}

}  // namespace vs11::irradiance
