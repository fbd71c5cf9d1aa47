#include "irradiance/io/environment_io.h"

// The system fmt goes first so that OpenImageIO's headers reuse it instead of their bundled copy.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <atomic>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <numbers>
#include <random>
#include <system_error>
#include <utility>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "irradiance/io/dds_reader.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using Layout = EnvironmentLayout;

// One row per layout: its name, what it is called in messages, and for single-image layouts the
// aspect ratio columns:rows that kAuto detects it by (0:0 for layouts that are not one image).
struct LayoutInfo {
  Layout layout;
  std::string_view name;
  std::string_view description;
  int aspect_columns;
  int aspect_rows;
};
constexpr std::array<LayoutInfo, 8> kLayoutInfo = {{
    {Layout::kAuto, "auto", "automatic", 0, 0},
    {Layout::kFaces, "faces", "six face files", 0, 0},
    {Layout::kHorizontalCross, "hcross", "horizontal cross", 4, 3},
    {Layout::kVerticalCross, "vcross", "vertical cross", 3, 4},
    {Layout::kHorizontalStrip, "hstrip", "horizontal strip", 6, 1},
    {Layout::kVerticalStrip, "vstrip", "vertical strip", 1, 6},
    {Layout::kLatLong, "latlong", "lat-long map", 2, 1},
    {Layout::kAngular, "angular", "angular map", 1, 1},
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
// IEC 61966-2-1 sRGB transfer function constants.
constexpr double kSrgbDecodeThreshold = 0.04045;
constexpr double kSrgbEncodeThreshold = 0.0031308;
constexpr double kSrgbLinearSlope = 12.92;
constexpr double kSrgbOffset = 0.055;
constexpr double kSrgbGamma = 2.4;
// Size of the exported lat-long (kExportScale N x kExportScale N / 2) and angular maps relative to
// the face size N: a little finer than the cube's centre texels (pi / (2 N) against 2 / N radians).
constexpr int kExportScale = 4;
// What the DDS reader reports for a cube map with every face.
constexpr std::string_view kCubeTextureFormat = "CubeFace Environment";
constexpr std::string_view kAllDdsCubeSides = "+x -x +y -y +z -z";

LoadResult Failure(std::string message) {
  LoadResult result;
  result.error = std::move(message);
  return result;
}

ImageReadResult ReadFailure(std::string message) {
  ImageReadResult result;
  result.error = std::move(message);
  return result;
}

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string AcceptedAspectRatios() {
  std::string text;
  for (const LayoutInfo& info : kLayoutInfo) {
    if (info.aspect_columns == 0) continue;
    if (!text.empty()) text += ", ";
    text += fmt::format("{}:{} {}", info.aspect_columns, info.aspect_rows, info.description);
  }
  return text;
}

std::optional<Layout> DetectLayout(int width, int height) {
  for (const LayoutInfo& info : kLayoutInfo) {
    if (info.aspect_columns == 0) continue;
    if (static_cast<std::int64_t>(width) * info.aspect_rows ==
        static_cast<std::int64_t>(height) * info.aspect_columns) {
      return info.layout;
    }
  }
  return std::nullopt;
}

// Whether a width x height image can hold `layout` (kAuto: any layout DetectLayout finds; kFaces:
// one square face). Checked on the header's size before any pixel is read, and again on the image.
std::optional<std::string> CheckLayoutSize(Layout layout, int width, int height) {
  if (layout == Layout::kAuto) {
    if (DetectLayout(width, height)) return std::nullopt;
    return fmt::format("cannot detect the layout of a {} x {} image: the accepted aspect ratios are {}",
                       width, height, AcceptedAspectRatios());
  }
  if (layout == Layout::kFaces) {
    if (width == height) return std::nullopt;
    return fmt::format("a cube face must be square, got {} x {}", width, height);
  }
  const LayoutInfo& info = Info(layout);
  if (const CubeGrid* grid = FindCubeGrid(layout)) {
    const int size = width / grid->columns;
    if (size > 0 && width == grid->columns * size && height == grid->rows * size) return std::nullopt;
    return fmt::format("a {} must be {}N x {}N pixels for a face size N, got {} x {}", info.description,
                       grid->columns, grid->rows, width, height);
  }
  if (static_cast<std::int64_t>(width) * info.aspect_rows == static_cast<std::int64_t>(height) * info.aspect_columns) {
    return std::nullopt;
  }
  return fmt::format("a {} must have an aspect ratio of {}:{}, got {} x {}", info.description, info.aspect_columns,
                     info.aspect_rows, width, height);
}

// ---- Reading -----------------------------------------------------------------------------------

// Held while OpenImageIO reads the pixels of a DDS cube map (see ReadImage): one per process,
// because the state it protects is OpenImageIO's, which is one per process.
std::mutex& DdsCubeReadMutex() {
  static std::mutex mutex;
  return mutex;
}

bool IsFloatType(OIIO::TypeDesc type) {
  return type.basetype == OIIO::TypeDesc::FLOAT || type.basetype == OIIO::TypeDesc::HALF ||
         type.basetype == OIIO::TypeDesc::DOUBLE;
}

std::string OiioMessage(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  return message.empty() ? std::string("no details from OpenImageIO") : message;
}

// Whether OpenImageIO has a reader for the extension of `path` ("extension_list" is
// "openexr:exr,sxr,mxr;tiff:tif,tiff,...").
bool IsKnownImageExtension(const fs::path& path) {
  std::string extension = Lower(path.extension().string());
  if (extension.empty()) return false;
  extension.erase(0, 1);  // the dot
  const std::string list = OIIO::get_string_attribute("extension_list");
  std::size_t begin = 0;
  while (begin < list.size()) {
    std::size_t end = list.find_first_of(":,;", begin);
    if (end == std::string::npos) end = list.size();
    const std::string_view token(list.data() + begin, end - begin);
    const bool is_format_name = end < list.size() && list[end] == ':';
    if (!is_format_name && token == extension) return true;
    begin = end + 1;
  }
  return false;
}

// The bytes of pixels a file must hold when they are stored uncompressed, as in PFM and in TIFF
// without compression (one sample of 8 bits or more per channel, no palette); nullopt for other
// files. Checked before the pixel buffer is allocated: OpenImageIO reads a short uncompressed TIFF
// without failing, and a tiny file must not make us allocate what its header claims.
std::optional<std::uint64_t> UncompressedPixelBytes(const OIIO::ImageInput& input,
                                                    const OIIO::ImageSpec& spec) {
  const std::string format = Lower(input.format_name());
  const bool pfm = format == "pnm" && spec.format == OIIO::TypeDesc::FLOAT;
  constexpr int kPhotometricPalette = 3;
  const bool raw_tiff =
      format == "tiff" &&
      Lower(std::string(spec.get_string_attribute("compression", "none"))) == "none" &&
      spec.get_int_attribute("oiio:BitsPerSample", 0) >= 8 &&
      spec.get_int_attribute("tiff:PhotometricInterpretation", 0) < kPhotometricPalette;
  if (!pfm && !raw_tiff) return std::nullopt;
  return static_cast<std::uint64_t>(spec.image_bytes(/*native=*/true));
}

// The largest ratio of pixel data to file size a compressed file may declare, per format. A header
// of a few bytes can claim an image of up to kMaxImagePixels, and OpenImageIO (and this loader)
// allocate the whole image before finding the data missing: gigabytes for a 400-byte EXR or PNG.
// Each bound is about the most that format's coding reaches on a constant image: deflate (PNG;
// EXR zip, zips, pxr24, piz's Huffman with run lengths stays below it) 1032:1; Radiance HDR's run
// lengths 127 bytes in 2; EXR rle 128 bytes in 2; EXR b44a 32 bytes in 3; EXR dwaa/dwab run-length
// code the transformed blocks and deflate them again, 32 x 1032. Other formats get deflate's bound:
// an image that compresses further (a BMP ending in its end-of-image code) is refused with a message
// saying so.
double MaxCompressionRatio(std::string_view format, std::string_view compression) {
  constexpr double kDeflate = 1032;
  if (format == "hdr") return 64;
  if (format == "openexr") {
    if (compression.starts_with("none")) return 1;
    if (compression.starts_with("rle")) return 64;
    if (compression.starts_with("b44")) return 11;
    if (compression.starts_with("dwa")) return 32 * kDeflate;
  }
  return kDeflate;
}

// Refuses, from the header alone, a compressed file too small for the image it declares (see
// MaxCompressionRatio). The pixel data is counted low: one channel per pixel, at the file's
// smallest sample size, so that no image its format can really store is refused.
std::optional<std::string> CheckCompressionRatio(const OIIO::ImageInput& input, const OIIO::ImageSpec& spec,
                                                 std::uintmax_t file_size) {
  const std::string format = Lower(input.format_name());
  const std::string compression = Lower(std::string(spec.get_string_attribute("compression", "")));
  int bits_per_sample = spec.get_int_attribute("oiio:BitsPerSample", static_cast<int>(spec.format.size() * 8));
  if (format == "openexr") bits_per_sample = 16;  // half, the smallest EXR sample
  if (format == "hdr") bits_per_sample = 8;       // one byte of RGBE
  const double pixel_bytes = static_cast<double>(spec.width) * spec.height * std::max(bits_per_sample, 1) / 8;
  const double ratio = MaxCompressionRatio(format, compression);
  if (pixel_bytes <= ratio * static_cast<double>(file_size)) return std::nullopt;
  return fmt::format(
      "corrupt or truncated file: its header declares a {} x {} image, at least {:.0f} bytes of pixels, "
      "which {} bytes of {}{} cannot hold (more than the {:.0f}:1 this format's compression reaches)",
      spec.width, spec.height, pixel_bytes, file_size, format, compression.empty() ? "" : " " + compression,
      ratio);
}

// The environment-map rules for a DDS file, beyond the container's own (dds_reader.h): a cube map
// has six square faces.
std::optional<std::string> DdsEnvironmentProblem(const DdsFileHeader& header) {
  if (!header.is_cube_map) return std::nullopt;
  if (header.width != header.height) {
    return fmt::format("DDS cube map faces are {} x {} pixels: faces must be square", header.width,
                       header.height);
  }
  if (header.faces != kCubeFaceCount) {
    return fmt::format("DDS cube map has {} of the six faces (cube map flags {:#x}), all six are "
                       "needed",
                       header.faces, header.cube_face_flags);
  }
  return std::nullopt;
}

// The file being read: its path and, when it could be found, its size.
struct ImageFile {
  fs::path path;
  std::optional<std::uintmax_t> size;
};

// Whether `path` names a non-empty regular file; fills `file`.
std::optional<std::string> CheckIsFile(const fs::path& path, ImageFile& file) {
  file.path = path;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) return "file not found";
  if (!fs::is_regular_file(status)) return "not a regular file";
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec) file.size = size;
  if (size == 0 && !ec) return "file is empty";
  return std::nullopt;
}

