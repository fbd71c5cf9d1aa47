// Helpers shared by the environment input tests: test cubes, inputs built with OpenImageIO or by
// hand (PFM, DDS) independently of the code under test, and a fixture with a fresh folder.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environment_io.h"

namespace vs11::irradiance::envtest {

namespace fs = std::filesystem;

// A cube whose texels differ on every face and position, all exactly representable as float.
inline CubeMap MakeTestCube(int size) {
  CubeMap cube(size);
  for (CubeFace face : kAllCubeFaces) {
    const int f = static_cast<int>(face);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        cube.face(face).at(x, y) =
            glm::vec3(f + 1 + 0.25f * x, 0.5f * y + 0.125f, 0.0625f * (3 * f + 1) + 0.03125f * x);
      }
    }
  }
  return cube;
}

// A smooth radiance that tells every axis and sign apart (one channel per axis).
inline glm::vec3 SmoothRadiance(glm::dvec3 d) {
  return glm::vec3(1.0 + 0.5 * d.x, 1.0 + 0.6 * d.y, 1.0 + 0.7 * d.z);
}

inline void ExpectCubesNear(const CubeMap& actual, const CubeMap& expected, float tolerance,
                            bool relative = false) {
  ASSERT_EQ(actual.face_size, expected.face_size);
  int failures = 0;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < expected.face_size; ++y) {
      for (int x = 0; x < expected.face_size; ++x) {
        const glm::vec3 a = actual.face(face).at(x, y);
        const glm::vec3 e = expected.face(face).at(x, y);
        const float limit = relative ? tolerance * std::max({e.r, e.g, e.b}) : tolerance;
        for (int c = 0; c < 3; ++c) {
          if (!(std::abs(a[c] - e[c]) <= limit) && failures++ < 10) {
            ADD_FAILURE() << "face " << CubeFaceName(face) << " texel (" << x << ", " << y
                          << ") channel " << c << ": " << a[c] << " vs " << e[c];
          }
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
}

inline void ExpectCubesEqual(const CubeMap& actual, const CubeMap& expected) {
  ExpectCubesNear(actual, expected, 0.0f);
}


// ---- Building test inputs with OpenImageIO, independently of the code under test -------------

inline std::vector<float> Interleave(const Image& image) {
  std::vector<float> data;
  for (const glm::vec3& p : image.pixels) data.insert(data.end(), {p.r, p.g, p.b});
  return data;
}

inline bool WriteWithOiio(const fs::path& path, int width, int height, int channels,
                          OIIO::TypeDesc type, const void* data,
                          const char* color_space = nullptr) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) return false;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (color_space) spec.attribute("oiio:ColorSpace", color_space);
  spec.attribute("CompressionQuality", 100);
  return out->open(path.string(), spec) && out->write_image(type, data) && out->close();
}

inline bool WriteFloatImage(const fs::path& path, const Image& image) {
  const std::vector<float> data = Interleave(image);
  return WriteWithOiio(path, image.width, image.height, 3, OIIO::TypeDesc::FLOAT, data.data());
}

inline void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string ReadBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

template <class T>
inline void Append(std::string& bytes, T value) {  // little-endian host (x86-64, AArch64)
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// Portable float map: "PF", width height, negative scale for little-endian, rows bottom to top.
inline void WritePfm(const fs::path& path, const Image& image) {
  std::string bytes = fmt::format("PF\n{} {}\n-1.0\n", image.width, image.height);
  for (int y = image.height - 1; y >= 0; --y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) Append(bytes, image.at(x, y)[c]);
    }
  }
  WriteBytes(path, bytes);
}

// Placing faces by hand (the layouts as drawn in environment_io.h), for inputs that do not go
// through CubeMapToImage.
struct Cell {
  int column;
  int row;
  bool rotated_180 = false;
};
inline Image PlaceFaces(const CubeMap& cube, int columns, int rows,
                        const std::array<Cell, 6>& cells) {
  const int n = cube.face_size;
  Image image(columns * n, rows * n, glm::vec3(-7.0f));  // unused cells are never read
  for (CubeFace face : kAllCubeFaces) {
    const Cell& cell = cells[static_cast<int>(face)];
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int sx = cell.rotated_180 ? n - 1 - x : x;
        const int sy = cell.rotated_180 ? n - 1 - y : y;
        image.at(cell.column * n + sx, cell.row * n + sy) = cube.face(face).at(x, y);
      }
    }
  }
  return image;
}

