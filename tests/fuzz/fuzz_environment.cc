// libFuzzer target: arbitrary bytes as an environment-map file through irradiance::LoadEnvironment
// (OpenImageIO reads it). The bytes go to a temporary file, since the loader takes a path; its
// neutral extension makes OpenImageIO try every reader it has.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "irradiance/io/environment_io.h"

namespace {

const std::filesystem::path& ScratchFile() {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("vs11_fuzz_environment_" + std::to_string(getpid()) + ".img");
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(ScratchFile(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  vs11::irradiance::LoadOptions options;
  options.face_size = 4;  // lat-long and angular maps resample to a tiny cube: the reading is what is fuzzed
  const vs11::Result<vs11::irradiance::LoadedEnvironment> result =
      vs11::irradiance::LoadEnvironment(ScratchFile(), options);
  (void)result;
  return 0;
}
