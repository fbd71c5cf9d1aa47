// vs11_write_environments: writes the built-in environments as files, for comparisons with other
// tools (bench/compare_cmgen.py). For each built-in NAME, into OUT_DIR:
//   NAME_hcross.exr   horizontal cross, 32-bit float (linear)
//   NAME_hcross.hdr   the same cross in Radiance RGBE (8-bit mantissas)
//   NAME_latlong.exr  lat-long 4N x 2N, 32-bit float (point-sampled from the cube: CubeMapToImage)
//   NAME_cube.dds     DDS cube map, 8-bit BGRA, sRGB-encoded and clamped to [0, 1]
//   NAME_ldr.png      the same 8-bit sRGB bytes as NAME_cube.dds, as a horizontal cross PNG (for
//                     tools that read no DDS)
// All files are written atomically (temporary, then rename).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"

namespace {

namespace fs = std::filesystem;
using vs11::irradiance::CubeMap;

constexpr double kByteMax = 255.0;

// DirectDraw Surface header fields (DDS_HEADER, DDS_PIXELFORMAT, DDSCAPS2 in Microsoft's reference).
constexpr std::uint32_t kDdsMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kDdsHeaderSize = 124;
constexpr std::uint32_t kDdsPixelFormatSize = 32;
constexpr std::uint32_t kDdsdCapsHeightWidthPixelFormatPitch = 0x1 | 0x2 | 0x4 | 0x1000 | 0x8;
constexpr std::uint32_t kDdpfRgbWithAlpha = 0x40 | 0x1;
constexpr std::uint32_t kDdsCapsComplexTexture = 0x8 | 0x1000;
constexpr std::uint32_t kDdsCaps2AllFacesOfACubeMap = 0x200 | 0xfc00;
constexpr std::array<std::uint32_t, 4> kBgraMasks = {0x00ff0000, 0x0000ff00, 0x000000ff, 0xff000000};  // r g b a

void Append(std::string& bytes, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

std::uint8_t SrgbByte(float linear) {
  return static_cast<std::uint8_t>(
      std::lround(vs11::irradiance::LinearToSrgb(std::clamp(static_cast<double>(linear), 0.0, 1.0)) * kByteMax));
}

// The cube as an uncompressed 8-bit DDS cube map with its six faces in D3D order.
std::string DdsCube(const CubeMap& cube) {
  const auto size = static_cast<std::uint32_t>(cube.face_size);
  std::string bytes;
  Append(bytes, kDdsMagic);
  Append(bytes, kDdsHeaderSize);
  Append(bytes, kDdsdCapsHeightWidthPixelFormatPitch);
  Append(bytes, size);  // height
  Append(bytes, size);  // width
  Append(bytes, size * 4);  // pitch
  Append(bytes, 0);  // depth
  Append(bytes, 1);  // mip levels
  for (int i = 0; i < 11; ++i) Append(bytes, 0);  // reserved1
  Append(bytes, kDdsPixelFormatSize);
  Append(bytes, kDdpfRgbWithAlpha);
  Append(bytes, 0);   // four-cc
  Append(bytes, 32);  // bits per pixel
  for (std::uint32_t mask : kBgraMasks) Append(bytes, mask);
  Append(bytes, kDdsCapsComplexTexture);
  Append(bytes, kDdsCaps2AllFacesOfACubeMap);
  for (int i = 0; i < 3; ++i) Append(bytes, 0);  // caps3, caps4, reserved2
  for (const vs11::irradiance::Image& face : cube.faces) {
    for (const glm::vec3& texel : face.pixels) {
      bytes.append({static_cast<char>(SrgbByte(texel.b)), static_cast<char>(SrgbByte(texel.g)),
                    static_cast<char>(SrgbByte(texel.r)), static_cast<char>(0xff)});
    }
  }
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_dir;
  int face_size = 256;
  std::vector<std::string> names = vs11::irradiance::BuiltinEnvironmentNames();
  CLI::App app{"vs11_write_environments: the built-in environments as files (hcross EXR and HDR, lat-long EXR, "
               "8-bit DDS cube map and the same bytes as an hcross PNG)"};
  app.add_option("OUT_DIR", out_dir, "output folder (created if needed)")->required();
  app.add_option("--face-size", face_size, "cube face size")->capture_default_str();
  app.add_option("--env", names, "built-ins to write (default: all)");
  CLI11_PARSE(app, argc, argv);

  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) {
    fmt::print(stderr, "vs11_write_environments: error: cannot create {} ({})\n", out_dir, ec.message());
    return 1;
  }
  using vs11::irradiance::EnvironmentLayout;
  for (const std::string& name : names) {
    const std::optional<CubeMap> cube = vs11::irradiance::MakeBuiltinEnvironment(name, face_size);
    if (!cube) {
      fmt::print(stderr, "vs11_write_environments: error: no built-in '{}' at face size {}\n", name, face_size);
      return 1;
    }
    const fs::path base = fs::path(out_dir) / name;
    vs11::Status written =
        vs11::irradiance::WriteCubeMap(*cube, base.string() + "_hcross.exr", EnvironmentLayout::kHorizontalCross);
    if (written) {
      written =
          vs11::irradiance::WriteCubeMap(*cube, base.string() + "_hcross.hdr", EnvironmentLayout::kHorizontalCross);
    }
    if (written) {
      written = vs11::irradiance::WriteImage(vs11::irradiance::CubeMapToImage(*cube, EnvironmentLayout::kLatLong),
                                             base.string() + "_latlong.exr");
    }
    if (written) written = vs11::WriteFileAtomically(base.string() + "_cube.dds", DdsCube(*cube));
    if (written) {
      written = vs11::irradiance::WriteImage(
          vs11::irradiance::CubeMapToImage(*cube, EnvironmentLayout::kHorizontalCross), base.string() + "_ldr.png");
    }
    if (!written) {
      fmt::print(stderr, "vs11_write_environments: error: {}\n", written.message());
      return 1;
    }
  }
  return 0;
}
