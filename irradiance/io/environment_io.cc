#include "irradiance/io/environment_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <atomic>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <exception>
#include <new>
#include <numbers>
#include <random>
#include <system_error>
#include <utility>

#include "irradiance/io/image_io_module.h"
#include "irradiance/io/option_names.h"
#include "irradiance/io/image_reader.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using Layout = EnvironmentLayout;

// One row per layout: what it is called in messages, and for single-image layouts the
// aspect ratio columns:rows that kAuto detects it by (0:0 for layouts that are not one image).
struct LayoutInfo {
  Layout layout;
  std::string_view description;
  int aspect_columns;
  int aspect_rows;
};
constexpr std::array<LayoutInfo, 8> kLayoutInfo = {{
    {Layout::kAuto, "automatic", 0, 0},
    {Layout::kFaces, "six face files", 0, 0},
    {Layout::kHorizontalCross, "horizontal cross", 4, 3},
    {Layout::kVerticalCross, "vertical cross", 3, 4},
    {Layout::kHorizontalStrip, "horizontal strip", 6, 1},
    {Layout::kVerticalStrip, "vertical strip", 1, 6},
    {Layout::kLatLong, "lat-long map", 2, 1},
    {Layout::kAngular, "angular map", 1, 1},
}};

const LayoutInfo& Info(Layout layout) {
  for (const LayoutInfo& info : kLayoutInfo) {
    if (info.layout == layout) return info;
  }
  assert(false && "every layout has a row in kLayoutInfo");
  return kLayoutInfo[0];
}

// Where each face sits in a layout made of square cells (see the diagrams in the header).
struct FaceCell {
  int column;
  int row;
  bool rotated_180;
};
struct CubeGrid {
  Layout layout;
  int columns;
  int rows;
  std::array<FaceCell, kCubeFaceCount> cells;  // CubeFace order
};
constexpr std::array<CubeGrid, 4> kCubeGrids = {{
    {Layout::kHorizontalCross,
     4,
     3,
     {{{2, 1, false}, {0, 1, false}, {1, 0, false}, {1, 2, false}, {1, 1, false}, {3, 1, false}}}},
    {Layout::kVerticalCross,
     3,
     4,
     {{{2, 1, false}, {0, 1, false}, {1, 0, false}, {1, 2, false}, {1, 1, false}, {1, 3, true}}}},
    {Layout::kHorizontalStrip,
     6,
     1,
     {{{0, 0, false}, {1, 0, false}, {2, 0, false}, {3, 0, false}, {4, 0, false}, {5, 0, false}}}},
    {Layout::kVerticalStrip,
     1,
     6,
     {{{0, 0, false}, {0, 1, false}, {0, 2, false}, {0, 3, false}, {0, 4, false}, {0, 5, false}}}},
}};

const CubeGrid* FindCubeGrid(Layout layout) {
  for (const CubeGrid& grid : kCubeGrids) {
    if (grid.layout == layout) return &grid;
  }
  return nullptr;
}

// Formats written as linear floats; everything else is written as 8-bit sRGB. (.pfm is read but not
// written: OpenImageIO 2.4 has no PFM writer, tested in environment_io_test.cc.)
constexpr std::array<std::string_view, 4> kFloatExtensions = {".exr", ".hdr", ".tif", ".tiff"};
constexpr double kByteMax = 255.0;
// Size of the exported lat-long (kExportScale N x kExportScale N / 2) and angular maps relative to
// the face size N: a little finer than the cube's centre texels (pi / (2 N) against 2 / N radians).
constexpr int kExportScale = 4;

// The error of an input that cannot be read as an environment (most of the loaders' errors).
Diagnostic Unreadable(std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); }

std::string AcceptedAspectRatios() {
  std::string text;
  for (const LayoutInfo& info : kLayoutInfo) {
    if (info.aspect_columns == 0 || info.layout == Layout::kAngular) continue;  // see DetectLayout
    if (!text.empty()) text += ", ";
    text += fmt::format("{}:{} {}", info.aspect_columns, info.aspect_rows, info.description);
  }
  return text;
}

std::optional<Layout> DetectLayout(int width, int height) {
  for (const LayoutInfo& info : kLayoutInfo) {
    // A square image is an angular map or one face of a cube: never guessed (EnvironmentFromImage asks for the layout).
    if (info.aspect_columns == 0 || info.layout == Layout::kAngular) continue;
    if (static_cast<std::int64_t>(width) * info.aspect_rows ==
        static_cast<std::int64_t>(height) * info.aspect_columns) {
      return info.layout;
    }
  }
  return std::nullopt;
}