// A DDS file, before OpenImageIO sees it: read here (`read`), refused (`error`), or left to
// OpenImageIO, with a cube map's faces stacked into one plain image in memory (dds_reader.h).
struct DdsStage {
  std::optional<Image> read;
  std::optional<std::string> error;
  bool is_cube_map = false;
  std::vector<unsigned char> stacked_faces;
};

DdsStage ReadDdsStage(const fs::path& path) {
  DdsStage stage;
  const DdsFileHeaderResult header = ReadDdsHeader(path, kMaxImagePixels);
  if (header.outcome == DdsFileHeaderResult::Outcome::kNotDds) return stage;
  if (header.outcome == DdsFileHeaderResult::Outcome::kError) {
    stage.error = header.error;
    return stage;
  }
  if ((stage.error = DdsEnvironmentProblem(header.header))) return stage;
  stage.is_cube_map = header.header.is_cube_map;
  DdsReadResult pixels = ReadDdsPixels(path, header.header);
  switch (pixels.outcome) {
    case DdsReadResult::Outcome::kError:
      stage.error = std::move(pixels.error);
      break;
    case DdsReadResult::Outcome::kRead:
      stage.read = std::move(pixels.image);
      break;
    case DdsReadResult::Outcome::kLeaveToOpenImageIo:
      stage.stacked_faces = std::move(pixels.stacked_faces);
      break;
  }
  return stage;
}

