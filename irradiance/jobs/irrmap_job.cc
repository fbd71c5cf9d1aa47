// The irrmap job. See irrmap_job.h.
#include "irradiance/jobs/irrmap_job.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <new>
#include <span>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/engine_exports.h"
#include "irradiance/jobs/irrmap_checks.h"
#include "irradiance/jobs/irrmap_environment.h"
#include "irradiance/jobs/irrmap_gpu_frame.h"
#include "irradiance/jobs/irrmap_outputs.h"
#include "irradiance/render/preview.h"
#include "irradiance/report/preview_errors.h"
#include "irradiance/sh/constants_output.h"
#include "irradiance/sh/nonneg_fit.h"
#include "irradiance/sh/sh_projection.h"
#include "programs/embedded_programs.h"
#include "vm/asm/assembler.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/core/input_file.h"
#include "vm/engines/engine_factory.h"
#include "vm/reference/verify.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Each level's coefficient update is repeated until this much time has passed (or kMaxTimingRuns
// runs), and the mean is reported: a 1 x 1 level takes a few microseconds.
constexpr double kMinTimingMs = 20.0;
constexpr int kMaxTimingRuns = 1000;
// The preview shows the levels whose faces have these sizes (besides level 0 and the chosen one),
// the sizes of the paper's Fig. 3.
constexpr std::array<int, 2> kPreviewLevelSizes = {64, 16};

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Runs `stage`, appending its time to the report.
template <class F>
auto Timed(IrrmapReport& report, std::string name, F&& stage) {
  const Clock::time_point start = Clock::now();
  if constexpr (std::is_void_v<decltype(stage())>) {
    stage();
    report.timings.push_back({std::move(name), MillisecondsSince(start)});
  } else {
    auto result = stage();
    report.timings.push_back({std::move(name), MillisecondsSince(start)});
    return result;
  }
}


Diagnostic LevelOutOfRange(const IrrmapOptions& options, int face_size) {
  return Failure(DiagnosticCode::kOptionValue,
                 fmt::format("{} is out of range: {}", LevelWithValue(options), LevelRange(face_size)));
}

// Fills `cube`, or `latlong` for a lat-long map, which is projected where it lies.
Status LoadCube(const IrrmapOptions& options, const CheckedOptions& checked, IrrmapReport& report, CubeMap& cube,
                std::optional<Image>& latlong) {
  if (options.latlong) {
    latlong = *options.latlong;
    report.environment = options.environment;
    report.layout = LayoutName(options.layout);
    report.layout_reason = "as given";
    report.sh_source = ShSourceKindOf(EnvironmentLayout::kLatLong);
    if (options.level && *options.level >= LevelCount(options.face_size)) {
      return LevelOutOfRange(options, options.face_size);
    }
    return {};
  }
  if (options.cube) {
    cube = *options.cube;
    report.environment = options.environment;
    report.layout = LayoutName(options.layout);
    report.layout_reason = "as given";
    report.sh_source = ShSourceKindOf(options.layout);
    if (Status size = CheckPyramidFaceSize(options.environment, cube.face_size); !size.ok()) return size;
    if (options.level && *options.level >= LevelCount(cube.face_size)) return LevelOutOfRange(options, cube.face_size);
    return {};
  }
  if (checked.builtin) {
    std::optional<CubeMap> made = MakeBuiltinEnvironment(options.environment, options.face_size);
    if (!made) {
      return Failure(DiagnosticCode::kNoSuchInput,
                     fmt::format("cannot make the built-in environment '{}'", options.environment));
    }
    cube = std::move(*made);
    report.environment = fmt::format("{} (built-in)", options.environment);
    report.layout = "builtin";
    report.layout_reason = "a built-in environment";
    if (options.layout != EnvironmentLayout::kAuto) {
      report.warnings.push_back(fmt::format("{} ignored for a built-in environment",
                                            OptionWithValue(OptionName(options.naming, "layout"), LayoutName(options.layout))));
    }
    return {};
  }
  LoadOptions load;
  load.layout = options.layout;
  load.face_size = options.face_size;
  load.keep_latlong = true;
  Result<LoadedEnvironment> loaded = LoadEnvironment(options.environment, load);
  if (!loaded) {
    report.usage_error = loaded.error().code == DiagnosticCode::kOptionValue;
    return loaded.error();
  }
  for (std::string& warning : loaded->warnings) report.warnings.push_back(std::move(warning));
  cube = std::move(loaded->cube);
  latlong = std::move(loaded->latlong);
  report.environment = options.environment;
  report.layout = std::string(LayoutName(loaded->layout));
  report.layout_reason = loaded->layout_reason;
  report.sh_source = ShSourceKindOf(loaded->layout);
  const bool resampled = loaded->layout == EnvironmentLayout::kLatLong || loaded->layout == EnvironmentLayout::kAngular;
  if (options.face_size_given && !resampled && cube.face_size != options.face_size) {
    report.warnings.push_back(fmt::format("{} ignored: {} is a cube map ({}) with faces of {}x{}; only "
                                          "lat-long and angular maps are resampled",
                                          OptionWithValue(OptionName(options.naming, "face-size"), options.face_size),
                                          options.environment, report.layout, cube.face_size, cube.face_size));
  }
  const int face_size = latlong ? options.face_size : cube.face_size;
  if (Status size = CheckPyramidFaceSize(options.environment, face_size); !size.ok()) return size;
  if (options.level && *options.level >= LevelCount(face_size)) return LevelOutOfRange(options, face_size);
  return {};
}

