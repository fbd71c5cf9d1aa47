#include "irradiance/io/ktx2_writer.h"

#include <array>
#include <cassert>

#include <fmt/format.h>

#include "irradiance/io/rgba16f_cube.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

// Values from the KTX 2.0 specification, the Khronos Data Format Specification (khr_df.h) and
// Vulkan's VkFormat.
constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                      0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kVkFormatR16G16B16A16Sfloat = 97;
constexpr std::uint32_t kTypeSize = 2;  // bytes of one component
constexpr std::uint32_t kCubeFaces = 6;
constexpr std::size_t kHeaderBytes = 48;     // identifier and nine UInt32
constexpr std::size_t kIndexBytes = 32;      // four UInt32 and two UInt64
constexpr std::size_t kLevelIndexBytes = 24;  // three UInt64 per level
constexpr std::size_t kDfdOffset = kHeaderBytes + kIndexBytes + kLevelIndexBytes;
constexpr int kSamples = 4;
constexpr std::uint32_t kBasicBlockBytes = 24 + 16 * kSamples;  // 6 words, then 4 per sample
constexpr std::uint32_t kDfdTotalBytes = 4 + kBasicBlockBytes;
constexpr std::uint32_t kDfVersion = 2;  // KHR_DF_VERSIONNUMBER_1_3
constexpr std::uint32_t kModelRgbsda = 1;
constexpr std::uint32_t kPrimariesBt709 = 1;
constexpr std::uint32_t kTransferLinear = 1;
constexpr std::uint32_t kFlagsAlphaStraight = 0;
constexpr std::uint32_t kQualifierFloatSigned = 0x80 | 0x40;  // KHR_DF_SAMPLE_DATATYPE_FLOAT | _SIGNED
constexpr std::array<std::uint32_t, kSamples> kChannelIds = {0, 1, 2, 15};  // R, G, B, alpha
constexpr std::uint32_t kBitsPerSample = 16;
constexpr std::uint32_t kMinusOneFloatBits = 0xBF800000;  // sampleLower of a signed float channel
constexpr std::uint32_t kOneFloatBits = 0x3F800000;       // sampleUpper
constexpr std::string_view kWriterKey = "KTXwriter";
constexpr std::size_t kLevelAlignment = 8;  // lcm(texel block size 8, 4)

// keyAndValueByteLength, the NUL-terminated key and value, and valuePadding.
std::vector<std::uint8_t> KeyValueData() {
  std::vector<std::uint8_t> data;
  LittleEndianBytes out(data);
  out.U32(static_cast<std::uint32_t>(kWriterKey.size() + 1 + kKtx2WriterName.size() + 1));
  for (std::string_view text : {kWriterKey, kKtx2WriterName}) {
    data.insert(data.end(), text.begin(), text.end());
    data.push_back(0);
  }
  out.ZerosUntilMultipleOf(4);
  return data;
}

void AppendDataFormatDescriptor(LittleEndianBytes& out) {
  out.U32(kDfdTotalBytes);
  out.U32(0);  // vendorId 0 (bits 0-16), descriptorType 0 (bits 17-31)
  out.U32(kDfVersion | (kBasicBlockBytes << 16));
  out.U32(kModelRgbsda | (kPrimariesBt709 << 8) | (kTransferLinear << 16) | (kFlagsAlphaStraight << 24));
  out.U32(0);  // texelBlockDimension0..3: 1x1x1x1 texel blocks
  out.U32(kRgba16fTexelBytes);  // bytesPlane0; bytesPlane1..3 0
  out.U32(0);                   // bytesPlane4..7
  for (int sample = 0; sample < kSamples; ++sample) {
    const std::uint32_t bit_offset = kBitsPerSample * static_cast<std::uint32_t>(sample);
    out.U32(bit_offset | ((kBitsPerSample - 1) << 16) | ((kQualifierFloatSigned | kChannelIds[sample]) << 24));
    out.U32(0);  // samplePosition0..3
    out.U32(kMinusOneFloatBits);
    out.U32(kOneFloatBits);
  }
}

}  // namespace

std::vector<std::uint8_t> EncodeKtx2CubeRgba16f(const CubeMap& cube) {
  assert(cube.face_size > 0);
  const std::uint32_t size = static_cast<std::uint32_t>(cube.face_size);
  const std::vector<std::uint8_t> texels = Rgba16fFaceBytes(cube);
  const std::vector<std::uint8_t> key_values = KeyValueData();
  const std::size_t kvd_offset = kDfdOffset + kDfdTotalBytes;
  std::size_t level_offset = kvd_offset + key_values.size();
  level_offset += (kLevelAlignment - level_offset % kLevelAlignment) % kLevelAlignment;

  std::vector<std::uint8_t> file;
  LittleEndianBytes out(file);
  out.Bytes(kIdentifier);
  for (std::uint32_t word : {kVkFormatR16G16B16A16Sfloat, kTypeSize, size, size, 0u, 0u, kCubeFaces, 1u, 0u}) {
    out.U32(word);  // vkFormat .. supercompressionScheme
  }
  out.U32(static_cast<std::uint32_t>(kDfdOffset));
  out.U32(kDfdTotalBytes);
  out.U32(static_cast<std::uint32_t>(kvd_offset));
  out.U32(static_cast<std::uint32_t>(key_values.size()));
  out.U64(0);  // sgdByteOffset
  out.U64(0);  // sgdByteLength
  out.U64(level_offset);
  out.U64(texels.size());  // byteLength
  out.U64(texels.size());  // uncompressedByteLength
  assert(out.size() == kDfdOffset);
  AppendDataFormatDescriptor(out);
  out.Bytes(key_values);
  out.ZerosUntilMultipleOf(kLevelAlignment);  // mipPadding
  assert(out.size() == level_offset);
  out.Bytes(texels);
  return file;
}

Status WriteKtx2Cube(const CubeMap& cube, const std::filesystem::path& path) {
  if (cube.face_size <= 0) {
    return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: cannot write an empty cube map", path.string()));
  }
  return WriteFileAtomically(path, EncodeKtx2CubeRgba16f(cube));
}

}  // namespace vs11::irradiance
