#include "irradiance/io/dds_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <Imath/half.h>

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// Layout facts of the DirectDraw Surface reference (DDS_HEADER, DDS_PIXELFORMAT,
// DDS_HEADER_DXT10); offsets count from the start of the file, magic included.
constexpr std::uint32_t kMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kHeaderSize = 124;
constexpr std::size_t kLegacyDataOffset = 4 + kHeaderSize;
constexpr std::size_t kDx10DataOffset = kLegacyDataOffset + 20;
constexpr std::size_t kFlagsAt = 8;
constexpr std::size_t kHeightAt = 12;
constexpr std::size_t kWidthAt = 16;
constexpr std::size_t kDepthAt = 24;
constexpr std::size_t kMipCountAt = 28;
constexpr std::size_t kPixelFormatFlagsAt = 80;
constexpr std::size_t kFourCcAt = 84;
constexpr std::size_t kBitCountAt = 88;
constexpr std::size_t kRedMaskAt = 92;
constexpr std::size_t kGreenMaskAt = 96;
constexpr std::size_t kBlueMaskAt = 100;
constexpr std::size_t kAlphaMaskAt = 104;
constexpr std::size_t kCaps2At = 112;
constexpr std::size_t kDxgiFormatAt = 128;
constexpr std::size_t kResourceDimensionAt = 132;
constexpr std::size_t kMiscFlagAt = 136;
constexpr std::size_t kArraySizeAt = 140;

constexpr std::uint32_t kFlagDepth = 0x800000;          // DDSD_DEPTH
constexpr std::uint32_t kPixelFormatAlphaPixels = 0x1;  // DDPF_ALPHAPIXELS
constexpr std::uint32_t kPixelFormatAlphaOnly = 0x2;    // DDPF_ALPHA
constexpr std::uint32_t kPixelFormatFourCc = 0x4;       // DDPF_FOURCC
constexpr std::uint32_t kPixelFormatRgb = 0x40;         // DDPF_RGB
constexpr std::uint32_t kPixelFormatLuminance = 0x20000;  // DDPF_LUMINANCE
constexpr std::uint32_t kCaps2Cubemap = 0x200;          // DDSCAPS2_CUBEMAP
constexpr std::uint32_t kCaps2AllFaces = 0xfc00;        // DDSCAPS2_CUBEMAP_POSITIVEX .. NEGATIVEZ
constexpr std::uint32_t kCaps2Volume = 0x200000;        // DDSCAPS2_VOLUME
constexpr std::uint32_t kMiscTextureCube = 0x4;         // D3D11_RESOURCE_MISC_TEXTURECUBE
constexpr std::uint32_t kDimensionTexture2D = 3;        // D3D10_RESOURCE_DIMENSION_TEXTURE2D

constexpr std::uint32_t FourCc(const char (&code)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(code[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[3])) << 24;
}

using Decoder = DdsDecoder;
using Format = DdsFormat;