// Mean time of one level's projection, in ms, repeated until `min_ms` have passed.
double TimeProjection(const IrrmapEnvironment& environment, int level, Sh9Rgb& coefficients, double min_ms) {
  const Clock::time_point start = Clock::now();
  int runs = 0;
  double elapsed = 0.0;
  do {
    coefficients = environment.Project(level);
    ++runs;
    elapsed = MillisecondsSince(start);
  } while (elapsed < min_ms && runs < kMaxTimingRuns);
  return elapsed / runs;
}

// "SH9 from 64x64 (level 2)"; `chosen` adds " *".
std::string PreviewLabel(const LevelReport& level, bool chosen) {
  const std::string name = level.level == 0 ? fmt::format("SH9 from {0}x{0}", level.size)
                                            : fmt::format("SH9 from {0}x{0} (level {1})", level.size, level.level);
  return chosen ? name + " *" : name;
}

// Levels shown in the preview: 0, those of kPreviewLevelSizes, and the chosen one, in order.
std::vector<int> PreviewLevels(const IrrmapReport& report) {
  std::vector<int> levels = {0, report.level};
  for (const LevelReport& level : report.levels) {
    if (std::find(kPreviewLevelSizes.begin(), kPreviewLevelSizes.end(), level.size) != kPreviewLevelSizes.end()) {
      levels.push_back(level.level);
    }
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  return levels;
}

// The error fields of coeffs.json (see irrmap_job.h); `channels` adds the per-channel figures.
void AddErrorFields(const ErrorStats& error, nlohmann::ordered_json& row, bool channels) {
  row["max_relative_error"] = error.max_relative;
  row["mean_relative_error"] = error.mean_relative;
  row["peak_error"] = error.max_peak;
  row["rms_error"] = error.max_rms;
  if (!channels) return;
  auto per_channel = [](glm::dvec3 rgb, double luminance) {
    return nlohmann::ordered_json{{"r", rgb.r}, {"g", rgb.g}, {"b", rgb.b}, {"luminance", luminance}};
  };
  row["peak_error_channels"] = per_channel(error.peak_rgb, error.peak_luminance);
  row["rms_error_channels"] = per_channel(error.rms_rgb, error.rms_luminance);
}

nlohmann::ordered_json CoefficientsJson(const IrrmapReport& report, const IrrmapOptions& options,
                                        const CheckedOptions& checked) {
  nlohmann::ordered_json json;
  nlohmann::ordered_json metadata = OutputMetadata(report, options);
  json["schema_version"] = metadata["schema_version"];
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const glm::dvec3& c : report.coefficients.coefficients) rows.push_back({c.r, c.g, c.b});
  json["coefficients"] = std::move(rows);
  json["level"] = report.level;
  json["level_size"] = report.levels[report.level].size;
  json["level_choice"] = options.level ? "level" : "max_error";
  if (!options.level) json["max_error"] = options.max_error;
  json["error_metric"] = std::string(ErrorMetricName(report.error_metric));
  const std::array<double, kSh9Bands>& factors = report.levels[report.level].window_factors;
  json["window"] = {{"name", std::string(ShWindowName(options.window))},
                    {"width", options.window_width},
                    {"factors", {factors[0], factors[1], factors[2]}}};
  json["face_size"] = report.face_size;
  json["layout"] = report.layout;
  json["environment"] = report.environment;
  json["engine"] = std::string(checked.engine);
  json["map_size"] = options.map_size;
  json["constants"] = ConstantsJson(report.constants);
  const ShOrderInfo& order = Info(report.order);
  json["order"] = std::string(ShOrderName(order.order));
  nlohmann::ordered_json program = {{"name", std::string(ShOrderName(order.order))},
                                    {"file", std::string(order.program_file)},
                                    {"slots", order.slots},
                                    {"estimated_error", report.order_estimated_error},
                                    {"error_vs_full_order2", report.program_vs_full_order2}};
  if (report.errors_measured) AddErrorFields(report.program_error, program, false);
  nlohmann::ordered_json registers = nlohmann::ordered_json::object();
  for (const NamedRegister& r : report.program_constants) {
    registers[r.name] = {r.value.x, r.value.y, r.value.z, r.value.w};
  }
  program["constants"] = std::move(registers);
  json["program"] = std::move(program);
  nlohmann::ordered_json estimates = nlohmann::ordered_json::array();
  for (const ProgramLevelEstimate& e : report.program_estimates) {
    estimates.push_back(
        {{"order", std::string(ShOrderName(e.order))}, {"level", e.level}, {"estimated_error", e.estimated}});
  }
  json["program_estimates"] = std::move(estimates);
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  for (const LevelReport& level : report.levels) {
    nlohmann::ordered_json row = {{"level", level.level}, {"size", level.size}, {"update_ms", level.update_ms}};
    if (!options.coefficients_only && !options.no_ground_truth) AddErrorFields(level.error, row, true);
    row["estimated_error"] = level.estimated_error;
    levels.push_back(std::move(row));
  }
  json["levels"] = std::move(levels);
  if (report.mesh) {
    const MeshReport& mesh = *report.mesh;
    nlohmann::ordered_json row = {{"file", mesh.file},
                                  {"vertex_count", mesh.vertex_count},
                                  {"triangle_count", mesh.triangle_count},
                                  {"unusable_normals", mesh.unusable_normals},
                                  {"ms_per_evaluation", mesh.ms_per_evaluation},
                                  {"ns_per_vertex", mesh.vertex_count > 0 ? mesh.ms_per_evaluation * 1e6 / mesh.vertex_count : 0.0},
                                  {"exact", mesh.has_truth}};
    if (mesh.has_truth) {
      AddErrorFields(mesh.error, row, false);
      row["error_scale"] = mesh.error_scale;
    }
    json["mesh"] = std::move(row);
  }
  if (report.gpu) json["gpu"] = GpuFrameJson(*report.gpu);
  json["convention"] = std::move(metadata["convention"]);
  json["provenance"] = std::move(metadata["provenance"]);
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const Timing& timing : report.timings) timings[timing.name] = timing.ms;
  json["timings_ms"] = std::move(timings);
  return json;
}

