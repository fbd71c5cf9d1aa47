#include "irradiance/io/map_file_formats.h"

#include <algorithm>
#include <cassert>

#include <fmt/format.h>

#include "irradiance/io/dds_writer.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/io/ktx1_writer.h"
#include "irradiance/io/ktx2_writer.h"
#include "irradiance/io/rgba16f_cube.h"

namespace vs11::irradiance {
namespace {

constexpr std::array<std::string_view, 1> kExrFiles = {"irradiance.exr"};
constexpr std::array<std::string_view, 1> kDdsFiles = {"irradiance.dds"};
constexpr std::array<std::string_view, 1> kKtx2Files = {"irradiance.ktx2"};
constexpr std::array<std::string_view, 1> kKtxFiles = {"irradiance.ktx"};
// kFaceFileNames' order and names, so that irrmap reads the six back as "irradiance_{face}.hdr".
constexpr std::array<std::string_view, kCubeFaceCount> kHdrFaceFiles = {
    "irradiance_px.hdr", "irradiance_nx.hdr", "irradiance_py.hdr",
    "irradiance_ny.hdr", "irradiance_pz.hdr", "irradiance_nz.hdr"};

struct FormatInfo {
  MapFileFormat format;
  std::span<const std::string_view> files;
};
constexpr std::array<FormatInfo, 5> kFormats = {{
    {MapFileFormat::kExr, kExrFiles},
    {MapFileFormat::kDds, kDdsFiles},
    {MapFileFormat::kKtx2, kKtx2Files},
    {MapFileFormat::kKtx, kKtxFiles},
    {MapFileFormat::kHdrFaces, kHdrFaceFiles},
}};

const FormatInfo& Info(MapFileFormat format) { return kFormats[static_cast<int>(format)]; }

std::size_t CountNegative(const CubeMap& cube) {
  std::size_t count = 0;
  for (const Image& face : cube.faces) {
    for (const glm::vec3& texel : face.pixels) {
      for (int c = 0; c < 3; ++c) count += texel[c] < 0.0f ? 1 : 0;
    }
  }
  return count;
}

// One face, negative values as 0: what RGBE stores of them (OpenImageIO would wrap them to garbage).
Status WriteHdrFace(const CubeMap& cube, std::size_t face, const std::filesystem::path& path) {
  Image image = cube.faces[face];
  for (glm::vec3& texel : image.pixels) texel = glm::max(texel, glm::vec3(0.0f));
  return WriteImage(image, path);
}

}  // namespace

std::span<const std::string_view> IrradianceMapFileNames(MapFileFormat format) { return Info(format).files; }

Status WriteMapFile(const CubeMap& cube, MapFileFormat format, std::size_t file, const std::filesystem::path& path) {
  assert(file < IrradianceMapFileNames(format).size());
  switch (format) {
    case MapFileFormat::kExr: return WriteCrossExr(cube, path);
    case MapFileFormat::kDds: return WriteDdsCube(cube, path);
    case MapFileFormat::kKtx2: return WriteKtx2Cube(cube, path);
    // Mirrored as cmgen mirrors: Filament then shows it in the frame sh_filament.txt assumes.
    case MapFileFormat::kKtx: return WriteKtx1Cube(MirroredInX(cube), path);
    case MapFileFormat::kHdrFaces:
      if (cube.face_size <= 0) {
        return Failure(DiagnosticCode::kCannotWriteFile,
                       fmt::format("{}: cannot write an empty cube map", path.string()));
      }
      return WriteHdrFace(cube, file, path);
  }
  return Failure(DiagnosticCode::kCannotWriteFile, "unknown map format");
}

std::optional<std::string> MapRangeWarning(const CubeMap& cube, MapFileFormat format, std::string_view file) {
  switch (format) {
    case MapFileFormat::kExr: return std::nullopt;
    case MapFileFormat::kDds:
    case MapFileFormat::kKtx2:
    case MapFileFormat::kKtx:
      if (const std::size_t clamped = CountBeyondHalfRange(cube); clamped > 0) {
        return fmt::format("{}: {} colour values lie beyond the largest half float ({}) and are clamped to it; "
                           "--map-format exr keeps 32-bit floats",
                           file, clamped, kHalfMax);
      }
      return std::nullopt;
    case MapFileFormat::kHdrFaces:
      if (const std::size_t negative = CountNegative(cube); negative > 0) {
        return fmt::format("{}: {} colour values are negative (the nine-term irradiance dips below 0) and Radiance "
                           "RGBE holds none: written as 0; --map-format exr keeps them",
                           file, negative);
      }
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace vs11::irradiance
