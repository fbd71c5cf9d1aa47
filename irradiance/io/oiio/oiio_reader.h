// OpenImageIO's side of ReadImageFile, inside the OpenImageIO module (image_io_module.h).
#pragma once

#include "irradiance/io/image_io_module.h"

namespace vs11::irradiance {

// Opens request.path (or its stacked DDS faces), checks the header (size, request.check_size,
// truncation, compression ratio, a DDS cube map's faces) and reads the pixels as linear RGB.
OiioReadResult ReadWithOiio(const OiioReadRequest& request);

}  // namespace vs11::irradiance