// One output: written by `write` to a temporary path with the same extension, then renamed.
struct PendingOutput {
  std::string_view name;
  std::function<Status(const fs::path&)> write;
};

Status WriteOutputs(const fs::path& out_dir, const std::vector<PendingOutput>& outputs,
                    std::vector<fs::path>& written) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot create the output directory {} ({})", out_dir.string(), ec.message()));
  }
  for (const PendingOutput& output : outputs) {  // a folder in the way would fail the last renames
    if (fs::is_directory(out_dir / output.name, ec)) {
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot write {}: it is a directory", (out_dir / output.name).string()));
    }
  }
  std::vector<PendingRename> renames;
  for (const PendingOutput& output : outputs) {
    const fs::path target = out_dir / output.name;
    const fs::path temporary = TemporaryPathBeside(target);
    Status status;
    try {
      status = output.write(temporary);
    } catch (const std::bad_alloc&) {
      status = Failure(DiagnosticCode::kCannotWriteFile, "out of memory");
    }
    if (!status) {
      RemoveQuietly(temporary);
      for (const PendingRename& finished : renames) RemoveQuietly(finished.temporary);
      Diagnostic error = status.error();
      error.message = fmt::format("cannot write {}: {}", target.string(), error.message);
      return error;
    }
    renames.push_back({temporary, target});
  }
  return CommitRenames(renames, &written);
}

std::string ConstantsFileComment(const IrrmapReport& report, const PaperProgram& program) {
  if (report.order != ShOrder::kOrder2) {
    const ShOrderInfo& order = Info(report.order);
    return fmt::format(
        "Irradiance constants for programs/{file} ({name}, {slots} slots; irradiance/sh/sh_order.h), written by "
        "irrmap\nbeside it as program.vsh. Environment: {environment}, face size {face}, coefficients from level "
        "{level} ({size}x{size}).\nEstimated error against the nine terms at level 0: {estimate:.3g} %.\n"
        "Run with: vs11 run program.vsh --fragment --consts constants.vsh --sphere 6 --sphere-reg v{normal}",
        fmt::arg("file", order.program_file), fmt::arg("name", ShOrderName(order.order)), fmt::arg("slots", order.slots),
        fmt::arg("environment", report.environment), fmt::arg("face", report.face_size),
        fmt::arg("level", report.level), fmt::arg("size", report.levels[report.level].size),
        fmt::arg("estimate", 100.0 * report.order_estimated_error), fmt::arg("normal", program.normal_register()));
  }
  return fmt::format(
      "Irradiance constants for programs/{file} (Ai, Peng & Zhang 2008, Table 1), written by irrmap\n"
      "beside it as program.vsh.\n"
      "Environment: {environment}, face size {face}, coefficients from level {level} ({size}x{size}).\n"
      "c{first}..c{last} = cAr cAg cAb cBr cBg cBb cC; normal in v{normal}, irradiance in {output}.rgb.\n"
      "Run with: vs11 run programs/{file} --fragment --consts constants.vsh --sphere 6 --sphere-reg v{normal}\n"
      "(--fragment: the program is the irradiance part only and writes no oPos), or with the\n"
      "complete shader programs/sh9_vertex_od0.vsh, which reads the same c0..c6.",
      fmt::arg("file", Info(ShOrder::kOrder2).program_file), fmt::arg("environment", report.environment),
      fmt::arg("face", report.face_size), fmt::arg("level", report.level),
      fmt::arg("size", report.levels[report.level].size), fmt::arg("first", program.constant_base()),
      fmt::arg("last", program.constant_base() + 6), fmt::arg("normal", program.normal_register()),
      fmt::arg("output", OutputSlotName(program.output_slot())));
}

