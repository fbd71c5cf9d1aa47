// The OpenImageIO module's entry point (image_io_module.h), and its writer and text drawing. Built
// with hidden visibility: the entry point is its only exported symbol.
// The system fmt goes first so that OpenImageIO's headers reuse it instead of their bundled copy.
#include <fmt/format.h>

#include <array>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "irradiance/io/image_io_module.h"
#include "irradiance/io/image_reader.h"
#include "irradiance/io/oiio/oiio_reader.h"

namespace vs11::irradiance {
namespace {

std::optional<std::string> WriteWithOiio(const OiioWriteRequest& request) {
  auto output = OIIO::ImageOutput::create(request.format);
  if (!output) return fmt::format("unsupported output format ({})", OiioMessage(OIIO::geterror()));
  const OIIO::TypeDesc type = request.as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(request.width, request.height, 3, type);
  spec.attribute("oiio:ColorSpace", request.as_float ? "Linear" : "sRGB");
  if (std::string_view(output->format_name()) == "openexr") spec.attribute("compression", "zip");
  if (!output->open(request.file.string(), spec)) {
    return fmt::format("cannot create file ({})", OiioMessage(output->geterror()));
  }
  const bool written = output->write_image(type, request.samples);
  const bool closed = output->close();
  if (!written || !closed) return fmt::format("write failed ({})", OiioMessage(output->geterror()));
  return std::nullopt;
}

std::optional<TextBox> TextSize(const std::string& text, int size, const std::string& font) {
  const OIIO::ROI box = OIIO::ImageBufAlgo::text_size(text, size, font);
  if (!box.defined()) return std::nullopt;
  return TextBox{box.xbegin, box.xend, box.ybegin, box.yend};
}

std::optional<std::string> RenderText(Image& image, int x, int y, const std::string& text, int size,
                                      const std::string& font, float value, bool centred) {
  // The image's own pixels, three floats each, drawn on in place.
  OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT),
                        image.pixels.data());
  const std::array<float, 3> colour = {value, value, value};
  const bool ok = OIIO::ImageBufAlgo::render_text(
      buffer, x, y, text, size, font, colour,
      centred ? OIIO::ImageBufAlgo::TextAlignX::Center : OIIO::ImageBufAlgo::TextAlignX::Left);
  if (!ok) return buffer.geterror();
  return std::nullopt;
}

constexpr ImageIoApi kApi = {ReadWithOiio, WriteWithOiio, TextSize, RenderText};

}  // namespace
}  // namespace vs11::irradiance

// The loader calls this once, before any thread reads an image. OpenImageIO catalogues its plugins on
// the first ImageInput::create, mutating its search-path string under its own lock while another
// thread's first create reads that string without it (ThreadSanitizer saw it in `irrmap batch`):
// asking for "extension_list" here catalogues them on this one thread first.
extern "C" __attribute__((visibility("default"))) const vs11::irradiance::ImageIoApi* vs11_image_io_api_v1() {
  static const bool catalogued = !OIIO::get_string_attribute("extension_list").empty();
  (void)catalogued;
  return &vs11::irradiance::kApi;
}