// DDS by hand (OpenImageIO cannot write DDS). Constants from the DirectDraw Surface reference
// (DDS_HEADER, DDS_PIXELFORMAT, DDSCAPS2 flags).
constexpr std::uint32_t kDdsMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kDdsHeaderSize = 124;
constexpr std::uint32_t kDdsPixelFormatSize = 32;
constexpr std::uint32_t kDdsdCapsHeightWidthPixelFormat = 0x1 | 0x2 | 0x4 | 0x1000;
constexpr std::uint32_t kDdsdPitch = 0x8;
constexpr std::uint32_t kDdpfAlphaPixels = 0x1;
constexpr std::uint32_t kDdpfFourCc = 0x4;
constexpr std::uint32_t kDdpfRgb = 0x40;
constexpr std::uint32_t kDdsCapsComplexTexture = 0x8 | 0x1000;
constexpr std::uint32_t kDdsCaps2Cubemap = 0x200;
constexpr std::array<std::uint32_t, 6> kDdsCaps2Face = {0x400,  0x800,  0x1000,
                                                        0x2000, 0x4000, 0x8000};
constexpr std::uint32_t kD3dFmtA32B32G32R32F = 116;

struct DdsPixelFormat {
  std::uint32_t flags;
  std::uint32_t four_cc;
  std::uint32_t bit_count;
  std::array<std::uint32_t, 4> masks;  // r g b a
};

inline std::string DdsHeader(int size, std::uint32_t caps2, const DdsPixelFormat& format,
                             int pitch) {
  std::string bytes;
  Append(bytes, kDdsMagic);
  Append(bytes, kDdsHeaderSize);
  Append(bytes, kDdsdCapsHeightWidthPixelFormat | kDdsdPitch);
  Append(bytes, static_cast<std::uint32_t>(size));  // height
  Append(bytes, static_cast<std::uint32_t>(size));  // width
  Append(bytes, static_cast<std::uint32_t>(pitch));
  Append(bytes, std::uint32_t{0});  // depth
  Append(bytes, std::uint32_t{1});  // mip levels
  for (int i = 0; i < 11; ++i) Append(bytes, std::uint32_t{0});
  Append(bytes, kDdsPixelFormatSize);
  Append(bytes, format.flags);
  Append(bytes, format.four_cc);
  Append(bytes, format.bit_count);
  for (std::uint32_t mask : format.masks) Append(bytes, mask);
  Append(bytes, kDdsCapsComplexTexture);
  Append(bytes, caps2);
  for (int i = 0; i < 3; ++i) Append(bytes, std::uint32_t{0});  // caps3, caps4, reserved2
  return bytes;
}

// An 8-bit BGRA cube map with the faces in `present` (texel bytes from `byte_of`).
inline std::string Dds8BitCube(
    int size, const std::vector<CubeFace>& present,
    const std::function<std::array<std::uint8_t, 3>(CubeFace, int, int)>& byte_of) {
  std::uint32_t caps2 = kDdsCaps2Cubemap;
  for (CubeFace face : present) caps2 |= kDdsCaps2Face[static_cast<int>(face)];
  const DdsPixelFormat format = {
      kDdpfRgb | kDdpfAlphaPixels, 0, 32, {0x00ff0000, 0x0000ff00, 0x000000ff, 0xff000000}};
  std::string bytes = DdsHeader(size, caps2, format, size * 4);
  for (CubeFace face : present) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const std::array<std::uint8_t, 3> rgb = byte_of(face, x, y);
        bytes.append({static_cast<char>(rgb[2]), static_cast<char>(rgb[1]),
                      static_cast<char>(rgb[0]), static_cast<char>(0xff)});
      }
    }
  }
  return bytes;
}

inline std::array<std::uint8_t, 3> DdsTestBytes(CubeFace face, int x, int y) {
  const int f = static_cast<int>(face);
  return {static_cast<std::uint8_t>(16 * x + 3), static_cast<std::uint8_t>(16 * y + 5),
          static_cast<std::uint8_t>(40 * f + 7)};
}

// ---- Fixture: a fresh folder per test --------------------------------------------------------

class TempFolderTest : public testing::Test {
 protected:
  void SetUp() override {
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    std::string name = fmt::format("vs11_environment_io_{}_{}_{:x}", info->test_suite_name(),
                                   info->name(), std::random_device{}());
    std::replace(name.begin(), name.end(), '/', '_');
    folder_ = fs::path(testing::TempDir()) / name;
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(folder_, ec);
  }
  fs::path Path(std::string_view name) const { return folder_ / name; }
  std::vector<std::string> FolderContents() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  const LoadedEnvironment& Load(const fs::path& path, LoadOptions options = {}) {
    Result<LoadedEnvironment> result = LoadEnvironment(path, options);
    EXPECT_TRUE(result.ok()) << result.message();
    environment_ = result ? std::move(*result) : LoadedEnvironment{};
    return environment_;
  }
  // The error loading `path` (its message; its code is `LoadFailure(...).code`).
  Diagnostic LoadFailure(const fs::path& path, LoadOptions options = {}) {
    const Result<LoadedEnvironment> result = LoadEnvironment(path, options);
    EXPECT_FALSE(result.ok()) << "loaded " << path;
    return result ? Diagnostic{} : result.error();
  }
  std::string LoadError(const fs::path& path, LoadOptions options = {}) { return LoadFailure(path, options).message; }

  fs::path folder_;
  LoadedEnvironment environment_;
};

}  // namespace vs11::irradiance::envtest