// Writes coeffs.json, constants.vsh and `more` into out_dir, all or none (WriteOutputs), timed as
// "write"; the paths go to report.files.
Status WriteJobOutputs(const IrrmapOptions& options, const CheckedOptions& checked, const PaperProgram& program,
                       std::vector<PendingOutput> more, IrrmapReport& report) {
  std::string coefficients_text;
  const std::string constants_text =
      report.order == ShOrder::kOrder2
          ? ConstantsDefText(report.constants, program.constant_base(), ConstantsFileComment(report, program))
          : RegisterDefText(report.program_constants, program.constant_base(), ConstantsFileComment(report, program));
  const std::string_view program_text = PaperProgram::EmbeddedText(Info(report.order).program_file);
  std::vector<PendingOutput> outputs = {
      {kCoefficientsFile, [&](const fs::path& path) { return WriteFileAtomically(path, coefficients_text); }},
      {kConstantsFile, [&](const fs::path& path) { return WriteFileAtomically(path, constants_text); }},
      {kProgramFile, [&](const fs::path& path) { return WriteFileAtomically(path, program_text); }},
  };
  for (PendingOutput& output : more) outputs.push_back(std::move(output));
  nlohmann::ordered_json coefficients = CoefficientsJson(report, options, checked);
  coefficients["files"] = nlohmann::ordered_json::array();  // this run's, to tell them from an earlier run's
  for (const PendingOutput& output : outputs) coefficients["files"].push_back(std::string(output.name));
  coefficients_text = coefficients.dump(2) + "\n";
  std::vector<fs::path> written;
  Status write_status = Timed(report, "write", [&] { return WriteOutputs(options.out_dir, outputs, written); });
  if (!write_status.ok()) return write_status;
  const std::vector<std::string> leftovers = LeftoverOutputWarnings(options.out_dir, written);
  report.warnings.insert(report.warnings.end(), leftovers.begin(), leftovers.end());
  report.files = std::move(written);
  return {};
}

// Picks report.order and report.level (--order, --level, else by --max-error), marks the level,
// records every level's and every (program, level) pair's estimated error, and applies the window
// to every level's coefficients.
void ChooseLevelAndWindow(const IrrmapOptions& options, const CheckedOptions& checked, IrrmapReport& report) {
  std::vector<Sh9Rgb> coefficients;
  for (const LevelReport& row : report.levels) coefficients.push_back(row.coefficients);
  const std::vector<glm::dvec3> normals = SphereNormals(kLevelErrorNormals);
  report.error_metric = options.error_metric;
  const std::vector<double> estimated = EstimateLevelErrors(coefficients, normals, options.error_metric);
  report.program_estimates = EstimateProgramLevelErrors(coefficients, estimated, normals, options.error_metric);
  std::vector<ShOrder> allowed;
  if (checked.order) allowed.push_back(*checked.order);
  const ProgramChoice choice = ChooseProgramAndLevel(report.program_estimates, estimated, options.max_error, allowed);
  report.order = choice.order;
  report.level = options.level ? *options.level : choice.level;
  for (const ProgramLevelEstimate& pair : report.program_estimates) {
    if (pair.order == report.order && pair.level == report.level) report.order_estimated_error = pair.estimated;
  }
  for (LevelReport& row : report.levels) {
    row.chosen = row.level == report.level;
    row.estimated_error = estimated[row.level];
    if (options.window == ShWindow::kNonNegative) {
      row.coefficients = FitNonNegative(row.coefficients);
      continue;
    }
    row.window_factors = options.window == ShWindow::kDering
                             ? LaplacianWindowFactors(DeringLambda(row.coefficients, normals))
                             : ShWindowFactors(options.window, options.window_width);
    row.coefficients = ApplyShWindow(row.coefficients, row.window_factors);
  }
}

}  // namespace

int DefaultLevel(int face_size) {
  assert(IsPowerOfTwo(face_size));
  int level = 0;
  while ((face_size >> level) > kRecommendedLevelSize) ++level;
  return level;
}

double IrrmapReport::TimingMs(std::string_view name) const {
  for (const Timing& timing : timings) {
    if (timing.name == name) return timing.ms;
  }
  return 0.0;
}


// ---- RunIrrmap -------------------------------------------------------------------------------------

namespace {

// What the stages of one run hand on to each other. Each stage reads what earlier stages left here,
// adds its results to the report, and queues the files it produces in `outputs`; RunIrrmap writes
// them all at its one exit.
struct IrrmapRun {
  IrrmapRun(const IrrmapOptions& options_in, IrrmapReport& report_in, const IrrmapProgress& progress_in)
      : options(options_in), report(report_in), progress(progress_in) {}

