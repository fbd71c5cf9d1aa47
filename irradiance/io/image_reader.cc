#include "irradiance/io/image_reader.h"

#include <fmt/format.h>

#include <cstdint>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "irradiance/io/dds_reader.h"
#include "irradiance/io/image_io_module.h"
#include "vm/core/input_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// The environment-map rules for a DDS file, beyond the container's own (dds_reader.h): a cube map
// has six square faces.
Status DdsEnvironmentProblem(const DdsFileHeader& header) {
  if (!header.is_cube_map) return {};
  if (header.width != header.height) {
    return Failure(DiagnosticCode::kCannotReadFile,
                   fmt::format("DDS cube map faces are {} x {} pixels: faces must be square", header.width,
                               header.height));
  }
  if (header.faces != kCubeFaceCount) {
    return Failure(DiagnosticCode::kCannotReadFile,
                   fmt::format("DDS cube map has {} of the six faces (cube map flags {:#x}), all six are needed",
                               header.faces, header.cube_face_flags));
  }
  return {};
}

// The file being read: its path and, when it could be found, its size.
struct ImageFile {
  fs::path path;
  std::optional<std::uintmax_t> size;
};

// Whether `path` names a non-empty regular file; fills `file`.
Status CheckIsFile(const fs::path& path, ImageFile& file) {
  file.path = path;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) return Failure(DiagnosticCode::kNoSuchInput, "file not found");
  // Images are read by seeking (OpenImageIO, DDS): a pipe is refused too, like a device or a folder.
  if (Status problem = InputFileProblem(path, /*pipes_allowed=*/false); !problem.ok()) return problem;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec) file.size = size;
  if (size == 0 && !ec) return Failure(DiagnosticCode::kCannotReadFile, "file is empty");
  return {};
}

// A DDS file, before OpenImageIO sees it: read here (`read`), or left to OpenImageIO, with a cube
// map's faces stacked into one plain image in memory (dds_reader.h); or refused (the error).
struct DdsStage {
  std::optional<Image> read;
  bool is_cube_map = false;
  std::vector<unsigned char> stacked_faces;
};

Result<DdsStage> ReadDdsStage(const fs::path& path) {
  DdsStage stage;
  const Result<std::optional<DdsFileHeader>> header = ReadDdsHeader(path, kMaxImagePixels);
  if (!header) return header.error();
  if (!header->has_value()) return stage;  // not a DDS file
  const DdsFileHeader& dds = **header;
  if (Status fits = DdsEnvironmentProblem(dds); !fits.ok()) return fits.error();
  stage.is_cube_map = dds.is_cube_map;
  Result<DdsPixels> pixels = ReadDdsPixels(path, dds);
  if (!pixels) return pixels.error();
  stage.read = std::move(pixels->image);
  stage.stacked_faces = std::move(pixels->stacked_faces);
  return stage;
}

}  // namespace

Result<ImageRead> ReadImageFile(const fs::path& path, const ImageSizeCheck& check_size) {
  const auto failure = [&](DiagnosticCode code, std::string_view message) {
    return Failure(code, fmt::format("{}: {}", path.string(), message));
  };
  ImageFile file;
  if (const Status checked = CheckIsFile(path, file); !checked.ok()) {
    return failure(checked.error().code, checked.message());
  }
  Result<DdsStage> staged = ReadDdsStage(path);
  if (!staged) return failure(staged.error().code, staged.message());
  DdsStage& dds = *staged;
  if (dds.read) return ImageRead{std::move(*dds.read), dds.is_cube_map};
  // Every other image is OpenImageIO's, loaded here on first use (image_io_module.h).
  const Result<const ImageIoApi*> module = ImageIo();
  if (!module) return failure(module.error().code, module.message());
  const ImageIoApi* image_io = *module;
  OiioReadRequest request{file.path, file.size, &dds.stacked_faces, dds.is_cube_map, check_size};
  OiioReadResult read = image_io->read(request);
  if (!read.image) return failure(DiagnosticCode::kCannotReadFile, read.error);
  return ImageRead{std::move(*read.image), read.dds_cube_map};
}

}  // namespace vs11::irradiance
