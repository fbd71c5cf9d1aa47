#include "irradiance/io/map_file_formats.h"

#include <array>

#include <fmt/format.h>

#include "irradiance/io/dds_writer.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/io/ktx2_writer.h"
#include "irradiance/io/rgba16f_cube.h"

namespace vs11::irradiance {
namespace {

struct FormatInfo {
  MapFileFormat format;
  std::string_view name;
  std::string_view file_name;
};
constexpr std::array<FormatInfo, 3> kFormats = {{
    {MapFileFormat::kExr, "exr", "irradiance.exr"},
    {MapFileFormat::kDds, "dds", "irradiance.dds"},
    {MapFileFormat::kKtx2, "ktx2", "irradiance.ktx2"},
}};

const FormatInfo& Info(MapFileFormat format) { return kFormats[static_cast<int>(format)]; }

}  // namespace

std::string_view MapFileFormatName(MapFileFormat format) { return Info(format).name; }

std::optional<MapFileFormat> ParseMapFileFormat(std::string_view name) {
  for (const FormatInfo& info : kFormats) {
    if (info.name == name) return info.format;
  }
  return std::nullopt;
}

std::string_view IrradianceMapFileName(MapFileFormat format) { return Info(format).file_name; }

std::optional<std::string> WriteMapFile(const CubeMap& cube, MapFileFormat format, const std::filesystem::path& path) {
  switch (format) {
    case MapFileFormat::kExr: return WriteCrossExr(cube, path);
    case MapFileFormat::kDds: return WriteDdsCube(cube, path);
    case MapFileFormat::kKtx2: return WriteKtx2Cube(cube, path);
  }
  return std::string("unknown map format");
}

std::optional<std::string> HalfRangeWarning(const CubeMap& cube, MapFileFormat format, std::string_view file) {
  if (format == MapFileFormat::kExr) return std::nullopt;
  const std::size_t clamped = CountBeyondHalfRange(cube);
  if (clamped == 0) return std::nullopt;
  return fmt::format("{}: {} colour values lie beyond the largest half float ({}) and are clamped to it; "
                     "--map-format exr keeps 32-bit floats",
                     file, clamped, kHalfMax);
}

}  // namespace vs11::irradiance
