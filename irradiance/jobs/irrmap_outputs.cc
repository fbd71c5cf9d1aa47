// irrmap's output files. See irrmap_outputs.h.
#include "irradiance/jobs/irrmap_outputs.h"

#include <algorithm>

#include <fmt/format.h>

#include "irradiance/io/map_file_formats.h"
#include "irradiance/sh/engine_sh.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// Every file an irrmap run may write, whatever its options.
std::vector<std::string_view> EveryOutputName() {
  std::vector<std::string_view> names = {kCoefficientsFile, kConstantsFile, kProgramFile,
                                         kPreviewFile,      kMeshFile,      kMeshPictureFile};
  for (MapFileFormat format : kAllMapFileFormats) {
    for (std::string_view name : IrradianceMapFileNames(format)) names.push_back(name);
  }
  for (ShExportFormat format : kAllShExportFormats) names.push_back(ShExportFileName(format));
  return names;
}

}  // namespace

std::vector<std::string> LeftoverOutputWarnings(const fs::path& out_dir, std::span<const fs::path> written) {
  std::vector<std::string> warnings;
  std::error_code ec;
  for (std::string_view name : EveryOutputName()) {
    const fs::path path = out_dir / name;
    if (std::find(written.begin(), written.end(), path) != written.end() || !fs::exists(path, ec)) continue;
    warnings.push_back(fmt::format("{} is left from an earlier run: this run did not write it (the \"files\" of {} "
                                   "are this run's)",
                                   path.string(), (out_dir / kCoefficientsFile).string()));
  }
  return warnings;
}

}  // namespace vs11::irradiance