// Whether a width x height image can hold `layout` (kAuto: any layout DetectLayout finds; kFaces:
// one square face). Checked on the header's size before any pixel is read, and again on the image.
Status CheckLayoutSize(Layout layout, int width, int height) {
  if (layout == Layout::kAuto) {
    // A square image is read, and then refused by EnvironmentFromImage with its own message.
    if (DetectLayout(width, height) || width == height) return {};
    return Unreadable(fmt::format("cannot detect the layout of a {} x {} image: the accepted aspect ratios are {}",
                                  width, height, AcceptedAspectRatios()));
  }
  if (layout == Layout::kFaces) {
    if (width == height) return {};
    return Unreadable(fmt::format("a cube face must be square, got {} x {}", width, height));
  }
  const LayoutInfo& info = Info(layout);
  if (const CubeGrid* grid = FindCubeGrid(layout)) {
    const int size = width / grid->columns;
    if (size > 0 && width == grid->columns * size && height == grid->rows * size) return {};
    return Unreadable(fmt::format("a {} must be {}N x {}N pixels for a face size N, got {} x {}", info.description,
                                  grid->columns, grid->rows, width, height));
  }
  if (static_cast<std::int64_t>(width) * info.aspect_rows == static_cast<std::int64_t>(height) * info.aspect_columns) {
    return {};
  }
  return Unreadable(fmt::format("a {} must have an aspect ratio of {}:{}, got {} x {}", info.description,
                                info.aspect_columns, info.aspect_rows, width, height));
}

// The check as the OpenImageIO module takes it: its message, the code being kCannotReadFile either way.
ImageSizeCheck LayoutSizeCheck(Layout layout) {
  return [layout](int width, int height) -> std::optional<std::string> {
    if (const Status fits = CheckLayoutSize(layout, width, height); !fits.ok()) return fits.message();
    return std::nullopt;
  };
}

// The pixel of a cross or strip image that holds texel (x, y) of the face in `cell`, faces `size`
// texels wide: the one mapping both directions use (reading a layout, writing one).
glm::ivec2 CellPixel(const FaceCell& cell, int size, int x, int y) {
  const int sx = cell.rotated_180 ? size - 1 - x : x;
  const int sy = cell.rotated_180 ? size - 1 - y : y;
  return {cell.column * size + sx, cell.row * size + sy};
}

CubeMap ExtractFaces(const Image& image, const CubeGrid& grid, int size) {
  CubeMap cube(size);
  for (CubeFace face : kAllCubeFaces) {
    const FaceCell& cell = grid.cells[static_cast<int>(face)];
    Image& out = cube.face(face);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::ivec2 pixel = CellPixel(cell, size, x, y);
        out.at(x, y) = image.at(pixel.x, pixel.y);
      }
    }
  }
  return cube;
}

std::string ReplaceToken(std::string_view pattern, std::string_view replacement) {
  std::string out(pattern);
  for (std::size_t at = out.find(kFaceToken); at != std::string::npos;
       at = out.find(kFaceToken, at + replacement.size())) {
    out.replace(at, kFaceToken.size(), replacement);
  }
  return out;
}

std::string SanitizeWarning(std::size_t changed, std::size_t total, std::string_view what) {
  return fmt::format("{}: {} of {} texels had NaN, infinite or negative values, set to 0", what,
                     changed, total);
}