// An OpenImageIO reader, and the memory it reads in place of the file, which must outlive it.
struct OpenedImage {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> input;
  OIIO::ImageSpec spec;
  bool read_by_faces = false;  // a DDS cube map OpenImageIO serves face by face
  bool dds_cube_map = false;   // read_by_faces, or stacked faces read as one image
};

std::optional<std::string> OpenImage(const ImageFile& file, const DdsStage& dds, OpenedImage& opened) {
  OIIO::ImageSpec open_config;
  if (!dds.stacked_faces.empty()) {
    opened.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(
        const_cast<unsigned char*>(dds.stacked_faces.data()), dds.stacked_faces.size());
    void* proxy = opened.memory.get();
    open_config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  }
  opened.input = OIIO::ImageInput::open(file.path.string(), opened.memory ? &open_config : nullptr);
  if (!opened.input) {
    const std::string oiio_error = OiioMessage(OIIO::geterror());
    if (!IsKnownImageExtension(file.path)) {
      return fmt::format("unsupported image format ({})", oiio_error);
    }
    return fmt::format(
        "cannot read: corrupt or truncated file, or a variant OpenImageIO does not read ({})",
        oiio_error);
  }
  opened.spec = opened.input->spec();
  opened.read_by_faces =
      Lower(opened.input->format_name()) == "dds" &&
      std::string(opened.spec.get_string_attribute("textureformat")) == kCubeTextureFormat;
  opened.dds_cube_map = opened.read_by_faces || (opened.memory && dds.is_cube_map);
  return std::nullopt;
}

