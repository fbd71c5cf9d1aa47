// The file formats of irrmap's irradiance cube map (--map-format): a horizontal cross of 32-bit floats
// in OpenEXR (environment_io.h), or a cube map texture of half floats that engines load as it is:
// DDS (dds_writer.h) or KTX2 (ktx2_writer.h).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

enum class MapFileFormat { kExr, kDds, kKtx2 };
inline constexpr std::array<MapFileFormat, 3> kAllMapFileFormats = {MapFileFormat::kExr, MapFileFormat::kDds,
                                                                    MapFileFormat::kKtx2};

// "exr", "dds", "ktx2" and back; nullopt for any other name.
std::string_view MapFileFormatName(MapFileFormat format);
std::optional<MapFileFormat> ParseMapFileFormat(std::string_view name);
inline constexpr std::string_view kMapFileFormatNames = "exr, dds or ktx2";

// "irradiance.exr", "irradiance.dds", "irradiance.ktx2".
std::string_view IrradianceMapFileName(MapFileFormat format);

// Writes `cube` in `format` to `path`, atomically; nullopt, or what failed.
std::optional<std::string> WriteMapFile(const CubeMap& cube, MapFileFormat format, const std::filesystem::path& path);

// For the half-float formats, a warning when some values lie beyond the largest half (65504) and are
// clamped to it; nullopt otherwise. `file` names the output in the message.
std::optional<std::string> HalfRangeWarning(const CubeMap& cube, MapFileFormat format, std::string_view file);

}  // namespace vs11::irradiance
