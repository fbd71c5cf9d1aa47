// The file formats of irrmap's irradiance cube map (--map-format): a horizontal cross of 32-bit floats
// in OpenEXR (environment_io.h); a cube map texture of half floats, DDS (dds_writer.h), KTX2
// (ktx2_writer.h) or Filament's KTX 1.1 (ktx1_writer.h, mirrored in x as cmgen writes its cubes); or
// six Radiance RGBE faces, the one HDR cube three.js's stock loaders build a CubeTexture from
// (HDRCubeTextureLoader).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "irradiance/io/cube_map.h"
#include "vm/core/name_table.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

enum class MapFileFormat { kExr, kDds, kKtx2, kKtx, kHdrFaces };
inline constexpr std::array<MapFileFormat, 5> kAllMapFileFormats = {
    MapFileFormat::kExr, MapFileFormat::kDds, MapFileFormat::kKtx2, MapFileFormat::kKtx, MapFileFormat::kHdrFaces};

// The names of --map-format, with what each writes and which engines load it.
inline constexpr NameTable kMapFileFormatNames("map format", {
    Choice(MapFileFormat::kExr, "exr", "irradiance.exr, a float cross"),
    Choice(MapFileFormat::kDds, "dds", "irradiance.dds, an RGBA16F cube map texture for Babylon.js and Direct3D"),
    Choice(MapFileFormat::kKtx2, "ktx2", "irradiance.ktx2, an RGBA16F cube map texture for Vulkan"),
    Choice(MapFileFormat::kKtx, "ktx", "irradiance.ktx, KTX 1.1 RGBA16F mirrored as cmgen's, for Filament"),
    Choice(MapFileFormat::kHdrFaces, "hdr-faces",
           "six Radiance faces irradiance_px.hdr .. irradiance_nz.hdr, for three.js's HDRCubeTextureLoader")});
inline std::string_view MapFileFormatName(MapFileFormat format) { return kMapFileFormatNames.Name(format); }

// The files of the map: "irradiance.exr", "irradiance.dds", "irradiance.ktx2", "irradiance.ktx", or for
// hdr-faces six,
// "irradiance_px.hdr" ... "irradiance_nz.hdr" in +x -x +y -y +z -z order.
std::span<const std::string_view> IrradianceMapFileNames(MapFileFormat format);

// Writes file `file` (an index into IrradianceMapFileNames(format)) of `cube` in `format` to `path`,
// atomically; success, or the error saying what failed. Precondition (asserted): file <
// IrradianceMapFileNames(format).size().
Status WriteMapFile(const CubeMap& cube, MapFileFormat format, std::size_t file, const std::filesystem::path& path);

// What `format` cannot hold of `cube`, as a warning naming `file`; nullopt when it holds all of it.
// The half-float formats clamp values beyond the largest half (65504); Radiance RGBE holds no
// negative value (a nine-term irradiance dips below 0 opposite a strong light) and writes 0.
std::optional<std::string> MapRangeWarning(const CubeMap& cube, MapFileFormat format, std::string_view file);

}  // namespace vs11::irradiance