Result<LoadedEnvironment> LoadFaces(const fs::path& path) {
  const std::string pattern = path.string();
  if (pattern.find(kFaceToken) == std::string::npos) {
    return Unreadable(
        fmt::format("{}: the six-face layout needs a path containing \"{}\"", pattern, kFaceToken));
  }
  LoadedEnvironment environment;
  environment.layout = Layout::kFaces;
  environment.layout_reason = fmt::format("six files: the path holds \"{}\"", kFaceToken);
  std::string first_name;
  for (CubeFace face : kAllCubeFaces) {
    const int index = static_cast<int>(face);
    const std::string short_name = ReplaceToken(pattern, kFaceFileNames[index]);
    const std::string signed_name = ReplaceToken(pattern, kSignedFaceFileNames[index]);
    std::error_code ec;
    const std::string& name = fs::exists(short_name, ec) ? short_name : signed_name;
    if (!fs::exists(name, ec)) {
      return Failure(DiagnosticCode::kNoSuchInput, fmt::format("missing the {} face: neither {} nor {} exists",
                                 CubeFaceName(face), short_name, signed_name));
    }
    Result<ImageRead> read = ReadImageFile(name, LayoutSizeCheck(Layout::kFaces));
    if (!read) return Failure(read.error().code, fmt::format("{} face: {}", CubeFaceName(face), read.message()));
    Image& image = read->image;
    if (image.width != image.height) {
      return Unreadable(fmt::format("{} face ({}) is {} x {} pixels: faces must be square",
                                 CubeFaceName(face), name, image.width, image.height));
    }
    if (face == CubeFace::kPositiveX) {
      environment.cube = CubeMap(image.width);
      first_name = name;
    } else if (image.width != environment.cube.face_size) {
      return Unreadable(fmt::format(
          "{} face ({}) is {} x {} pixels but the +x face ({}) is {} x {}: mismatched face sizes",
          CubeFaceName(face), name, image.width, image.height, first_name,
          environment.cube.face_size, environment.cube.face_size));
    }
    if (const std::size_t changed = SanitizeRadiance(image); changed > 0) {
      environment.warnings.push_back(SanitizeWarning(changed, image.pixels.size(), name));
    }
    environment.cube.face(face) = std::move(image);
  }
  return environment;
}

// ---- Writing -----------------------------------------------------------------------------------

bool HasFloatExtension(const fs::path& path) {
  const std::string extension = AsciiLower(path.extension().string());
  return std::find(kFloatExtensions.begin(), kFloatExtensions.end(), extension) !=
         kFloatExtensions.end();
}

// Writes `image` to a new temporary file beside `path` in `format` (an OpenImageIO format name, or
// empty for the one `path`'s extension names). Returns the temporary's path, or the error
// (kCannotWriteFile, naming `path`).
Result<fs::path> WriteTemporary(const Image& image, const fs::path& path, std::string_view format) {
  const auto failure = [&](std::string_view why) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: {}", path.string(), why));
  };
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    return failure("cannot write a zero-size image");
  }
  const bool as_float = format == "openexr" || (format.empty() && HasFloatExtension(path));
  const Result<const ImageIoApi*> module = ImageIo();
  if (!module) return failure(module.message());
  const ImageIoApi* image_io = *module;

  std::vector<float> floats;
  std::vector<std::uint8_t> bytes;
  const void* data = nullptr;
  if (as_float) {
    floats.reserve(image.pixels.size() * 3);
    for (const glm::vec3& p : image.pixels) floats.insert(floats.end(), {p.r, p.g, p.b});
    data = floats.data();
  } else {
    bytes.reserve(image.pixels.size() * 3);
    for (const glm::vec3& p : image.pixels) {
      for (int c = 0; c < 3; ++c) {
        const double value =
            std::isnan(p[c]) ? 0.0 : std::clamp(static_cast<double>(p[c]), 0.0, 1.0);
        bytes.push_back(static_cast<std::uint8_t>(std::lround(LinearToSrgb(value) * kByteMax)));
      }
    }
    data = bytes.data();
  }

  const fs::path temporary = TemporaryPathBeside(path);
  const OiioWriteRequest request{format.empty() ? path.string() : std::string(format), temporary,
                                 image.width, image.height, as_float, data};
  // The module answers with a plain message (image_io_module.h says why); it becomes a Result here.
  if (std::optional<std::string> refused = image_io->write(request)) {
    RemoveQuietly(temporary);
    return failure(*refused);
  }
  return temporary;
}

Status WriteAtomically(const Image& image, const fs::path& path, std::string_view format) {
  try {
    const Result<fs::path> temporary = WriteTemporary(image, path, format);
    if (!temporary) return temporary.error();
    const PendingRename rename[] = {{*temporary, path}};
    return CommitRenames(rename);
  } catch (const std::exception& e) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: {}", path.string(), e.what()));
  }
}

}  // namespace

// ---- Public ------------------------------------------------------------------------------------

std::size_t SanitizeRadiance(Image& image) {
  std::size_t changed = 0;
  for (glm::vec3& p : image.pixels) {
    bool any = false;
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p[c]) || p[c] < 0.0f) {
        p[c] = 0.0f;
        any = true;
      }
    }
    changed += any ? 1 : 0;
  }
  return changed;
}

