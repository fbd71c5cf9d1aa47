// OpenImageIO's side of ReadImageFile (image_reader.cc): opening the file (or a DDS cube map's
// stacked faces in memory), the checks on its header before any pixel is allocated, and the pixels
// as linear RGB. Compiled into the OpenImageIO module only (image_io_module.h).
#include "irradiance/io/oiio/oiio_reader.h"

// The system fmt goes first so that OpenImageIO's headers reuse it instead of their bundled copy.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string_view>
#include <utility>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/image_reader.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// What the DDS reader reports for a cube map with every face.
constexpr std::string_view kCubeTextureFormat = "CubeFace Environment";
constexpr std::string_view kAllDdsCubeSides = "+x -x +y -y +z -z";

// Held while OpenImageIO reads the pixels of a DDS cube map (see ReadPixels): one per process,
// because the state it protects is OpenImageIO's, which is one per process.
std::mutex& DdsCubeReadMutex() {
  static std::mutex mutex;
  return mutex;
}

bool IsFloatType(OIIO::TypeDesc type) {
  return type.basetype == OIIO::TypeDesc::FLOAT || type.basetype == OIIO::TypeDesc::HALF ||
         type.basetype == OIIO::TypeDesc::DOUBLE;
}

// Whether OpenImageIO has a reader for the extension of `path` ("extension_list" is
// "openexr:exr,sxr,mxr;tiff:tif,tiff,...").
bool IsKnownImageExtension(const fs::path& path) {
  std::string extension = AsciiLower(path.extension().string());
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
  const std::string format = AsciiLower(input.format_name());
  const bool pfm = format == "pnm" && spec.format == OIIO::TypeDesc::FLOAT;
  constexpr int kPhotometricPalette = 3;
  const bool raw_tiff =
      format == "tiff" &&
      AsciiLower(std::string(spec.get_string_attribute("compression", "none"))) == "none" &&
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
  const std::string format = AsciiLower(input.format_name());
  const std::string compression = AsciiLower(std::string(spec.get_string_attribute("compression", "")));
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

// An OpenImageIO reader, and the memory it reads in place of the file, which must outlive it.
struct OpenedImage {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> input;
  OIIO::ImageSpec spec;
  bool read_by_faces = false;  // a DDS cube map OpenImageIO serves face by face
  bool dds_cube_map = false;   // read_by_faces, or stacked faces read as one image
};

std::optional<std::string> OpenImage(const OiioReadRequest& file, OpenedImage& opened) {
  OIIO::ImageSpec open_config;
  if (file.stacked_faces && !file.stacked_faces->empty()) {
    opened.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(
        const_cast<unsigned char*>(file.stacked_faces->data()), file.stacked_faces->size());
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
      AsciiLower(opened.input->format_name()) == "dds" &&
      std::string(opened.spec.get_string_attribute("textureformat")) == kCubeTextureFormat;
  opened.dds_cube_map = opened.read_by_faces || (opened.memory && file.dds_cube_map);
  return std::nullopt;
}

// The checks on OpenImageIO's header before any pixel is read: the size, the caller's `check_size`
// (when set), truncation and the compression ratio, a DDS cube map's faces.
std::optional<std::string> CheckOpenedHeader(const OiioReadRequest& file, const OpenedImage& opened) {
  const ImageSizeCheck& check_size = file.check_size;
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
  if (check_size && !opened.dds_cube_map) {
    if (std::optional<std::string> error = check_size(spec.width, spec.height)) {
      return error;
    }
  }
  const std::optional<std::uint64_t> needed = UncompressedPixelBytes(*opened.input, spec);
  if (needed && file.file_size && *file.file_size < *needed) {
    return fmt::format(
        "truncated file: {} bytes, but the {} x {} uncompressed pixels its header declares take {}",
        *file.file_size, spec.width, spec.height, *needed);
  }
  if (file.file_size && !needed) {
    if (std::optional<std::string> error = CheckCompressionRatio(*opened.input, spec, *file.file_size)) {
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

// Reads the first `channels` channels of every pixel, converted to `type`, into `data`.
std::optional<std::string> ReadPixels(OpenedImage& opened, int channels, OIIO::TypeDesc type,
                                      void* data) {
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
  if (!opened.input->read_image(0, 0, 0, channels, type, data) || opened.input->has_error()) {
    return fmt::format("cannot read pixels, corrupt or truncated file ({})",
                       OiioMessage(opened.input->geterror()));
  }
  opened.input->close();
  return std::nullopt;
}

// The pixels as RGB, each channel through `decode`; one- and two-channel images replicate their
// first channel.
template <class Sample, class Decode>
Image ToRgb(const OIIO::ImageSpec& spec, int channels, const std::vector<Sample>& data,
            Decode decode) {
  Image image(spec.width, spec.height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) rgb[c] = decode(data[i * channels + (channels == 3 ? c : 0)]);
    image.pixels[i] = rgb;
  }
  return image;
}

template <class Sample, class Decode>
std::optional<std::string> ReadAndDecode(OpenedImage& opened, int channels, OIIO::TypeDesc type,
                                         Decode decode, Image& image) {
  std::vector<Sample> data(static_cast<std::size_t>(opened.spec.width) * opened.spec.height *
                           channels);
  if (std::optional<std::string> error = ReadPixels(opened, channels, type, data.data())) {
    return error;
  }
  image = ToRgb(opened.spec, channels, data, decode);
  return std::nullopt;
}

// Reads the pixels as linear RGB. Integer data holds sRGB-encoded values unless the reader says it
// is linear; 8- and 16-bit codes (every channel of one type) are read as they are and decoded by
// table, other integer types as float through SrgbToLinear.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "rows of pixels are read as interleaved floats");

std::optional<std::string> ReadLinearRgb(OpenedImage& opened, Image& image) {
  const OIIO::ImageSpec& spec = opened.spec;
  const int channels = std::min(spec.nchannels, 3);
  const bool decode_srgb =
      !IsFloatType(spec.format) &&
      AsciiLower(std::string(spec.get_string_attribute("oiio:ColorSpace"))) != "linear";
  const auto as_float = [](float value) { return value; };
  if (!decode_srgb && channels == 3) {
    // RGB floats are the layout of Image's pixels: read straight into them, without a second
    // buffer of the whole image and a copy (150 MB for a cross of 1024 faces).
    Image read(spec.width, spec.height);
    if (std::optional<std::string> error = ReadPixels(opened, 3, OIIO::TypeDesc::FLOAT, read.pixels.data())) {
      return error;
    }
    image = std::move(read);
    return std::nullopt;
  }
  if (!decode_srgb) {
    return ReadAndDecode<float>(opened, channels, OIIO::TypeDesc::FLOAT, as_float, image);
  }
  const bool one_type = spec.channelformats.empty();
  if (one_type && spec.format == OIIO::TypeDesc::UINT8) {
    return ReadAndDecode<std::uint8_t>(opened, channels, OIIO::TypeDesc::UINT8, SrgbByteToLinear,
                                       image);
  }
  if (one_type && spec.format == OIIO::TypeDesc::UINT16) {
    return ReadAndDecode<std::uint16_t>(opened, channels, OIIO::TypeDesc::UINT16, SrgbWordToLinear,
                                        image);
  }
  const auto srgb = [](float value) { return static_cast<float>(SrgbToLinear(value)); };
  return ReadAndDecode<float>(opened, channels, OIIO::TypeDesc::FLOAT, srgb, image);
}

}  // namespace

OiioReadResult ReadWithOiio(const OiioReadRequest& request) {
  OiioReadResult result;
  OpenedImage opened;
  if (std::optional<std::string> error = OpenImage(request, opened)) {
    result.error = std::move(*error);
    return result;
  }
  if (std::optional<std::string> error = CheckOpenedHeader(request, opened)) {
    result.error = std::move(*error);
    return result;
  }
  Image image;
  if (std::optional<std::string> error = ReadLinearRgb(opened, image)) {
    result.error = std::move(*error);
    return result;
  }
  result.dds_cube_map = opened.dds_cube_map;
  result.image = std::move(image);
  return result;
}

}  // namespace vs11::irradiance