// The checks on OpenImageIO's header before any pixel is read: the size, the layout `expected`
// (when set), truncation and the compression ratio, a DDS cube map's faces.
std::optional<std::string> CheckOpenedHeader(const ImageFile& file, const OpenedImage& opened,
                                             std::optional<Layout> expected) {
  const OIIO::ImageSpec& spec = opened.spec;
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels <= 0) {
    return fmt::format("zero-size image ({} x {} pixels, {} channels)", spec.width, spec.height,
                       spec.nchannels);
  }
  const std::size_t pixel_count = static_cast<std::size_t>(spec.width) * spec.height;
  if (spec.width > static_cast<int>(kMaxImagePixels) || pixel_count > kMaxImagePixels) {
    return fmt::format("image of {} x {} pixels is larger than the {} pixels accepted", spec.width,
                       spec.height, kMaxImagePixels);
  }
  if (expected && !opened.dds_cube_map) {
    if (std::optional<std::string> error = CheckLayoutSize(*expected, spec.width, spec.height)) {
      return error;
    }
  }
  const std::optional<std::uint64_t> needed = UncompressedPixelBytes(*opened.input, spec);
  if (needed && file.size && *file.size < *needed) {
    return fmt::format(
        "truncated file: {} bytes, but the {} x {} uncompressed pixels its header declares take {}",
        *file.size, spec.width, spec.height, *needed);
  }
  if (file.size && !needed) {
    if (std::optional<std::string> error = CheckCompressionRatio(*opened.input, spec, *file.size)) {
      return error;
    }
  }
  if (opened.read_by_faces) {
    const std::string sides(spec.get_string_attribute("dds:CubeMapSides"));
    if (sides != kAllDdsCubeSides || spec.height != 6 * spec.width) {
      return fmt::format("DDS cube map has faces \"{}\", all six (\"{}\") are needed", sides,
                         kAllDdsCubeSides);
    }
  }
  return std::nullopt;
}

// Reads the first `channels` channels of every pixel as float into `data`.
std::optional<std::string> ReadPixels(OpenedImage& opened, int channels, std::vector<float>& data) {
  data.resize(static_cast<std::size_t>(opened.spec.width) * opened.spec.height * channels);
  // OpenImageIO 2.4's DDS reader serves a cube map's faces as tiles and remembers which face its
  // buffer holds in function-level statics (DDSInput::read_native_tile's lastx/lasty/lastz), shared
  // by every reader in the process: two cube maps read at once hand each other's face numbers over
  // and copy a stale face. Most cube maps are therefore read as stacked faces (above); those whose
  // faces do not stack (BC faces not a multiple of 4 texels, faces over 5461 texels) are read by
  // faces one at a time. Every other reader keeps its state in its own object
  // (environment_concurrency_test.cc reads every format from 4 threads).
  std::unique_lock<std::mutex> dds_cube_read;
  if (opened.read_by_faces) dds_cube_read = std::unique_lock(DdsCubeReadMutex());
  // Some readers (TIFF, DDS, BMP) return true for a short file and only record the error.
  if (!opened.input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()) ||
      opened.input->has_error()) {
    return fmt::format("cannot read pixels, corrupt or truncated file ({})",
                       OiioMessage(opened.input->geterror()));
  }
  opened.input->close();
  return std::nullopt;
}

