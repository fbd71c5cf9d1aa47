// One image file read as linear RGB, the way environment_io.h describes (ReadImage, and the
// loaders): the file's checks (missing, empty, truncated, oversized, compressed beyond what its
// format reaches), DDS files through dds_reader.h first, everything else through OpenImageIO,
// sRGB decoded from integer data.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "irradiance/io/environment_io.h"

namespace vs11::irradiance {

// A rule on the image's size, checked on the header before any pixel is allocated: nullopt when
// width x height is acceptable, else the message.
using ImageSizeCheck = std::function<std::optional<std::string>(int width, int height)>;

// Reads `path`. `check_size` (when set) applies to every image but a DDS cube map, which is always
// read as a vertical strip of six square faces. Errors name the file: kNoSuchInput for a missing
// one, kImageIoModule when OpenImageIO cannot be loaded, kCannotReadFile for the rest.
Result<ImageRead> ReadImageFile(const std::filesystem::path& path, const ImageSizeCheck& check_size);

// sRGB-encoded 8- and 16-bit code values to linear: the bits of
// float(SrgbToLinear(v)) for v the code as OpenImageIO converts it to float (code / 255 or
// code / 65535), from tables built once instead of a std::pow per channel of every texel.
float SrgbByteToLinear(std::uint8_t code);
float SrgbWordToLinear(std::uint16_t code);

// OpenImageIO's error text without trailing newlines and blanks, or a note that it gave none.
std::string OiioMessage(std::string message);
// `text` with ASCII letters in lower case (extensions and OpenImageIO's format names).
std::string AsciiLower(std::string text);

}  // namespace vs11::irradiance
