// irrmap's option checks. See irrmap_checks.h.
#include "irradiance/jobs/irrmap_checks.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_outputs.h"
#include "irradiance/render/preview.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/engines/engine_factory.h"
#include "vm/core/input_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxSphereDiameter = 2048;
constexpr int kMaxErrorNormals = 1 << 20;
constexpr double kMaxWindowWidth = 1e6;

std::string BuiltinList() {
  std::string out;
  for (const std::string& name : BuiltinEnvironmentNames()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

bool IsBuiltinName(std::string_view name) {
  const std::vector<std::string> names = BuiltinEnvironmentNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::string LevelRange(int face_size) {
  return fmt::format("face size {} has levels 0 ({}x{}) to {} (1x1)", face_size, face_size, face_size,
                     LevelCount(face_size) - 1);
}

std::string LevelWithValue(const IrrmapOptions& options) {
  return OptionWithValue(OptionName(options.naming, "level"), options.level.value_or(0));
}

Status CheckOptionValues(const IrrmapOptions& options, CheckedOptions& checked) {
  auto named = [&](std::string_view flag, const auto& value) {
    return OptionWithValue(OptionName(options.naming, flag), value);
  };
  auto usage = [](std::string message) { return Failure(DiagnosticCode::kOptionValue, std::move(message)); };
  std::optional<EngineInfo> engine = FindEngine(options.engine);
  if (!engine) return usage(fmt::format("unknown engine '{}' (use {})", options.engine, EngineNameList()));
  checked.engine = engine->name;
  checked.order = options.order;
  if (!checked.order && options.level) checked.order = ShOrder::kOrder2;
  if (!(options.window_width > 0.0) || options.window_width > kMaxWindowWidth) {
    return usage(fmt::format("{} is out of range: above 0, at most {}", named("window-width", options.window_width),
                             kMaxWindowWidth));
  }
  if (!(options.max_error > 0.0 && options.max_error < 1.0)) {
    return usage(fmt::format("{} is out of range: a fraction above 0 and below 1 ({} = {} %)",
                             named("max-error", options.max_error), kDefaultMaxLevelError,
                             100 * kDefaultMaxLevelError));
  }
  if (Status size = CheckFaceSizeOption(OptionName(options.naming, "face-size"), options.face_size); !size.ok()) {
    return size;
  }
  if (options.level && *options.level < 0) {
    return usage(
        fmt::format("{} is out of range: levels start at 0 (full resolution)", named("level", *options.level)));
  }
  if (options.map_size < 1 || options.map_size > kMaxMapSize) {
    return usage(fmt::format("{} is out of range: 1 to {}", named("map-size", options.map_size), kMaxMapSize));
  }
  if (options.threads < 0) {
    return usage(fmt::format("{} must be >= 0 (0: every core)", named("threads", options.threads)));
  }
  if (options.error_normals < 1 || options.error_normals > kMaxErrorNormals) {
    return usage(
        fmt::format("{} is out of range: 1 to {}", named("error-normals", options.error_normals), kMaxErrorNormals));
  }
  if (options.sphere_diameter < kMinPreviewSphereDiameter || options.sphere_diameter > kMaxSphereDiameter) {
    return usage(fmt::format("{} is out of range: {} to {}", named("sphere-size", options.sphere_diameter),
                             kMinPreviewSphereDiameter, kMaxSphereDiameter));
  }
  if (options.write_files && options.out_dir.empty()) return usage("the output directory is empty");
  if (options.environment.empty()) return usage("no environment given");
  checked.exports = CheckedExportsOf(options.map_format, options.sh_exports);
  return {};
}

Status CheckOptions(const IrrmapOptions& options, CheckedOptions& checked) {
  if (Status error = CheckOptionValues(options, checked); !error.ok()) return error;
  if (options.write_files) {
    if (Status error = CheckOutputFolder(options.out_dir); !error.ok()) return error;
    if (Status error = CheckOutputsAreNotInputs(options, options.mesh ? options.mesh->name : ""); !error.ok()) {
      return error;
    }
  }
  std::error_code ec;
  const bool exists = options.cube || options.latlong || fs::exists(options.environment, ec);
  checked.builtin = IsBuiltinName(options.environment) && !exists;
  if (!checked.builtin && !exists && options.environment.find(kFaceToken) == std::string::npos) {
    return Failure(DiagnosticCode::kNoSuchInput,
                   fmt::format("environment '{}' is neither an existing file nor a built-in ({})", options.environment,
                               BuiltinList()));
  }
  if (checked.builtin && options.level && *options.level >= LevelCount(options.face_size)) {
    return Failure(DiagnosticCode::kOptionValue,
                   fmt::format("{} is out of range: {}", LevelWithValue(options), LevelRange(options.face_size)));
  }
  const unsigned cores = std::thread::hardware_concurrency();
  checked.threads = options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, cores));
  return {};
}

Status CheckIrrmapOptions(const IrrmapOptions& options) {
  CheckedOptions checked;
  return CheckOptionValues(options, checked);
}


// ---- The output folder -----------------------------------------------------------------------------

Status CheckOutputFolder(const fs::path& out_dir) {
  std::error_code ec;
  // The folder itself, or the nearest existing folder above it, where it would be created.
  fs::path existing = out_dir;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  if (!fs::is_directory(existing, ec)) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot write into {}: {} is not a directory", out_dir.string(), existing.string()));
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot write into {}: {} is not writable", out_dir.string(), existing.string()));
  }
  return {};
}

Status CheckOutputsAreNotInputs(const IrrmapOptions& options, const fs::path& mesh_file) {
  std::vector<fs::path> inputs = {options.environment, mesh_file};
  if (const std::size_t token = options.environment.find(kFaceToken); token != std::string::npos) {
    for (const auto* names : {&kFaceFileNames, &kSignedFaceFileNames}) {
      for (std::string_view face : *names) {
        inputs.push_back(std::string(options.environment).replace(token, kFaceToken.size(), face));
      }
    }
  }
  const CheckedExports exports = CheckedExportsOf(options.map_format, options.sh_exports);
  // The files StagesFor's stages write.
  std::vector<std::string_view> names = {kCoefficientsFile, kConstantsFile, kProgramFile};
  if (!mesh_file.empty()) names.insert(names.end(), {kMeshFile, kMeshPictureFile});
  for (ShExportFormat format : exports.sh_exports) names.push_back(ShExportFileName(format));
  if (!options.coefficients_only) {
    for (std::string_view name : IrradianceMapFileNames(exports.map_format)) names.push_back(name);
  }
  if (!options.coefficients_only && !options.no_ground_truth) names.push_back(kPreviewFile);
  for (std::string_view name : names) {
    if (Status error = OutputOverwritesInput(options.out_dir / name, inputs); !error.ok()) return error;
  }
  return {};
}

}  // namespace vs11::irradiance