  const IrrmapOptions& options;
  IrrmapReport& report;
  const IrrmapProgress& progress;
  CheckedOptions checked;
  EngineOptions engine_options;
  int face_size = 0;                    // of the environment's cube (or the cube a panorama stands for)
  IrrmapEnvironment environment;
  std::optional<PaperProgram> program;  // the nine terms: the level table's and the preview's errors
  std::optional<PaperProgram> chosen_program;
  ConstantBank chosen_bank;
  MeshLighting lighting;
  CubeMap irradiance_map;
  std::vector<glm::dvec3> gpu_irradiance;  // the irradiance map's texels, from GpuFrameStage
  std::vector<glm::dvec3> error_normals;
  std::vector<glm::dvec3> error_truth;  // the ground truth at error_normals
  HemisphereGrid grid;                  // the ground truth at the preview's directions
  PreviewResult preview;
  std::vector<PendingOutput> outputs;   // beside coeffs.json, constants.vsh and program.vsh

  // The progress callback for a stage with fractions, or an empty one.
  std::function<void(double)> FractionsOf(std::string_view stage) const {
    if (!progress) return {};
    return [this, stage](double fraction) { progress(stage, fraction); };
  }
};

Status LoadStage(IrrmapRun& run) {
  CubeMap cube;
  std::optional<Image> latlong;
  // Loading has no fraction to report: the bar shows the stage at 0 % and at its end.
  if (run.progress) run.progress("load", 0.0);
  Status error =
      Timed(run.report, "load", [&] { return LoadCube(run.options, run.checked, run.report, cube, latlong); });
  if (!error.ok()) return error;
  if (run.progress) run.progress("load", 1.0);
  // Hashed after loading, so that a file the loader refused is reported as the loader says.
  if (!run.options.cube && !run.options.latlong && !run.checked.builtin) {
    error = Timed(run.report, "hash", [&]() -> Status {
      for (const fs::path& file : EnvironmentFiles(run.options.environment)) {
        if (Status digested = DigestInputFile(file, run.report.input_files.emplace_back()); !digested.ok()) {
          return digested;
        }
      }
      return {};
    });
    if (!error.ok()) return error;
  }
  IrrmapEnvironment& environment = run.environment;
  environment.threads = run.checked.threads;
  if (latlong) {
    run.face_size = run.report.face_size = environment.face_size = run.options.face_size;
    run.report.texel_range = RangeOfTexels(*latlong);
    // The pyramid takes the panorama as its level 0 rather than a second copy.
    environment.panorama = Timed(run.report, "latlong_pyramid", [&] {
      return BuildLatLongPyramid(std::move(*latlong), run.face_size, run.checked.threads);
    });
    return {};
  }
  run.face_size = run.report.face_size = environment.face_size = cube.face_size;
  run.report.texel_range = RangeOfTexels(cube);
  // The pyramid takes the map as its level 0 rather than a second copy.
  environment.mips = Timed(run.report, "env_mips", [&] { return BuildEnvironmentMips(std::move(cube)); });
  environment.basis = Timed(run.report, "basis_pyramid", [&]() -> std::shared_ptr<const BasisPyramid> {
    if (run.options.shared_basis) return run.options.shared_basis(run.face_size);
    std::optional<BasisPyramid> built =
        BuildBasisPyramid(run.face_size, run.checked.threads, run.FractionsOf("basis pyramid"));
    if (!built) return nullptr;
    return std::make_shared<const BasisPyramid>(std::move(*built));
  });
  if (!environment.mips || !environment.basis) {
    return Failure(DiagnosticCode::kOutOfMemory,
                   fmt::format("cannot build the mip pyramids of face size {}", run.face_size));
  }
  return {};
}

// The environment as a cube, for the stages that read one: a panorama is resampled the first time,
// timed as "resample_cube".
const CubeMap& EnvironmentCube(IrrmapRun& run) {
  if (run.environment.NeedsResample()) Timed(run.report, "resample_cube", [&] { run.environment.Cube(); });
  return run.environment.Cube();
}

// Every level's coefficients (each update timed on its own), the level and window chosen, the
// constants packed.
Status CoefficientsStage(IrrmapRun& run) {
  IrrmapReport& report = run.report;
  Timed(report, "level_updates", [&] {
    for (int level = 0; level < LevelCount(run.face_size); ++level) {
      LevelReport row;
      row.level = level;
      row.size = run.face_size >> level;
      row.update_ms = TimeProjection(run.environment, level, row.coefficients,
                                     run.options.coefficients_only ? 0.0 : kMinTimingMs);
      report.levels.push_back(row);
    }
  });
  ChooseLevelAndWindow(run.options, run.checked, report);
  const LevelReport& chosen = report.levels[report.level];
  report.coefficients = chosen.coefficients;
  report.timings.push_back({"projection", chosen.update_ms});
  report.constants = Timed(report, "constants", [&] {
    report.program_constants = PackShOrder(report.coefficients, report.order);
    return PackTable1(report.coefficients);
  });
  report.program_vs_full_order2 =
      IrradianceDifference(ReduceToOrder(report.coefficients, report.order), report.levels[0].coefficients,
                           SphereNormals(kLevelErrorNormals), run.options.error_metric);
  // Every level's constants feed the level table and the preview, not only the chosen one's.
  for (const LevelReport& row : report.levels) {
    const SevenConstants constants = PackTable1(row.coefficients);
    if (const Status fits = CheckCoefficientsFitFloat(row.coefficients, constants.registers, report.texel_range);
        !fits.ok()) {
      return Failure(fits.error().code, fmt::format("{}: level {}: {}", report.environment, row.level, fits.message()));
    }
  }
  std::vector<glm::vec4> program_registers;
  for (const NamedRegister& r : report.program_constants) program_registers.push_back(r.value);
  if (const Status fits = CheckCoefficientsFitFloat(report.coefficients, program_registers, report.texel_range);
      !fits.ok()) {
    return Failure(fits.error().code, fmt::format("{}: {}", report.environment, fits.message()));
  }
  Result<PaperProgram> program = Timed(report, "program", [] { return PaperProgram::Load(); });
  if (!program) return program.error();
  run.program = std::move(program).value();
  Result<PaperProgram> chosen_program = PaperProgram::LoadOrder(report.order);
  if (!chosen_program) return chosen_program.error();
  run.chosen_program = std::move(chosen_program).value();
  run.chosen_bank = run.chosen_program->Constants(report.program_constants);
  return {};
}

// --engine gl: the chosen level's frame on the GPU (irrmap_gpu_frame.h); the bank follows the
// constants it leaves in the report.
Status GpuFrameStage(IrrmapRun& run) {
  Status error =
      RunIrrmapGpuFrame({run.options.gpu_frame, run.environment, run.options.window, *run.chosen_program,
                         run.options.coefficients_only ? 0 : run.options.map_size},
                        run.report, run.gpu_irradiance);
  run.chosen_bank = run.chosen_program->Constants(run.report.program_constants);
  return error;
}

Status MeshStage(IrrmapRun& run) {
  const IrrmapOptions& options = run.options;
  const CubeMap& cube = EnvironmentCube(run);
  Result<MeshLighting> lit = Timed(run.report, "mesh", [&] {
    MeshLightingOptions mesh_options{run.checked.engine, run.engine_options, run.checked.threads,
                                     options.mesh_truth_vertex_limit, options.mesh_panel_size};
    return LightMesh(*options.mesh, *run.program, run.report.constants, cube, mesh_options);
  });
  if (!lit) return lit.error();
  run.lighting = std::move(lit).value();
  const MeshLighting& lighting = run.lighting;
  for (const std::string& warning : lighting.warnings) run.report.warnings.push_back(warning);
  run.report.mesh = MeshReport{options.mesh->name, options.mesh->positions.size(), options.mesh->indices.size() / 3,
                               lighting.ms_per_evaluation, lighting.unusable_normals, !lighting.truth.empty(),
                               lighting.error, lighting.exposure, lighting.error_scale};
  run.outputs.push_back({kMeshFile, [&run](const fs::path& path) {
                           return run.options.mesh->write
                                      ? run.options.mesh->write(path, run.lighting.display_colors)
                                      : Status(Failure(DiagnosticCode::kCannotWriteFile, "no mesh writer"));
                         }});
  run.outputs.push_back({kMeshPictureFile, [&run](const fs::path& path) { return WriteImage(run.lighting.picture, path); }});
  return {};
}

// The irradiance cube map: the chosen program once per texel direction.
Status IrradianceMapStage(IrrmapRun& run) {
  run.irradiance_map = CubeMap(run.options.map_size);
  const Status filled = Timed(run.report, "irradiance_map", [&]() -> Status {
    std::vector<glm::dvec3> evaluated;  // stays empty where the GPU frame evaluated the map (--engine gl)
    if (run.gpu_irradiance.empty()) {
      Result<std::vector<glm::dvec3>> irradiance = run.chosen_program->Irradiance(
          run.chosen_bank, CubeTexelDirections(run.options.map_size), run.checked.engine, run.engine_options);
      if (!irradiance) return irradiance.error();
      evaluated = std::move(irradiance).value();
    }
    const std::vector<glm::dvec3>& values = run.gpu_irradiance.empty() ? evaluated : run.gpu_irradiance;
    std::size_t k = 0;
    for (Image& face : run.irradiance_map.faces) {
      for (glm::vec3& texel : face.pixels) texel = glm::vec3(values[k++]);
    }
    return {};
  });
  if (!filled) return filled;
  if (!AllTexelsFinite(run.irradiance_map)) {
    return Failure(DiagnosticCode::kBeyondFloatRange,
                   fmt::format("{}: {}", run.report.environment,
                               BeyondFloatRangeMessage("the irradiance map is", run.report.texel_range)));
  }
  const MapFileFormat format = run.checked.exports.map_format;
  const std::span<const std::string_view> files = IrradianceMapFileNames(format);
  if (std::optional<std::string> warning =
          MapRangeWarning(run.irradiance_map, format, fmt::format("{}", fmt::join(files, ", ")))) {
    run.report.warnings.push_back(*warning);
  }
  for (std::size_t file = 0; file < files.size(); ++file) {
    run.outputs.push_back({files[file], [&run, format, file](const fs::path& path) {
                             return WriteMapFile(run.irradiance_map, format, file, path);
                           }});
  }
  return {};
}

// The nine coefficients in each --sh-export engine's convention (irradiance/sh/engine_sh.h).
Status ShExportStage(IrrmapRun& run) {
  if (run.options.coefficients_only && run.checked.exports.map_format != MapFileFormat::kExr) {
    run.report.warnings.push_back(fmt::format("--map-format {} ignored: --coefficients-only makes no irradiance map",
                                              MapFileFormatName(run.options.map_format)));
  }
  const std::string source = ExportSourceLine(run.report, ShWindowName(run.options.window));
  for (ShExportFormat format : run.checked.exports.sh_exports) {
    run.outputs.push_back({ShExportFileName(format), [&run, format, source](const fs::path& path) {
                             return WriteFileAtomically(
                                 path, ShExportText(format, run.report.sh_source, run.report.coefficients, source));
                           }});
  }
  return {};
}

// The ground truth at the error normals and at the preview's grid, in one pass, and every level's
// error against it.
Status GroundTruthStage(IrrmapRun& run) {
  IrrmapReport& report = run.report;
  run.error_normals = SphereNormals(run.options.error_normals);
  std::vector<glm::dvec3> truth_normals = run.error_normals;
  truth_normals.insert(truth_normals.end(), run.grid.normals().begin(), run.grid.normals().end());
  const CubeMap& cube = EnvironmentCube(run);
  std::vector<glm::dvec3> truth = Timed(report, "ground_truth", [&] {
    return GroundTruthIrradiance(cube, truth_normals, run.checked.threads,
                                 run.FractionsOf("ground truth"));
  });
  const auto grid_start = truth.begin() + static_cast<std::ptrdiff_t>(run.error_normals.size());
  run.grid.SetValues(std::vector<glm::dvec3>(grid_start, truth.end()));
  truth.erase(grid_start, truth.end());
  run.error_truth = std::move(truth);

  const Status compared = Timed(report, "level_errors", [&]() -> Status {
    for (LevelReport& level : report.levels) {
      const Result<std::vector<glm::dvec3>> estimate = run.program->Irradiance(
          PackTable1(level.coefficients), run.error_normals, run.checked.engine, run.engine_options);
      if (!estimate) return estimate.error();
      level.error = CompareIrradiance(*estimate, run.error_truth, run.error_normals);
    }
    const Result<std::vector<glm::dvec3>> chosen =
        run.chosen_program->Irradiance(run.chosen_bank, run.error_normals, run.checked.engine, run.engine_options);
    if (!chosen) return chosen.error();
    report.program_error = CompareIrradiance(*chosen, run.error_truth, run.error_normals);
    return {};
  });
  if (!compared) return compared;
  report.errors_measured = true;
  report.error_normals = static_cast<int>(run.error_normals.size());
  return {};
}

Status PreviewStage(IrrmapRun& run) {
  const IrrmapReport& report = run.report;
  const CubeMap& cube = EnvironmentCube(run);
  Result<PreviewResult> preview = Timed(run.report, "preview", [&]() -> Result<PreviewResult> {
    PreviewOptions preview_options;
    preview_options.sphere_diameter = run.options.sphere_diameter;
    if (!run.options.font.empty()) preview_options.font = run.options.font;
    const SpherePixels sphere = MakeSpherePixels(run.options.sphere_diameter);
    PreviewPanel truth_panel{"exact convolution", {}};
    truth_panel.irradiance.reserve(sphere.normals.size());
    for (const glm::dvec3& n : sphere.normals) truth_panel.irradiance.push_back(run.grid.Sample(n));
    std::vector<PreviewPanel> panels;
    std::vector<ErrorStats> table_errors;  // each panel's row of the level table: the captions state its figures
    const bool order2 = report.order == ShOrder::kOrder2;
    for (int level : PreviewLevels(report)) {
      const LevelReport& row = report.levels[level];
      Result<std::vector<glm::dvec3>> irradiance = run.program->Irradiance(
          PackTable1(row.coefficients), sphere.normals, run.checked.engine, run.engine_options);
      if (!irradiance) return irradiance.error();
      panels.push_back({PreviewLabel(row, row.chosen && order2), std::move(irradiance).value()});
      table_errors.push_back(row.error);
    }
    if (!order2) {  // the chosen program beside the nine terms it approximates
      const LevelReport& chosen = report.levels[report.level];
      Result<std::vector<glm::dvec3>> irradiance =
          run.chosen_program->Irradiance(run.chosen_bank, sphere.normals, run.checked.engine, run.engine_options);
      if (!irradiance) return irradiance.error();
      panels.push_back({fmt::format("{} from {}x{} *", ShOrderName(report.order), chosen.size, chosen.size),
                        std::move(irradiance).value()});
      table_errors.push_back(report.program_error);
    }
    const PreviewErrorBasis basis{report.error_metric, table_errors,
                                  SampleErrorScale(run.error_truth, report.error_metric, kPreviewErrorFloor)};
    const PreviewErrors errors = AnalysePreviewErrors(truth_panel, panels, basis);
    for (std::size_t p = 0; p < panels.size(); ++p) {
      run.report.preview_panels.push_back({panels[p].label, errors.captions[p]});
    }
    return RenderPreview(sphere, truth_panel, panels, errors, cube, preview_options);
  });
  if (!preview) return preview.error();
  run.preview = std::move(preview).value();
  for (const std::string& warning : run.preview.warnings) run.report.warnings.push_back(warning);
  run.outputs.push_back({kPreviewFile, [&run](const fs::path& path) { return WriteImage(run.preview.image, path); }});
  return {};
}

struct Stage {
  const char* doing;  // "while ..." in an out-of-memory message
  Status (*run)(IrrmapRun&);
};

// The stages the options ask for, in order.
std::vector<Stage> StagesFor(const IrrmapOptions& options) {
  std::vector<Stage> stages = {{"loading the environment and building its pyramids", LoadStage},
                               {"projecting every level", CoefficientsStage}};
  if (options.gpu_frame) stages.push_back({"running the frame on the GPU", GpuFrameStage});
  if (options.mesh) stages.push_back({"lighting the mesh", MeshStage});
  stages.push_back({"exporting the coefficients", ShExportStage});
  if (options.coefficients_only) return stages;
  stages.push_back({"computing the irradiance map", IrradianceMapStage});
  if (options.no_ground_truth) return stages;
  stages.push_back({"computing the ground truth", GroundTruthStage});
  stages.push_back({"rendering the preview", PreviewStage});
  return stages;
}

// The error of a job that ran out of memory `doing` something, with what its pyramids take.
Diagnostic OutOfMemory(const IrrmapRun& run, std::string_view doing) {
  const int face_size = run.face_size > 0 ? run.face_size : run.options.face_size;
  return Failure(DiagnosticCode::kOutOfMemory,
                 fmt::format("{}: out of memory while {} (face size {} needs about {} MB)", run.options.environment,
                             doing, face_size, (ProjectionMemoryBytes(face_size) >> 20) + 1));
}

// The engine is built once for the paper's program before any work: where one that depends on a driver
// (the gl engine) cannot be built, the job ends with MakeEngine's error before any stage runs (the
// stages that build it again, PaperProgram::Irradiance and LightMesh, return the error of a build or
// a run that fails later). (The CPU engines never fail; building them costs microseconds.)
Status CheckEngine(const std::string& kind, const EngineOptions& engine_options) {
  const Result<PaperProgram> paper = PaperProgram::LoadOrder(ShOrder::kOrder2);
  if (!paper) return paper.error();
  const Result<std::unique_ptr<Engine>> engine = MakeEngine(kind, paper->program(), ConstantBank(), engine_options);
  if (engine) return {};
  return Failure(engine.error().code, fmt::format("--engine {}: {}", kind, engine.message()));
}

}  // namespace