struct DxgiFormat {
  std::uint32_t code;
  Format format;
};
// The DXGI formats whose size is known here (sizes from the DXGI_FORMAT reference); others are
// left to OpenImageIO unchecked.
constexpr std::array<DxgiFormat, 31> kDxgiFormats = {{
    {2, {"R32G32B32A32_FLOAT", 16, false, Decoder::kFloat32, 4}},
    {6, {"R32G32B32_FLOAT", 12, false, Decoder::kFloat32, 3}},
    {10, {"R16G16B16A16_FLOAT", 8, false, Decoder::kHalf, 4}},
    {26, {"R11G11B10_FLOAT", 4, false, Decoder::kR11G11B10, 3}},
    {67, {"R9G9B9E5_SHAREDEXP", 4, false, Decoder::kRgb9e5, 3}},
    {27, {"R8G8B8A8_TYPELESS", 4, false, Decoder::kOpenImageIo, 4}},
    {28, {"R8G8B8A8_UNORM", 4, false, Decoder::kOpenImageIo, 4}},
    {29, {"R8G8B8A8_UNORM_SRGB", 4, false, Decoder::kOpenImageIo, 4}},
    {87, {"B8G8R8A8_UNORM", 4, false, Decoder::kOpenImageIo, 4}},
    {88, {"B8G8R8X8_UNORM", 4, false, Decoder::kOpenImageIo, 4}},
    {91, {"B8G8R8A8_UNORM_SRGB", 4, false, Decoder::kOpenImageIo, 4}},
    {93, {"B8G8R8X8_UNORM_SRGB", 4, false, Decoder::kOpenImageIo, 4}},
    {70, {"BC1_TYPELESS", 8, true, Decoder::kOpenImageIo, 4}},
    {71, {"BC1_UNORM", 8, true, Decoder::kOpenImageIo, 4}},
    {72, {"BC1_UNORM_SRGB", 8, true, Decoder::kOpenImageIo, 4}},
    {73, {"BC2_TYPELESS", 16, true, Decoder::kOpenImageIo, 4}},
    {74, {"BC2_UNORM", 16, true, Decoder::kOpenImageIo, 4}},
    {75, {"BC2_UNORM_SRGB", 16, true, Decoder::kOpenImageIo, 4}},
    {76, {"BC3_TYPELESS", 16, true, Decoder::kOpenImageIo, 4}},
    {77, {"BC3_UNORM", 16, true, Decoder::kOpenImageIo, 4}},
    {78, {"BC3_UNORM_SRGB", 16, true, Decoder::kOpenImageIo, 4}},
    {79, {"BC4_TYPELESS", 8, true, Decoder::kOpenImageIo, 1}},
    {80, {"BC4_UNORM", 8, true, Decoder::kOpenImageIo, 1}},
    {81, {"BC4_SNORM", 8, true, Decoder::kOpenImageIo, 1}},
    {83, {"BC5_UNORM", 16, true, Decoder::kOpenImageIo, 2}},
    {84, {"BC5_SNORM", 16, true, Decoder::kOpenImageIo, 2}},
    {95, {"BC6H_UF16", 16, true, Decoder::kOpenImageIo, 3}},
    {96, {"BC6H_SF16", 16, true, Decoder::kOpenImageIo, 3}},
    {97, {"BC7_TYPELESS", 16, true, Decoder::kOpenImageIo, 4}},
    {98, {"BC7_UNORM", 16, true, Decoder::kOpenImageIo, 4}},
    {99, {"BC7_UNORM_SRGB", 16, true, Decoder::kOpenImageIo, 4}},
}};

struct FourCcFormat {
  std::uint32_t code;
  Format format;
};
constexpr std::array<FourCcFormat, 9> kFourCcFormats = {{
    {116, {"A32B32G32R32F", 16, false, Decoder::kFloat32, 4}},
    {113, {"A16B16G16R16F", 8, false, Decoder::kHalf, 4}},
    {FourCc("DXT1"), {"DXT1", 8, true, Decoder::kOpenImageIo, 4}},
    {FourCc("DXT3"), {"DXT3", 16, true, Decoder::kOpenImageIo, 4}},
    {FourCc("DXT5"), {"DXT5", 16, true, Decoder::kOpenImageIo, 4}},
    {FourCc("ATI1"), {"ATI1", 8, true, Decoder::kOpenImageIo, 1}},
    {FourCc("BC4U"), {"BC4U", 8, true, Decoder::kOpenImageIo, 1}},
    {FourCc("ATI2"), {"ATI2", 16, true, Decoder::kOpenImageIo, 2}},
    {FourCc("BC5U"), {"BC5U", 16, true, Decoder::kOpenImageIo, 2}},
}};

// The raw header: magic, DDS_HEADER and, if present, DDS_HEADER_DXT10.
using Header = std::array<unsigned char, kDx10DataOffset>;
static_assert(std::tuple_size_v<decltype(DdsFileHeader::raw)> == kDx10DataOffset);

std::uint32_t Word(const Header& header, std::size_t at) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = value << 8 | header[at + i];
  return value;
}

// What is wrong with a DDS file (its name left to the caller).
Diagnostic Error(std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); }