Image CubeMapToImage(const CubeMap& cube, EnvironmentLayout layout) {
  assert(cube.face_size > 0);
  const int n = cube.face_size;
  if (const CubeGrid* grid = FindCubeGrid(layout)) {
    Image image(grid->columns * n, grid->rows * n);
    for (CubeFace face : kAllCubeFaces) {
      const FaceCell& cell = grid->cells[static_cast<int>(face)];
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const glm::ivec2 pixel = CellPixel(cell, n, x, y);
          image.at(pixel.x, pixel.y) = cube.face(face).at(x, y);
        }
      }
    }
    return image;
  }
  if (layout == Layout::kLatLong) {
    Image image(kExportScale * n, kExportScale * n / 2);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        image.at(x, y) = SampleCubeMap(
            cube, LatLongDirection((x + 0.5) / image.width, (y + 0.5) / image.height));
      }
    }
    return image;
  }
  assert(layout == Layout::kAngular);
  Image image(kExportScale * n, kExportScale * n);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double a = 2.0 * (x + 0.5) / image.width - 1.0;
      const double b = 1.0 - 2.0 * (y + 0.5) / image.height;
      if (a * a + b * b > 1.0) continue;  // outside the disk
      image.at(x, y) = SampleCubeMap(cube, AngularDirection(a, b));
    }
  }
  return image;
}

Result<ImageRead> ReadImage(const std::filesystem::path& path) {
  try {
    return ReadImageFile(path, nullptr);
  } catch (const std::exception& e) {
    return Unreadable(fmt::format("{}: {}", path.string(), e.what()));
  }
}

Result<LoadedEnvironment> EnvironmentFromImage(Image image, EnvironmentLayout layout, int face_size,
                                               bool keep_latlong) {
  try {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
      return Unreadable(fmt::format("zero-size image ({} x {} pixels)", image.width, image.height));
    }
    if (layout == Layout::kFaces) {
      return Unreadable(fmt::format(
          "the six-face layout reads six files: pass a path containing \"{}\"", kFaceToken));
    }
    if (Status fits = CheckLayoutSize(layout, image.width, image.height); !fits.ok()) return fits.error();
    LoadedEnvironment environment;
    environment.layout_reason = "as given";
    if (layout == Layout::kAuto) {
      if (image.width == image.height) {
        // The caller must name the layout: a usage error rather than a bad file.
        return Failure(DiagnosticCode::kOptionValue,
                       fmt::format("cannot tell the layout of a square {} x {} image: it may be an angular map "
                                   "(--layout angular) or one face of a cube (--layout faces, with \"{}\" in the "
                                   "path); name it with --layout",
                                   image.width, image.height, kFaceToken));
      }
      layout = *DetectLayout(image.width, image.height);
      const LayoutInfo& info = Info(layout);
      environment.layout_reason = fmt::format("detected from the {}:{} aspect ratio of the {} x {} image",
                                              info.aspect_columns, info.aspect_rows, image.width, image.height);
    }
    environment.layout = layout;
    if (const std::size_t changed = SanitizeRadiance(image); changed > 0) {
      environment.warnings.push_back(SanitizeWarning(changed, image.pixels.size(), "image"));
    }
    if (const CubeGrid* grid = FindCubeGrid(layout)) {
      environment.cube = ExtractFaces(image, *grid, image.width / grid->columns);
    } else if (layout == Layout::kLatLong && keep_latlong) {
      environment.latlong = std::move(image);
    } else {
      if (face_size < 1 || face_size > kMaxFaceSize) {
        return Failure(DiagnosticCode::kFaceSize,
                       fmt::format("face size {} is outside [1, {}]", face_size, kMaxFaceSize));
      }
      environment.cube = layout == Layout::kLatLong ? ResampleLatLong(image, face_size)
                                                    : ResampleAngular(image, face_size);
    }
    return environment;
  } catch (const std::bad_alloc&) {
    const int size = FindCubeGrid(layout) != nullptr ? image.width / FindCubeGrid(layout)->columns : face_size;
    return Failure(DiagnosticCode::kOutOfMemory,
                   fmt::format("out of memory while building the cube map (faces of {} need about {} MB)", size,
                               (static_cast<std::size_t>(size) * size * kCubeFaceCount * sizeof(glm::vec3) >> 20) + 1));
  } catch (const std::exception& e) {
    return Unreadable(fmt::format("cannot build the cube map: {}", e.what()));
  }
}

