// The speed/accuracy sweep. See speed_accuracy.h.
#include "irradiance/report/speed_accuracy.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A 1 x 1 level takes microseconds: cap the runs of one batch so the sweep cannot stall on it.
constexpr int kMaxRunsPerBatch = 100000;
// The coarse level of the chart's order panel (the level irrmap picks for the sky).
constexpr int kOrderChartLevelSize = 16;
// Environment colours of the chart (gnuplot's default palette is hard to tell apart past four).
constexpr std::array<const char*, 8> kColours = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                                 "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f"};

bool IsBuiltinName(std::string_view name) {
  const std::vector<std::string> names = BuiltinEnvironmentNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// The environment as irrmap reads its ENV: an existing file or {face} pattern first, else a built-in.
Status LoadSweepEnvironment(const std::string& name, const SpeedAccuracyOptions& options, EnvironmentLayout layout,
                            CubeMap& cube, std::vector<std::string>& warnings) {
  std::error_code ec;
  if (IsBuiltinName(name) && !fs::exists(name, ec)) {
    std::optional<CubeMap> made = MakeBuiltinEnvironment(name, options.face_size);
    if (!made) {
      return Failure(DiagnosticCode::kNoSuchInput, fmt::format("cannot make the built-in environment '{}'", name));
    }
    cube = std::move(*made);
    return {};
  }
  LoadOptions load;
  load.layout = layout;
  load.face_size = options.face_size;
  Result<LoadedEnvironment> loaded = LoadEnvironment(name, load);
  if (!loaded) return loaded.error();
  for (std::string& warning : loaded->warnings) warnings.push_back(name + ": " + warning);
  cube = std::move(loaded->cube);
  return CheckPyramidFaceSize(name, cube.face_size);
}

// The median over options.batches of the mean time of `update` in a batch, in ms.
template <class F>
double MedianBatchMs(const SpeedAccuracyOptions& options, F&& update) {
  std::vector<double> means;
  for (int batch = 0; batch < options.batches; ++batch) {
    const Clock::time_point start = Clock::now();
    int runs = 0;
    double elapsed = 0.0;
    do {
      update();
      ++runs;
      elapsed = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    } while (elapsed < options.min_batch_ms && runs < kMaxRunsPerBatch);
    means.push_back(elapsed / runs);
  }
  std::sort(means.begin(), means.end());
  return means[means.size() / 2];
}

}  // namespace

Status CheckSpeedAccuracyOptions(const SpeedAccuracyOptions& options) {
  if (Status size = CheckFaceSizeOption("--face-size", options.face_size); !size.ok()) return size;
  const auto usage = [](std::string message) { return Failure(DiagnosticCode::kOptionValue, std::move(message)); };
  if (options.error_normals < 1) return usage(fmt::format("--error-normals {} must be >= 1", options.error_normals));
  if (options.threads < 0) return usage(fmt::format("--threads {} must be >= 0 (0: every core)", options.threads));
  if (options.batches < 1) return usage(fmt::format("--batches {} must be >= 1", options.batches));
  if (!(options.min_batch_ms >= 0.0)) return usage(fmt::format("--min-batch-ms {} must be >= 0", options.min_batch_ms));
  return {};
}

double ChartErrorFigure(const ErrorStats& error, ErrorMetric metric) {
  return metric == ErrorMetric::kRelative ? error.mean_relative : ErrorFigure(error, metric);
}

std::string ChartEnvironmentName(const std::string& environment) {
  const std::string base = fs::path(environment).filename().string();
  return base.empty() ? environment : base;
}

