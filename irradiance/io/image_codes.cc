// The pure helpers of image I/O, compiled into both the irradiance library and the OpenImageIO
// module (image_io_module.h), which share no code at run time: the sRGB transfer function and its
// 8- and 16-bit tables, and the text helpers of the readers' messages. Declared in
// environment_io.h and image_reader.h.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/image_reader.h"

namespace vs11::irradiance {
namespace {

// IEC 61966-2-1 sRGB transfer function constants.
constexpr double kSrgbDecodeThreshold = 0.04045;
constexpr double kSrgbEncodeThreshold = 0.0031308;
constexpr double kSrgbLinearSlope = 12.92;
constexpr double kSrgbOffset = 0.055;
constexpr double kSrgbGamma = 2.4;

// The table of every `Code` value decoded from sRGB: the code converted to float as OpenImageIO's
// read_image converts it (times the reciprocal of the largest code, in float), then SrgbToLinear.
template <class Code>
std::vector<float> SrgbTable() {
  constexpr std::size_t kCodes = std::size_t{1} << (8 * sizeof(Code));
  constexpr float kScale = 1.0f / static_cast<float>(kCodes - 1);
  std::vector<float> table(kCodes);
  for (std::size_t i = 0; i < kCodes; ++i) {
    table[i] = static_cast<float>(SrgbToLinear(static_cast<float>(i) * kScale));
  }
  return table;
}

}  // namespace

double SrgbToLinear(double encoded) {
  if (encoded <= kSrgbDecodeThreshold) return encoded / kSrgbLinearSlope;
  return std::pow((encoded + kSrgbOffset) / (1.0 + kSrgbOffset), kSrgbGamma);
}

double LinearToSrgb(double linear) {
  if (linear <= kSrgbEncodeThreshold) return linear * kSrgbLinearSlope;
  return (1.0 + kSrgbOffset) * std::pow(linear, 1.0 / kSrgbGamma) - kSrgbOffset;
}

float SrgbByteToLinear(std::uint8_t code) {
  static const std::vector<float> table = SrgbTable<std::uint8_t>();
  return table[code];
}

float SrgbWordToLinear(std::uint16_t code) {
  // 65536 std::pow once (a few milliseconds), against one per channel of every 16-bit texel.
  static const std::vector<float> table = SrgbTable<std::uint16_t>();
  return table[code];
}

std::string OiioMessage(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  return message.empty() ? std::string("no details from OpenImageIO") : message;
}

std::string AsciiLower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace vs11::irradiance