// The pixels as linear RGB: integer data holds sRGB-encoded values unless the reader says it is
// linear; one- and two-channel images replicate their first channel.
Image ToLinearRgb(const OIIO::ImageSpec& spec, int channels, const std::vector<float>& data) {
  const bool decode_srgb =
      !IsFloatType(spec.format) &&
      Lower(std::string(spec.get_string_attribute("oiio:ColorSpace"))) != "linear";
  Image image(spec.width, spec.height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
      float value = data[i * channels + (channels == 3 ? c : 0)];
      if (decode_srgb) value = static_cast<float>(SrgbToLinear(value));
      rgb[c] = value;
    }
    image.pixels[i] = rgb;
  }
  return image;
}

// `expected`: the layout the image must fit, checked on the header's size before the pixels are
// read, so that a small file claiming a huge image of a useless shape allocates nothing; nullopt
// for any shape (ReadImage). A DDS cube map is always accepted (it is read as a vertical strip).
ImageReadResult ReadImageUnchecked(const fs::path& path, std::optional<Layout> expected) {
  const auto failure = [&](std::string_view message) {
    return ReadFailure(fmt::format("{}: {}", path.string(), message));
  };
  ImageFile file;
  if (std::optional<std::string> error = CheckIsFile(path, file)) return failure(*error);
  DdsStage dds = ReadDdsStage(path);
  if (dds.error) return failure(*dds.error);
  ImageReadResult result;
  result.is_dds_cube_map = dds.is_cube_map;
  if (dds.read) {
    result.image = std::move(dds.read);
    return result;
  }
  OpenedImage opened;
  if (std::optional<std::string> error = OpenImage(file, dds, opened)) return failure(*error);
  if (std::optional<std::string> error = CheckOpenedHeader(file, opened, expected)) {
    return failure(*error);
  }
  const int channels = std::min(opened.spec.nchannels, 3);
  std::vector<float> data;
  if (std::optional<std::string> error = ReadPixels(opened, channels, data)) return failure(*error);
  result.is_dds_cube_map = opened.dds_cube_map;
  result.image = ToLinearRgb(opened.spec, channels, data);
  return result;
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

LoadResult LoadFaces(const fs::path& path) {
  const std::string pattern = path.string();
  if (pattern.find(kFaceToken) == std::string::npos) {
    return Failure(
        fmt::format("{}: the six-face layout needs a path containing \"{}\"", pattern, kFaceToken));
  }
  LoadedEnvironment environment;
  environment.layout = Layout::kFaces;
  std::string first_name;
  for (CubeFace face : kAllCubeFaces) {
    const int index = static_cast<int>(face);
    const std::string short_name = ReplaceToken(pattern, kFaceFileNames[index]);
    const std::string signed_name = ReplaceToken(pattern, kSignedFaceFileNames[index]);
    std::error_code ec;
    const std::string& name = fs::exists(short_name, ec) ? short_name : signed_name;
    if (!fs::exists(name, ec)) {
      return Failure(fmt::format("missing the {} face: neither {} nor {} exists",
                                 CubeFaceName(face), short_name, signed_name));
    }
    ImageReadResult read = ReadImageUnchecked(name, Layout::kFaces);
    if (!read.ok()) return Failure(fmt::format("{} face: {}", CubeFaceName(face), read.error));
    Image& image = *read.image;
    if (image.width != image.height) {
      return Failure(fmt::format("{} face ({}) is {} x {} pixels: faces must be square",
                                 CubeFaceName(face), name, image.width, image.height));
    }
    if (face == CubeFace::kPositiveX) {
      environment.cube = CubeMap(image.width);
      first_name = name;
    } else if (image.width != environment.cube.face_size) {
      return Failure(fmt::format(
          "{} face ({}) is {} x {} pixels but the +x face ({}) is {} x {}: mismatched face sizes",
          CubeFaceName(face), name, image.width, image.height, first_name,
          environment.cube.face_size, environment.cube.face_size));
    }
    if (const std::size_t changed = SanitizeRadiance(image); changed > 0) {
      environment.warnings.push_back(SanitizeWarning(changed, image.pixels.size(), name));
    }
    environment.cube.face(face) = std::move(image);
  }
  LoadResult result;
  result.environment = std::move(environment);
  return result;
}

// ---- Writing -----------------------------------------------------------------------------------

bool HasFloatExtension(const fs::path& path) {
  const std::string extension = Lower(path.extension().string());
  return std::find(kFloatExtensions.begin(), kFloatExtensions.end(), extension) !=
         kFloatExtensions.end();
}

// Writes `image` to a new temporary file beside `path` in `format` (an OpenImageIO format name, or
// empty for the one `path`'s extension names). Returns the temporary's path, or sets `error`.
std::optional<fs::path> WriteTemporary(const Image& image, const fs::path& path,
                                       std::string_view format, std::string& error) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    error = fmt::format("{}: cannot write a zero-size image", path.string());
    return std::nullopt;
  }
  const bool as_float = format == "openexr" || (format.empty() && HasFloatExtension(path));
  auto output = OIIO::ImageOutput::create(format.empty() ? path.string() : std::string(format));
  if (!output) {
    error = fmt::format("{}: unsupported output format ({})", path.string(),
                        OiioMessage(OIIO::geterror()));
    return std::nullopt;
  }
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", as_float ? "Linear" : "sRGB");
  if (std::string_view(output->format_name()) == "openexr") spec.attribute("compression", "zip");

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
  if (!output->open(temporary.string(), spec)) {
    error =
        fmt::format("{}: cannot create file ({})", path.string(), OiioMessage(output->geterror()));
    RemoveQuietly(temporary);
    return std::nullopt;
  }
  const bool written =
      output->write_image(as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8, data);
  const bool closed = output->close();
  if (!written || !closed) {
    error = fmt::format("{}: write failed ({})", path.string(), OiioMessage(output->geterror()));
    RemoveQuietly(temporary);
    return std::nullopt;
  }
  return temporary;
}