// What is wrong with an uncompressed pixel format given by a bit count and channel masks, if
// anything. OpenImageIO 2.4 never returns from a file whose bit count is 0 or whose masks in use
// include a 0 (it shifts the mask down until its lowest bit is set), so those are refused here.
Status MaskedFormatProblem(const Header& h) {
  const std::uint32_t flags = Word(h, kPixelFormatFlagsAt);
  const std::uint32_t bit_count = Word(h, kBitCountAt);
  if (bit_count != 8 && bit_count != 16 && bit_count != 24 && bit_count != 32) {
    return Error(fmt::format("unsupported DDS pixel format: {} bits per pixel (flags {:#x})", bit_count, flags));
  }
  std::vector<std::pair<std::size_t, std::string_view>> masks_in_use;
  if (flags & kPixelFormatLuminance) {
    masks_in_use.emplace_back(kRedMaskAt, "luminance");
  } else if ((flags & kPixelFormatAlphaOnly) && !(flags & kPixelFormatRgb)) {
    masks_in_use.emplace_back(kAlphaMaskAt, "alpha");
  } else {
    masks_in_use = {{kRedMaskAt, "red"}, {kGreenMaskAt, "green"}, {kBlueMaskAt, "blue"}};
  }
  if (flags & kPixelFormatAlphaPixels) masks_in_use.emplace_back(kAlphaMaskAt, "alpha");
  for (const auto& [at, channel] : masks_in_use) {
    if (Word(h, at) == 0) {
      return Error(
          fmt::format("corrupt DDS pixel format: the {} channel's bit mask is 0 (flags {:#x})", channel, flags));
    }
  }
  return {};
}

// Bytes of one mip level.
std::uint64_t LevelBytes(const Format& format, std::uint64_t width, std::uint64_t height) {
  if (format.block_compressed) return ((width + 3) / 4) * ((height + 3) / 4) * format.bytes;
  return width * height * format.bytes;
}

// An unsigned float of `mantissa_bits` with a 5-bit exponent (bias 15, as half), as half bits.
std::uint16_t SmallFloatToHalf(std::uint32_t bits, int mantissa_bits) {
  const std::uint32_t mantissa = bits & ((1u << mantissa_bits) - 1);
  const std::uint32_t exponent = (bits >> mantissa_bits) & 0x1f;
  return static_cast<std::uint16_t>(exponent << 10 | mantissa << (10 - mantissa_bits));
}

// Converts `count` pixels of `format` to linear RGB.
void DecodePixels(const Format& format, const unsigned char* data, std::size_t count,
                  glm::vec3* out) {
  switch (format.decoder) {
    case Decoder::kFloat32:
    case Decoder::kHalf: {
      std::vector<float> floats(count * format.channels);
      if (format.decoder == Decoder::kHalf) {
        for (std::size_t i = 0; i < floats.size(); ++i) {
          std::uint16_t bits;
          std::memcpy(&bits, data + 2 * i, 2);
          floats[i] = imath_half_to_float(bits);
        }
      } else {
        std::memcpy(floats.data(), data, floats.size() * sizeof(float));
      }
      for (std::size_t i = 0; i < count; ++i) {
        const float* p = &floats[i * format.channels];
        out[i] = glm::vec3(p[0], p[1], p[2]);
      }
      return;
    }
    case Decoder::kR11G11B10: {
      std::vector<std::uint16_t> halfs(count * 3);
      for (std::size_t i = 0; i < count; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, data + 4 * i, 4);
        halfs[3 * i] = SmallFloatToHalf(bits, 6);
        halfs[3 * i + 1] = SmallFloatToHalf(bits >> 11, 6);
        halfs[3 * i + 2] = SmallFloatToHalf(bits >> 22, 5);
      }
      std::vector<float> floats(count * 3);
      for (std::size_t i = 0; i < floats.size(); ++i) floats[i] = imath_half_to_float(halfs[i]);
      for (std::size_t i = 0; i < count; ++i) {
        out[i] = glm::vec3(floats[3 * i], floats[3 * i + 1], floats[3 * i + 2]);
      }
      return;
    }
    case Decoder::kRgb9e5: {
      // Three 9-bit mantissas without an implicit leading one, a shared 5-bit exponent, bias 15.
      for (std::size_t i = 0; i < count; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, data + 4 * i, 4);
        const int exponent = static_cast<int>(bits >> 27) - 15 - 9;
        for (int c = 0; c < 3; ++c) {
          out[i][c] = std::ldexp(static_cast<float>((bits >> (9 * c)) & 0x1ff), exponent);
        }
      }
      return;
    }
    case Decoder::kOpenImageIo:
      break;
  }
}

// BCn blocks cover 4 x 4 texels.
constexpr std::uint64_t kBlockSide = 4;
// OpenImageIO 2.4 refuses plain DDS images with a side above this.
constexpr std::uint64_t kMaxPlainImageSide = 32768;

