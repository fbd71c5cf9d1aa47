#include "irradiance/jobs/engine_exports.h"

#include <algorithm>

#include <fmt/format.h>

namespace vs11::irradiance {

CheckedExports CheckedExportsOf(MapFileFormat map_format, std::span<const ShExportFormat> sh_exports) {
  CheckedExports checked{map_format, {}};
  for (ShExportFormat format : sh_exports) {
    if (std::find(checked.sh_exports.begin(), checked.sh_exports.end(), format) == checked.sh_exports.end()) {
      checked.sh_exports.push_back(format);
    }
  }
  return checked;
}

ShSourceKind ShSourceKindOf(EnvironmentLayout layout) {
  return layout == EnvironmentLayout::kLatLong ? ShSourceKind::kLatLong : ShSourceKind::kCube;
}

std::string ExportSourceLine(const IrrmapReport& report, std::string_view window_name) {
  const int size = report.levels.at(report.level).size;
  return fmt::format("Written by irrmap from {}, face size {}, coefficients from level {} ({}x{}), window {}.",
                     report.environment, report.face_size, report.level, size, size, window_name);
}

}  // namespace vs11::irradiance
