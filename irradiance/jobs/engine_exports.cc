#include "irradiance/jobs/engine_exports.h"

#include <algorithm>

#include <fmt/format.h>

namespace vs11::irradiance {

std::optional<std::string> CheckExportOptions(std::string_view map_format, std::span<const std::string> sh_exports,
                                              CheckedExports& checked) {
  std::optional<MapFileFormat> format = ParseMapFileFormat(map_format);
  if (!format) return fmt::format("unknown map format '{}' (use {})", map_format, kMapFileFormatNames);
  checked.map_format = *format;
  checked.sh_exports.clear();
  for (const std::string& name : sh_exports) {
    std::optional<ShExportFormat> sh_format = ParseShExportFormat(name);
    if (!sh_format) return fmt::format("unknown --sh-export format '{}' (use {})", name, ShExportFormatNames());
    if (std::find(checked.sh_exports.begin(), checked.sh_exports.end(), *sh_format) == checked.sh_exports.end()) {
      checked.sh_exports.push_back(*sh_format);
    }
  }
  return std::nullopt;
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