// A DDS file holding level 0 of the six faces of the cube map in `file` as one plain image, the
// faces stacked top to bottom in file order (+x -x +y -y +z -z): the header with six times the
// height, one mip level and the cube map flags cleared, then each face's level 0 (they are `stride`
// bytes apart in `file`, `face_bytes` long). Faces stack into a valid image when whole block rows
// do, hence square faces a multiple of 4 texels high for block-compressed formats. Empty when the
// file cannot be read.
std::vector<unsigned char> StackedFacesFile(const Header& header, std::size_t data_offset, std::ifstream& file,
                                            std::uint64_t stride, std::uint64_t face_bytes) {
  std::vector<unsigned char> out(data_offset + 6 * face_bytes);
  std::memcpy(out.data(), header.data(), data_offset);
  const auto set_word = [&](std::size_t at, std::uint32_t value) {
    for (int i = 0; i < 4; ++i) out[at + i] = static_cast<unsigned char>(value >> (8 * i));
  };
  set_word(kHeightAt, 6 * Word(header, kHeightAt));
  set_word(kMipCountAt, 1);
  set_word(kCaps2At, Word(header, kCaps2At) & ~(kCaps2Cubemap | kCaps2AllFaces));
  if (data_offset == kDx10DataOffset) set_word(kMiscFlagAt, Word(header, kMiscFlagAt) & ~kMiscTextureCube);
  for (std::uint64_t face = 0; face < 6; ++face) {
    file.seekg(static_cast<std::streamoff>(data_offset + face * stride));
    file.read(reinterpret_cast<char*>(out.data() + data_offset + face * face_bytes),
              static_cast<std::streamsize>(face_bytes));
    if (!file) return {};
  }
  return out;
}

// The fields of a DX10 or legacy header that say what the file holds.
struct HeaderFacts {
  bool dx10 = false;
  bool dx10_cube = false;    // flagged in the DX10 misc flags
  bool legacy_cube = false;  // flagged in the legacy caps2
  std::uint32_t caps2 = 0;
  std::uint64_t array_size = 1;
  bool volume = false;
};

HeaderFacts ReadFacts(const Header& header, DdsFileHeader& out) {
  HeaderFacts facts;
  facts.dx10 = (Word(header, kPixelFormatFlagsAt) & kPixelFormatFourCc) != 0 &&
               Word(header, kFourCcAt) == FourCc("DX10");
  out.data_offset = facts.dx10 ? kDx10DataOffset : kLegacyDataOffset;
  out.width = Word(header, kWidthAt);
  out.height = Word(header, kHeightAt);
  facts.caps2 = Word(header, kCaps2At);
  // A DX10 header flags a cube map in its misc flags; writers set the legacy caps2 bits as well,
  // and OpenImageIO only looks at those.
  facts.dx10_cube = facts.dx10 && (Word(header, kMiscFlagAt) & kMiscTextureCube) != 0;
  facts.legacy_cube = (facts.caps2 & kCaps2Cubemap) != 0;
  out.is_cube_map = facts.dx10_cube || facts.legacy_cube;
  out.faces = !out.is_cube_map ? 1
              : facts.dx10_cube
                  ? 6
                  : static_cast<std::uint64_t>(std::popcount(facts.caps2 & kCaps2AllFaces));
  facts.array_size = facts.dx10 ? Word(header, kArraySizeAt) : 1;
  const bool has_depth = (Word(header, kFlagsAt) & kFlagDepth) != 0 && Word(header, kDepthAt) > 1;
  facts.volume = facts.dx10 ? Word(header, kResourceDimensionAt) != kDimensionTexture2D
                            : (facts.caps2 & kCaps2Volume) != 0 || has_depth;
  out.cube_face_flags = facts.caps2 & kCaps2AllFaces;
  out.volume_or_array = facts.volume || facts.array_size > 1;
  return facts;
}