Result<LoadedEnvironment> LoadEnvironment(const std::filesystem::path& path, const LoadOptions& options) {
  try {
    const bool face_pattern = path.string().find(kFaceToken) != std::string::npos;
    if (options.layout == Layout::kFaces || (options.layout == Layout::kAuto && face_pattern)) {
      return LoadFaces(path);
    }
    Result<ImageRead> read = ReadImageFile(path, LayoutSizeCheck(options.layout));
    if (!read) return read.error();
    Layout layout = options.layout;
    if (read->is_dds_cube_map) {
      if (layout != Layout::kAuto && layout != Layout::kVerticalStrip) {
        return Unreadable(fmt::format(
            "{}: a DDS cube map holds its six faces itself; its layout can only be auto or vstrip, "
            "not {}",
            path.string(), LayoutName(layout)));
      }
      layout = Layout::kVerticalStrip;
    }
    Result<LoadedEnvironment> result =
        EnvironmentFromImage(std::move(read->image), layout, options.face_size, options.keep_latlong);
    if (!result) return Failure(result.error().code, fmt::format("{}: {}", path.string(), result.message()));
    if (read->is_dds_cube_map) result->layout_reason = "a DDS cube map";
    for (std::string& warning : result->warnings) warning = fmt::format("{}: {}", path.string(), warning);
    return result;
  } catch (const std::bad_alloc&) {
    return Failure(DiagnosticCode::kOutOfMemory, fmt::format("{}: out of memory while reading it", path.string()));
  } catch (const std::exception& e) {
    return Unreadable(fmt::format("{}: {}", path.string(), e.what()));
  }
}

Status WriteImage(const Image& image, const std::filesystem::path& path) { return WriteAtomically(image, path, ""); }

Status WriteCrossExr(const CubeMap& cube, const std::filesystem::path& path) {
  if (cube.face_size <= 0) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile,
                         fmt::format("{}: cannot write an empty cube map", path.string()));
  }
  return WriteAtomically(CubeMapToImage(cube, Layout::kHorizontalCross), path, "openexr");
}

Status WriteCubeMap(const CubeMap& cube, const std::filesystem::path& path, EnvironmentLayout layout) {
  if (cube.face_size <= 0) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile,
                         fmt::format("{}: cannot write an empty cube map", path.string()));
  }
  const std::string pattern = path.string();
  const bool face_pattern = pattern.find(kFaceToken) != std::string::npos;
  if (layout == Layout::kAuto) layout = face_pattern ? Layout::kFaces : Layout::kHorizontalCross;
  if (layout != Layout::kFaces) return WriteAtomically(CubeMapToImage(cube, layout), path, "");
  if (!face_pattern) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile,
                         fmt::format("{}: writing six faces needs a path containing \"{}\"", pattern, kFaceToken));
  }
  try {
    std::vector<PendingRename> renames;
    for (CubeFace face : kAllCubeFaces) {
      const fs::path target = ReplaceToken(pattern, kFaceFileNames[static_cast<int>(face)]);
      const Result<fs::path> temporary = WriteTemporary(cube.face(face), target, "");
      if (!temporary) {
        for (const PendingRename& written : renames) RemoveQuietly(written.temporary);
        return temporary.error();
      }
      renames.push_back({*temporary, target});
    }
    return CommitRenames(renames);
  } catch (const std::exception& e) {
    return vs11::Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: {}", pattern, e.what()));
  }
}

Status CheckFaceSizeOption(std::string_view option, int face_size, int max_size) {
  if (IsPowerOfTwo(face_size) && face_size <= max_size) return {};
  return vs11::Failure(DiagnosticCode::kFaceSize,
                       fmt::format("{} must be a power of two from 1 to {} (the mip pyramid halves it down to 1x1)",
                                   OptionWithValue(option, face_size), max_size));
}

Status CheckPyramidFaceSize(std::string_view source, int face_size) {
  if (IsPowerOfTwo(face_size)) return {};
  return vs11::Failure(
      DiagnosticCode::kFaceSize,
      fmt::format("{}face size {} is not a power of two; the mip pyramid needs exact 2x2 parents down to 1x1 "
                  "(resample the map, or give a lat-long map with --face-size)",
                  source.empty() ? std::string() : std::string(source) + ": ", face_size));
}

}  // namespace vs11::irradiance