Status RunSpeedAccuracySweep(const SpeedAccuracyOptions& options, SpeedAccuracyResult& result,
                             const SpeedAccuracyProgress& progress) {
  result = SpeedAccuracyResult{};
  if (Status error = CheckSpeedAccuracyOptions(options); !error.ok()) return error;
  result.metric = options.error_metric;
  const EnvironmentLayout layout = options.layout;
  const std::vector<std::string> names =
      options.environments.empty() ? BuiltinEnvironmentNames() : options.environments;
  const int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const EngineOptions engine_options{threads};
  const Result<PaperProgram> program = PaperProgram::Load();
  if (!program) return program.error();
  std::vector<PaperProgram> order_programs;  // the reduced orders, kAllShOrders order
  for (std::size_t o = 0; o + 1 < kAllShOrders.size(); ++o) {
    Result<PaperProgram> loaded = PaperProgram::LoadOrder(kAllShOrders[o]);
    if (!loaded) return loaded.error();
    order_programs.push_back(std::move(loaded).value());
  }
  const std::vector<glm::dvec3> normals = SphereNormals(options.error_normals);

  std::optional<BasisPyramid> basis;  // rebuilt only when the face size changes
  CubeMipChain mips;                  // refilled in place for every environment of one size
  for (std::size_t e = 0; e < names.size(); ++e) {
    const std::string& name = names[e];
    if (progress) progress(name, static_cast<int>(e), static_cast<int>(names.size()));
    CubeMap cube;
    if (Status error = LoadSweepEnvironment(name, options, layout, cube, result.warnings); !error.ok()) return error;
    if (!basis || basis->face_size != cube.face_size) basis = BuildBasisPyramid(cube.face_size, threads);
    SpeedAccuracyEnvironment environment{name, cube.face_size, 0.0};
    environment.mips_ms = MedianBatchMs(options, [&] { RefillEnvironmentMips(cube, mips); });
    result.environments.push_back(environment);

    const std::vector<glm::dvec3> truth = GroundTruthIrradiance(cube, normals, threads);
    for (ProjectionMethod method : kAllProjectionMethods) {
      for (int level = 0; level < LevelCount(cube.face_size); ++level) {
        SpeedAccuracyPoint point{name, method, level, cube.face_size >> level, ShOrder::kOrder2, 0.0, {}};
        Sh9Rgb coefficients;
        point.update_ms = MedianBatchMs(options, [&] {
          coefficients = method == ProjectionMethod::kMipPyramid ? ProjectLevel(mips, *basis, level)
                                                                 : ProjectDirect(mips.levels[level]);
        });
        // The batch engine never fails (the CPU engines' Run returns no error).
        const std::vector<glm::dvec3> estimate =
            program->Irradiance(PackTable1(coefficients), normals, "batch", engine_options).value();
        point.error = CompareIrradiance(estimate, truth, normals);
        result.points.push_back(point);
        if (method != ProjectionMethod::kMipPyramid) continue;
        for (std::size_t o = 0; o + 1 < kAllShOrders.size(); ++o) {
          SpeedAccuracyPoint reduced = point;
          reduced.order = kAllShOrders[o];
          const PaperProgram& order_program = order_programs[o];
          reduced.error = CompareIrradiance(
              order_program.Irradiance(order_program.Constants(PackShOrder(coefficients, reduced.order)), normals,
                                       "batch", engine_options)
                  .value(),
              truth, normals);
          result.points.push_back(reduced);
        }
      }
    }
  }
  return {};
}

std::string SpeedAccuracyCsv(const SpeedAccuracyResult& result) {
  std::string csv =
      "environment,method,level,size,update_ms,mips_ms,mean_relative_error,max_relative_error,order,slots,"
      "peak_error,rms_error\n";
  for (const SpeedAccuracyPoint& point : result.points) {
    double mips_ms = 0.0;
    for (const SpeedAccuracyEnvironment& environment : result.environments) {
      if (environment.name == point.environment) mips_ms = environment.mips_ms;
    }
    std::string name = point.environment;
    std::replace(name.begin(), name.end(), ',', '_');  // keep the columns unambiguous
    csv += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{},{:.6g},{:.6g}\n", name,
                       kProjectionMethodNames.Name(point.method), point.level, point.size, point.update_ms, mips_ms,
                       point.error.mean_relative, point.error.max_relative, ShOrderName(point.order),
                       Info(point.order).slots, point.error.max_peak, point.error.max_rms);
  }
  return csv;
}

namespace {

// Left panel: error against update time, per environment and projection method, order 2 only.
// Appends one data block per curve to `data`, counting `block`; returns the plot clauses.
std::string SpeedPanelPlots(const SpeedAccuracyResult& result, std::string& data, int& block) {
  std::string plots;
  for (std::size_t e = 0; e < result.environments.size(); ++e) {
    const SpeedAccuracyEnvironment& environment = result.environments[e];
    const std::string colour = GnuplotQuote(kColours[e % kColours.size()]);
    for (ProjectionMethod method : kAllProjectionMethods) {
      data += fmt::format("# {} {}: update_ms {}_error_percent level\n", ChartEnvironmentName(environment.name),
                          kProjectionMethodNames.Name(method), ErrorMetricName(result.metric));
      for (const SpeedAccuracyPoint& point : result.points) {
        if (point.environment != environment.name || point.method != method || point.order != ShOrder::kOrder2) {
          continue;
        }
        data += fmt::format("{:.6g} {:.6g} {}\n", point.update_ms, 100.0 * ChartErrorFigure(point.error, result.metric),
                            point.level);
      }
      data += "\n\n";
      const bool mip = method == ProjectionMethod::kMipPyramid;
      const std::string title =
          fmt::format("{} ({})", ChartEnvironmentName(environment.name), mip ? "mip pyramid" : "direct on level");
      plots += fmt::format(
          "{}datafile index {} using 1:2 with linespoints lc rgb {} dt {} pt {} ps 0.8 title {}, "
          "datafile index {} using 1:2:3 with labels offset char {},0.55 font ',8' tc rgb {} notitle",
          plots.empty() ? "" : ", \\\n  ", block, colour, mip ? 1 : 2, mip ? 7 : 6, GnuplotLiteral(title), block,
          mip ? 0.6 : -0.6, colour);
      ++block;
    }
  }
  return plots;
}

// Right panel: error against slots per vertex, per environment, at level 0 and at 16x16. Appends
// to `data` and counts `block` as SpeedPanelPlots does.
std::string OrderPanelPlots(const SpeedAccuracyResult& result, std::string& data, int& block) {
  std::string plots;
  for (std::size_t e = 0; e < result.environments.size(); ++e) {
    const SpeedAccuracyEnvironment& environment = result.environments[e];
    const std::string colour = GnuplotQuote(kColours[e % kColours.size()]);
    // Full resolution, and the 16x16 level where it is a coarser one.
    std::vector<int> sizes = {environment.face_size};
    if (kOrderChartLevelSize < environment.face_size) sizes.push_back(kOrderChartLevelSize);
    for (int size : sizes) {
      std::string curve = fmt::format("# {} orders from {}x{}: slots {}_error_percent order\n",
                                      ChartEnvironmentName(environment.name), size, size,
                                      ErrorMetricName(result.metric));
      bool any = false;
      for (ShOrder order : kAllShOrders) {
        for (const SpeedAccuracyPoint& point : result.points) {
          if (point.environment == environment.name && point.method == ProjectionMethod::kMipPyramid &&
              point.size == size && point.order == order) {
            curve += fmt::format("{} {:.6g} {}\n", Info(order).slots,
                                 100.0 * ChartErrorFigure(point.error, result.metric), ShOrderName(order));
            any = true;
          }
        }
      }
      if (!any) continue;
      data += curve + "\n\n";
      const bool full = size == environment.face_size;
      plots += fmt::format("{}datafile index {} using 1:2 with linespoints lc rgb {} dt {} pt {} ps 0.8 title {}",
                           plots.empty() ? "" : ", \\\n  ", block, colour, full ? 1 : 2, full ? 7 : 6,
                           GnuplotLiteral(fmt::format("{} from {}x{}", ChartEnvironmentName(environment.name), size,
                                                      size)));
      ++block;
    }
  }
  return plots;
}

// The y axis: what ChartErrorFigure plots.
std::string_view ChartAxisName(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::kRelative: return "mean relative irradiance error";
    case ErrorMetric::kPeak: return "peak irradiance error, max |E - E*| / max E*";
    case ErrorMetric::kRms: return "RMS irradiance error / mean irradiance";
  }
  return "error";
}

