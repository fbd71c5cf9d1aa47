#include "vm/core/vertex_texture.h"

#include <fmt/format.h>

namespace vs11 {

Result<VertexTexture> VertexTexture::Make(TextureFormat format, int width, int height, std::vector<float> texels) {
  if (width < 1 || height < 1) {
    return Failure(DiagnosticCode::kTexture, fmt::format("a texture of {} x {} texels: both sizes must be 1 or more", width, height));
  }
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (count > kMaxTextureTexels) {
    return Failure(DiagnosticCode::kTexture,
                   fmt::format("a texture of {} x {} texels: over the limit of {} texels", width, height, kMaxTextureTexels));
  }
  const std::size_t expected = count * static_cast<std::size_t>(ChannelCount(format));
  if (texels.size() != expected) {
    return Failure(DiagnosticCode::kTexture, fmt::format("a {} texture of {} x {} texels needs {} floats, not {}",
                                                         TextureFormatName(format), width, height, expected, texels.size()));
  }
  return VertexTexture{format, width, height, std::move(texels)};
}

TextureShape ShapeOf(const SamplerBinding& binding) {
  if (!binding.texture) return {};
  return {true, binding.texture->format, binding.texture->width, binding.texture->height, binding.state};
}

std::string TextureFormatName(TextureFormat format) {
  return format == TextureFormat::kR32F ? "R32F" : "A32B32G32R32F";
}

}  // namespace vs11
