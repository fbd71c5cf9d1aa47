// The OpenImageIO module (libvs11_image_io.so): everything that calls OpenImageIO, in a shared
// module loaded on first use. OpenImageIO 2.4 brings about 260 shared libraries whose symbol
// resolution takes most of a short run's time (0.3-0.5 s); a tool or Python process that reads no
// image file OpenImageIO decodes (--help, the built-in environments, a DDS file of the formats
// dds_reader.h decodes) never loads it.
//
// Where the module is looked for, first found wins (ImageIoModuleCandidates):
//   1. beside the executable or shared object that holds this library's code (the installed Python
//      package keeps it beside _vs11.so);
//   2. <that folder>/../<libdir>/vs11/ (the tools: bin/irrmap finds lib/vs11/; in the build tree
//      build/irradiance/irrmap finds build/<libdir>/vs11/, where the module is built);
//   3. the build tree's module folder, while it exists (the Python module and the fuzzers there);
//   4. <prefix>/<libdir>/vs11/ as installed (any other program linking the installed libraries).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

inline constexpr const char* kImageIoModuleFileName = "libvs11_image_io.so";
// The module's one exported symbol: a function returning its ImageIoApi. The version is in the
// name, so that a module from a vs11 with another table is refused instead of misread.
inline constexpr const char* kImageIoEntryPoint = "vs11_image_io_api_v1";

// What the reader knows before OpenImageIO opens the file (image_reader.cc): its path and size, and
// for a DDS cube map whose faces dds_reader.h stacked into one image, those bytes (read in place of
// the file).
struct OiioReadRequest {
  std::filesystem::path path;
  std::optional<std::uintmax_t> file_size;
  const std::vector<unsigned char>* stacked_faces = nullptr;  // empty or null: read the file
  bool dds_cube_map = false;                                   // the DDS header says cube map
  std::function<std::optional<std::string>(int width, int height)> check_size;
};

// An image OpenImageIO read as linear RGB, or the error (without the file name, which the caller
// adds). The module's answers (this struct, and the optional messages of write and render_text
// below) stay plain values rather than vs11::Result: the module is dlopen'ed and links neither
// vs11's core library, where Result's out-of-line parts (Failure, the abort on reading a failed
// Result) are defined, nor anything else of vs11's. Each caller turns the answer into a Result with
// its DiagnosticCode as soon as the call returns (ReadImageFile: kCannotReadFile).
struct OiioReadResult {
  std::optional<Image> image;
  bool dds_cube_map = false;
  std::string error;
};

// 8-bit sRGB or linear float RGB samples, width x height x 3, to write with OpenImageIO.
struct OiioWriteRequest {
  std::string format;  // an OpenImageIO format name, or the destination's file name (its extension)
  std::filesystem::path file;  // the file created
  int width = 0;
  int height = 0;
  bool as_float = false;  // float samples tagged Linear, else 8-bit samples tagged sRGB
  const void* samples = nullptr;
};

// The pixel box a text takes, relative to its origin (OpenImageIO's text_size).
struct TextBox {
  int xbegin = 0;
  int xend = 0;
  int ybegin = 0;
  int yend = 0;
  int width() const { return xend - xbegin; }
};

struct ImageIoApi {
  OiioReadResult (*read)(const OiioReadRequest& request);
  // The error text ("unsupported output format (...)", "cannot create file (...)", "write failed
  // (...)") or nullopt; the file is left as OpenImageIO left it.
  std::optional<std::string> (*write)(const OiioWriteRequest& request);
  // nullopt when the font cannot measure the text.
  std::optional<TextBox> (*text_size)(const std::string& text, int size, const std::string& font);
  // Draws `text` in grey `value` at (x, y) (its baseline; centred on x or starting there); the error
  // text when it cannot.
  std::optional<std::string> (*render_text)(Image& image, int x, int y, const std::string& text, int size,
                                            const std::string& font, float value, bool centred);
};

// The module, loaded on the first call from any thread (later calls return the same); an error
// (kImageIoModule) when it cannot be loaded (a message naming the files looked for).
Result<const ImageIoApi*> ImageIo();

// Where ImageIo looks, in order (see the top of this file).
std::vector<std::filesystem::path> ImageIoModuleCandidates();

// Loads the first of `candidates` that exists (dlopen; never unloaded). Used by ImageIo; public so
// that tests can give other folders.
Result<const ImageIoApi*> LoadImageIoModule(const std::vector<std::filesystem::path>& candidates);

}  // namespace vs11::irradiance
