// vs11_decode_images: only decodes image files, for bench/irradiance/dataset_throughput.py's
// baseline (what labelling a file costs beyond reading it). The files one after another, with
// OpenImageIO's default threads (as irrmap batch and vs11.irradiance.batch run it):
//   --reader oiio  OpenImageIO alone: ImageInput::open and read_image as float RGB (the least any
//                  labeller pays);
//   --reader vs11  vs11's ReadImage (the file checks, OpenImageIO, the conversion to its RGB image),
//                  what irrmap batch does before it resamples.
// Prints one JSON line: {"reader", "files", "seconds", "pixels"}; exit 1 naming a file it cannot read.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "irradiance/io/environment_io.h"

namespace {

// The pixel count, or nullopt (and a message on stderr) when `path` cannot be read.
std::optional<std::size_t> DecodeWithOiio(const std::string& path) {
  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
  if (!input) {
    fmt::print(stderr, "vs11_decode_images: {}: {}\n", path, OIIO::geterror());
    return std::nullopt;
  }
  const OIIO::ImageSpec& spec = input->spec();
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * 3);
  if (!input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data())) {
    fmt::print(stderr, "vs11_decode_images: {}: {}\n", path, input->geterror());
    return std::nullopt;
  }
  return pixels.size() / 3;
}

std::optional<std::size_t> DecodeWithVs11(const std::string& path) {
  const vs11::Result<vs11::irradiance::ImageRead> read = vs11::irradiance::ReadImage(path);
  if (!read) {
    fmt::print(stderr, "vs11_decode_images: {}\n", read.message());
    return std::nullopt;
  }
  return read->image.pixels.size();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Decodes image files on one thread and prints how long it took, as JSON."};
  std::vector<std::string> files;
  std::string reader = "oiio";
  app.add_option("FILE", files, "image files")->required();
  app.add_option("--reader", reader, "oiio (OpenImageIO alone) or vs11 (irrmap's reader)")
      ->check(CLI::IsMember({"oiio", "vs11"}))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const auto start = std::chrono::steady_clock::now();
  std::size_t pixels = 0;
  for (const std::string& file : files) {
    const std::optional<std::size_t> count = reader == "oiio" ? DecodeWithOiio(file) : DecodeWithVs11(file);
    if (!count) return 1;
    pixels += *count;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("{{\"reader\": \"{}\", \"files\": {}, \"seconds\": {:.6f}, \"pixels\": {}}}\n", reader, files.size(),
             seconds, pixels);
  return 0;
}