std::optional<std::string> WriteAtomically(const Image& image, const fs::path& path,
                                           std::string_view format) {
  try {
    std::string error;
    const std::optional<fs::path> temporary = WriteTemporary(image, path, format, error);
    if (!temporary) return error;
    const PendingRename rename[] = {{*temporary, path}};
    return CommitRenames(rename);
  } catch (const std::exception& e) {
    return fmt::format("{}: {}", path.string(), e.what());
  }
}

}  // namespace

// ---- Public ------------------------------------------------------------------------------------

std::optional<EnvironmentLayout> ParseLayout(std::string_view name) {
  for (const LayoutInfo& info : kLayoutInfo) {
    if (info.name == name) return info.layout;
  }
  return std::nullopt;
}

std::string_view LayoutName(EnvironmentLayout layout) { return Info(layout).name; }

double SrgbToLinear(double encoded) {
  if (encoded <= kSrgbDecodeThreshold) return encoded / kSrgbLinearSlope;
  return std::pow((encoded + kSrgbOffset) / (1.0 + kSrgbOffset), kSrgbGamma);
}

double LinearToSrgb(double linear) {
  if (linear <= kSrgbEncodeThreshold) return linear * kSrgbLinearSlope;
  return (1.0 + kSrgbOffset) * std::pow(linear, 1.0 / kSrgbGamma) - kSrgbOffset;
}

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

ImageReadResult ReadImage(const std::filesystem::path& path) {
  try {
    return ReadImageUnchecked(path, std::nullopt);
  } catch (const std::exception& e) {
    return ReadFailure(fmt::format("{}: {}", path.string(), e.what()));
  }
}

LoadResult EnvironmentFromImage(Image image, EnvironmentLayout layout, int face_size) {
  try {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
      return Failure(fmt::format("zero-size image ({} x {} pixels)", image.width, image.height));
    }
    if (layout == Layout::kFaces) {
      return Failure(fmt::format(
          "the six-face layout reads six files: pass a path containing \"{}\"", kFaceToken));
    }
    if (std::optional<std::string> error = CheckLayoutSize(layout, image.width, image.height)) {
      return Failure(std::move(*error));
    }
    if (layout == Layout::kAuto) layout = *DetectLayout(image.width, image.height);

    LoadedEnvironment environment;
    environment.layout = layout;
    if (const std::size_t changed = SanitizeRadiance(image); changed > 0) {
      environment.warnings.push_back(SanitizeWarning(changed, image.pixels.size(), "image"));
    }
    if (const CubeGrid* grid = FindCubeGrid(layout)) {
      environment.cube = ExtractFaces(image, *grid, image.width / grid->columns);
    } else {
      if (face_size < 1 || face_size > kMaxFaceSize) {
        return Failure(fmt::format("face size {} is outside [1, {}]", face_size, kMaxFaceSize));
      }
      environment.cube = layout == Layout::kLatLong ? ResampleLatLong(image, face_size)
                                                    : ResampleAngular(image, face_size);
    }
    LoadResult result;
    result.environment = std::move(environment);
    return result;
  } catch (const std::exception& e) {
    return Failure(fmt::format("cannot build the cube map: {}", e.what()));
  }
}