// The pixel format, if its size is known here (nullopt: left to OpenImageIO unchecked), or the
// reason it is refused.
Result<std::optional<Format>> FindFormat(const Header& header, bool dx10) {
  std::optional<Format> format;
  if (dx10) {
    const std::uint32_t code = Word(header, kDxgiFormatAt);
    for (const DxgiFormat& entry : kDxgiFormats) {
      if (entry.code == code) format = entry.format;
    }
  } else if (Word(header, kPixelFormatFlagsAt) & kPixelFormatFourCc) {
    const std::uint32_t code = Word(header, kFourCcAt);
    if (code == FourCc("DXT2") || code == FourCc("DXT4")) {
      // OpenImageIO 2.4.7 undoes their premultiplied alpha by dividing by it, and a texel whose
      // alpha is 0 ends the process with SIGFPE. Nobody stores radiance premultiplied; DXT3 and
      // DXT5 hold the same blocks without the premultiplication.
      return Error(fmt::format(
          "premultiplied-alpha DDS ({}) is not read: store the environment as DXT3/DXT5 (BC2/BC3) "
          "or another format",
          code == FourCc("DXT2") ? "DXT2" : "DXT4"));
    }
    for (const FourCcFormat& entry : kFourCcFormats) {
      if (entry.code == code) format = entry.format;
    }
  } else {
    if (Status masks = MaskedFormatProblem(header); !masks) return masks.error();
    format = Format{"uncompressed", static_cast<int>(Word(header, kBitCountAt) / 8), false, Decoder::kOpenImageIo, 0};
  }
  return format;
}

// The checks on the image's size and mip chain, from the header alone.
Status SizeProblem(const DdsFileHeader& h, const HeaderFacts& facts, std::size_t max_pixels) {
  if (h.width == 0 || h.height == 0) {
    return Error(fmt::format("zero-size image ({} x {} pixels in the DDS header)", h.width, h.height));
  }
  if (h.width * h.height > max_pixels || h.width * h.height * h.faces > max_pixels) {
    return Error(fmt::format("image of {} x {} pixels ({} face(s)) is larger than the {} pixels accepted",
                             h.width, h.height, h.faces, max_pixels));
  }
  if (facts.array_size == 0) return Error("corrupt DDS header: DX10 array size 0");
  // DirectXTex's reading: a mip count of 0 means 1. More levels than down to 1 x 1 is corrupt.
  const auto full_chain = static_cast<std::uint64_t>(std::bit_width(std::max(h.width, h.height)));
  if (h.mip_count > full_chain) {
    return Error(fmt::format("corrupt DDS header: {} mip levels for a {} x {} image (at most {})",
                             h.mip_count, h.width, h.height, full_chain));
  }
  return {};
}

// Every face holds its whole mip chain; the last face's level 0 must be in the file.
Status TruncationProblem(DdsFileHeader& h, std::uint64_t file_size) {
  h.chain_bytes = 0;
  for (std::uint64_t level = 0; level < h.mip_count; ++level) {
    h.chain_bytes += LevelBytes(*h.format, std::max<std::uint64_t>(h.width >> level, 1),
                                std::max<std::uint64_t>(h.height >> level, 1));
  }
  h.level0_bytes = LevelBytes(*h.format, h.width, h.height);
  // A cube map flagging no face stores nothing; it is the caller's to refuse (as having 0 faces).
  const std::uint64_t faces = std::max<std::uint64_t>(h.faces, 1);
  const std::uint64_t needed = h.data_offset + (faces - 1) * h.chain_bytes + h.level0_bytes;
  if (file_size >= needed) return {};
  return Error(fmt::format(
      "truncated DDS file: {} bytes, but its header ({} x {} {}, {} face(s), {} mip level(s)) "
      "needs at least {}",
      file_size, h.width, h.height, h.format->name, h.faces, h.mip_count, needed));
}

// Reads the magic and the headers into `raw`: true when they are all there, false when the file is
// not a DDS file.
Result<bool> ReadRawHeader(std::ifstream& file, std::uintmax_t file_size, Header& raw) {
  file.read(reinterpret_cast<char*>(raw.data()), 4);
  if (!file || Word(raw, 0) != kMagic) return false;
  file.read(reinterpret_cast<char*>(raw.data()) + 4, kLegacyDataOffset - 4);
  if (!file) {
    return Error(fmt::format("truncated DDS file: {} bytes, shorter than its {}-byte header",
                                   file_size, kLegacyDataOffset));
  }
  if (Word(raw, 4) != kHeaderSize) {
    return Error(fmt::format("corrupt DDS header: header size {}, not {}", Word(raw, 4), kHeaderSize));
  }
  const bool dx10 = (Word(raw, kPixelFormatFlagsAt) & kPixelFormatFourCc) != 0 &&
                    Word(raw, kFourCcAt) == FourCc("DX10");
  if (dx10) {
    file.read(reinterpret_cast<char*>(raw.data()) + kLegacyDataOffset,
              kDx10DataOffset - kLegacyDataOffset);
    if (!file) {
      return Error(fmt::format(
          "truncated DDS file: {} bytes, shorter than its {}-byte header", file_size, kDx10DataOffset));
    }
  }
  return true;
}

