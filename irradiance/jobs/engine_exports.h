// What irrmap's --map-format and --sh-export ask for, checked, and the line each exported file
// gives about its source (irradiance/io/map_file_formats.h, irradiance/sh/engine_sh.h).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/map_file_formats.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/engine_sh.h"

namespace vs11::irradiance {

struct CheckedExports {
  MapFileFormat map_format = MapFileFormat::kExr;
  std::vector<ShExportFormat> sh_exports;  // each once, in the order first named
};

// The options with each --sh-export format once.
CheckedExports CheckedExportsOf(MapFileFormat map_format, std::span<const ShExportFormat> sh_exports);

// How engines see an input of `layout`: a lat-long map is a panorama they map themselves; every other
// layout (faces, crosses, strips, DDS cubes, angular maps, which no engine shows as they are) reaches
// them as a cube map.
ShSourceKind ShSourceKindOf(EnvironmentLayout layout);

// "Written by irrmap from sky (built-in), face size 256, coefficients from level 4 (16x16), window none."
std::string ExportSourceLine(const IrrmapReport& report, std::string_view window_name);

}  // namespace vs11::irradiance