Status RunIrrmap(const IrrmapOptions& options, IrrmapReport& report, const IrrmapProgress& progress) {
  report = IrrmapReport{};
  IrrmapRun run(options, report, progress);
  Status error = CheckOptions(options, run.checked);
  if (error.ok()) {
    report.threads = run.checked.threads;
    run.engine_options = EngineOptions{run.checked.threads};
    run.engine_options.settings = options.engine_settings;
    error = CheckEngine(run.checked.engine, run.engine_options);
  }
  if (error.ok()) {
    for (const Stage& stage : StagesFor(options)) {
      try {
        error = stage.run(run);
      } catch (const std::bad_alloc&) {
        error = OutOfMemory(run, stage.doing);
      }
      if (!error.ok()) break;
    }
  }
  if (!error.ok()) return error;
  // The last guard: a figure no stage checked (an error measured from an irradiance beyond float
  // range at the ground truth's normals) fails the job rather than becoming null in coeffs.json.
  if (!AllNumbersFinite(CoefficientsJson(report, options, run.checked))) {
    return Failure(DiagnosticCode::kBeyondFloatRange,
                   fmt::format("{}: {}", report.environment,
                               BeyondFloatRangeMessage("a figure of coeffs.json is", report.texel_range)));
  }
  report.irradiance_map = run.irradiance_map;
  if (!options.write_files) return {};
  try {
    return WriteJobOutputs(options, run.checked, *run.chosen_program, std::move(run.outputs), report);
  } catch (const std::bad_alloc&) {  // WriteOutputs has removed its temporaries
    return OutOfMemory(run, "writing the outputs");
  }
}

}  // namespace vs11::irradiance