// "256x256, 64x64": the environments' face sizes, each once.
std::string FaceSizesText(const SpeedAccuracyResult& result) {
  std::string face_sizes;
  for (const SpeedAccuracyEnvironment& environment : result.environments) {
    const std::string size = fmt::format("{0}x{0}", environment.face_size);
    if (face_sizes.find(size) == std::string::npos) face_sizes += (face_sizes.empty() ? "" : ", ") + size;
  }
  return face_sizes;
}

}  // namespace

GnuplotChart SpeedAccuracyChart(const SpeedAccuracyResult& result) {
  GnuplotChart chart;
  chart.width = 1600;
  chart.height = 650;
  int block = 0;
  const std::string plots = SpeedPanelPlots(result, chart.data, block);
  const std::string order_plots = OrderPanelPlots(result, chart.data, block);
  chart.script = fmt::format(
      "set multiplot layout 1,2\n"
      "set logscale xy\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set format y '%g'\n"
      "set xlabel 'time per coefficient update, ms (log scale; mips built beforehand)'\n"
      "set ylabel {}\n"
      "set title {}\n"
      "set key below maxrows 3\n"
      "plot {}\n"
      "unset logscale x\n"
      "set xrange [0:12]\n"
      "set xtics ('order0' 1, 'order1' 3, 'zh3' 6, 'order2' 11)\n"
      "set xlabel 'instruction slots per vertex of the program'\n"
      "set title {}\n"
      "plot {}\n"
      "unset multiplot\n",
      GnuplotQuote(fmt::format("{}, % (log scale)", ChartAxisName(result.metric))),
      GnuplotQuote(fmt::format("SH9 coefficients from each mip level (labels: level), faces {}",
                               FaceSizesText(result))),
      plots.empty() ? "NaN notitle" : plots,
      GnuplotQuote("Each program's error against its cost per vertex (the update time is the same projection's)"),
      order_plots.empty() ? "NaN notitle" : order_plots);
  return chart;
}

Status WriteSpeedAccuracy(const SpeedAccuracyResult& result, const fs::path& out_dir, std::vector<fs::path>& written) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot create the output directory {} ({})", out_dir.string(), ec.message()));
  }
  const fs::path csv = out_dir / kSpeedAccuracyCsv;
  const std::vector<fs::path> images = {out_dir / kSpeedAccuracySvg, out_dir / kSpeedAccuracyPng};
  for (const fs::path& path : {csv, images[0], images[1]}) {
    if (fs::is_directory(path, ec)) {
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot write {}: it is a directory", path.string()));
    }
  }
  if (Status chart = RenderGnuplotChart(SpeedAccuracyChart(result), images); !chart.ok()) return chart;
  if (const Status csv_written = WriteFileAtomically(csv, SpeedAccuracyCsv(result)); !csv_written.ok()) {
    for (const fs::path& image : images) fs::remove(image, ec);
    return Failure(csv_written.error().code, fmt::format("cannot write {}: {}", csv.string(), csv_written.message()));
  }
  written = {csv, images[0], images[1]};
  return {};
}

}  // namespace vs11::irradiance