LoadResult LoadEnvironment(const std::filesystem::path& path, const LoadOptions& options) {
  try {
    const bool face_pattern = path.string().find(kFaceToken) != std::string::npos;
    if (options.layout == Layout::kFaces || (options.layout == Layout::kAuto && face_pattern)) {
      return LoadFaces(path);
    }
    ImageReadResult read = ReadImageUnchecked(path, options.layout);
    if (!read.ok()) return Failure(std::move(read.error));
    Layout layout = options.layout;
    if (read.is_dds_cube_map) {
      if (layout != Layout::kAuto && layout != Layout::kVerticalStrip) {
        return Failure(fmt::format(
            "{}: a DDS cube map holds its six faces itself; its layout can only be auto or vstrip, "
            "not {}",
            path.string(), LayoutName(layout)));
      }
      layout = Layout::kVerticalStrip;
    }
    LoadResult result = EnvironmentFromImage(std::move(*read.image), layout, options.face_size);
    if (!result.ok()) {
      result.error = fmt::format("{}: {}", path.string(), result.error);
      return result;
    }
    for (std::string& warning : result.environment->warnings) {
      warning = fmt::format("{}: {}", path.string(), warning);
    }
    return result;
  } catch (const std::exception& e) {
    return Failure(fmt::format("{}: {}", path.string(), e.what()));
  }
}

std::optional<std::string> WriteImage(const Image& image, const std::filesystem::path& path) {
  return WriteAtomically(image, path, "");
}

std::optional<std::string> WriteCrossExr(const CubeMap& cube, const std::filesystem::path& path) {
  if (cube.face_size <= 0) return fmt::format("{}: cannot write an empty cube map", path.string());
  return WriteAtomically(CubeMapToImage(cube, Layout::kHorizontalCross), path, "openexr");
}

std::optional<std::string> WriteCubeMap(const CubeMap& cube, const std::filesystem::path& path,
                                        EnvironmentLayout layout) {
  if (cube.face_size <= 0) return fmt::format("{}: cannot write an empty cube map", path.string());
  const std::string pattern = path.string();
  const bool face_pattern = pattern.find(kFaceToken) != std::string::npos;
  if (layout == Layout::kAuto) layout = face_pattern ? Layout::kFaces : Layout::kHorizontalCross;
  if (layout != Layout::kFaces) return WriteAtomically(CubeMapToImage(cube, layout), path, "");
  if (!face_pattern) {
    return fmt::format("{}: writing six faces needs a path containing \"{}\"", pattern, kFaceToken);
  }
  try {
    std::vector<PendingRename> renames;
    for (CubeFace face : kAllCubeFaces) {
      const fs::path target = ReplaceToken(pattern, kFaceFileNames[static_cast<int>(face)]);
      std::string error;
      const std::optional<fs::path> temporary = WriteTemporary(cube.face(face), target, "", error);
      if (!temporary) {
        for (const PendingRename& written : renames) RemoveQuietly(written.temporary);
        return error;
      }
      renames.push_back({*temporary, target});
    }
    return CommitRenames(renames);
  } catch (const std::exception& e) {
    return fmt::format("{}: {}", pattern, e.what());
  }
}

bool IsPowerOfTwo(int n) { return n > 0 && std::has_single_bit(static_cast<unsigned>(n)); }

std::optional<std::string> CheckFaceSizeOption(std::string_view option, int face_size, int max_size) {
  if (IsPowerOfTwo(face_size) && face_size <= max_size) return std::nullopt;
  return fmt::format("{} {} must be a power of two from 1 to {} (the mip pyramid halves it down to 1x1)", option,
                     face_size, max_size);
}

std::optional<std::string> CheckPyramidFaceSize(std::string_view source, int face_size) {
  if (IsPowerOfTwo(face_size)) return std::nullopt;
  return fmt::format("{}face size {} is not a power of two; the mip pyramid needs exact 2x2 parents down to 1x1 "
                     "(resample the map, or give a lat-long map with --face-size)",
                     source.empty() ? std::string() : std::string(source) + ": ", face_size);
}

}  // namespace vs11::irradiance