// Level 0 of each face, decoded here.
Result<DdsPixels> DecodeFaces(const DdsFileHeader& header, std::ifstream& file) {
  const int w = static_cast<int>(header.width);
  const int h = static_cast<int>(header.height);
  DdsPixels result;
  Image& image = result.image.emplace(w, h * static_cast<int>(header.faces));
  std::vector<unsigned char> level0(header.level0_bytes);
  const std::size_t face_pixels = static_cast<std::size_t>(w) * h;
  for (std::uint64_t face = 0; face < header.faces; ++face) {
    file.seekg(static_cast<std::streamoff>(header.data_offset + face * header.chain_bytes));
    file.read(reinterpret_cast<char*>(level0.data()), static_cast<std::streamsize>(level0.size()));
    if (!file) return Error("cannot read the pixels: the file shrank or cannot be read");
    DecodePixels(*header.format, level0.data(), face_pixels, &image.pixels[face * face_pixels]);
  }
  return result;
}

}  // namespace

Result<std::optional<DdsFileHeader>> ReadDdsHeader(const fs::path& path, std::size_t max_pixels) {
  std::error_code ec;
  const std::uintmax_t file_size = fs::file_size(path, ec);
  if (ec) return Error(fmt::format("cannot read the file size ({})", ec.message()));
  std::ifstream file(path, std::ios::binary);
  Header raw{};
  const Result<bool> is_dds = ReadRawHeader(file, file_size, raw);
  if (!is_dds) return is_dds.error();
  if (!*is_dds) return std::optional<DdsFileHeader>();
  DdsFileHeader header;
  header.raw = raw;
  const HeaderFacts facts = ReadFacts(header.raw, header);
  header.mip_count = std::max<std::uint32_t>(Word(header.raw, kMipCountAt), 1);
  if (Status size = SizeProblem(header, facts, max_pixels); !size) return size.error();

  Result<std::optional<Format>> format = FindFormat(header.raw, facts.dx10);
  if (!format) return format.error();
  header.format = *format;
  const bool decode_here = header.format && header.format->decoder != Decoder::kOpenImageIo;
  // OpenImageIO reports on volumes and arrays of the formats it decodes.
  if (!header.format || (header.volume_or_array && !decode_here)) return header;
  if (facts.volume) return Error("a DDS volume texture is not an environment map");
  if (facts.array_size > 1) {
    return Error(fmt::format("DDS texture arrays ({} elements) are not read, only single "
                                   "images and single cube maps",
                                   facts.array_size));
  }
  if (Status complete = TruncationProblem(header, file_size); !complete) return complete.error();
  if (!decode_here && facts.dx10_cube &&
      (!facts.legacy_cube || (facts.caps2 & kCaps2AllFaces) != kCaps2AllFaces)) {
    return Error(fmt::format(
        "DX10 cube map without the DDSCAPS2 cube map flags (caps2 {:#x}): OpenImageIO, which "
        "decodes {}, would read one face only",
        facts.caps2, header.format->name));
  }
  return header;
}

Result<DdsPixels> ReadDdsPixels(const fs::path& path, const DdsFileHeader& header) {
  DdsPixels result;  // left to OpenImageIO
  if (!header.format || header.volume_or_array) return result;
  std::ifstream file(path, std::ios::binary);
  if (header.format->decoder != Decoder::kOpenImageIo) return DecodeFaces(header, file);
  const bool faces_stack = !header.format->block_compressed || header.width % kBlockSide == 0;
  if (header.is_cube_map && header.faces == 6 && faces_stack &&
      header.faces * header.height <= kMaxPlainImageSide) {
    result.stacked_faces = StackedFacesFile(header.raw, header.data_offset, file, header.chain_bytes,
                                            header.level0_bytes);
    if (result.stacked_faces.empty()) {
      return Error("cannot read the pixels: the file shrank or cannot be read");
    }
  }
  return result;
}

}  // namespace vs11::irradiance
