// libFuzzer target: `vs11 run --buffer`'s layout flags and the buffer they describe. The input is
// one line, "STRIDE ELEMENT..." (each ELEMENT as --element takes it, "v3=12:3"), then the buffer's
// bytes. Whatever parses and reads must have read each float from inside the buffer, at
// vertex * stride + offset; ASan reports any read outside it.
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vm/core/checked_arithmetic.h"
#include "vm/mesh/vertex_buffer.h"

namespace {

// The buffer's bytes at `at`, or a trap where they lie outside it.
float FloatAt(std::span<const std::uint8_t> bytes, std::optional<std::size_t> at) {
  if (!at || *at > bytes.size() || bytes.size() - *at < sizeof(float)) __builtin_trap();
  float value;
  std::memcpy(&value, bytes.data() + *at, sizeof value);
  return value;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t newline = input.find('\n');
  if (newline == std::string_view::npos) return 0;
  std::string_view line = input.substr(0, newline);
  const std::span<const std::uint8_t> bytes(data + newline + 1, size - newline - 1);

  std::size_t stride = 0;
  const std::size_t space = std::min(line.find(' '), line.size());
  auto [end, error] = std::from_chars(line.data(), line.data() + space, stride);
  if (error != std::errc() || end != line.data() + space) return 0;
  line.remove_prefix(space);
  std::vector<vs11::mesh::BufferElement> elements;
  while (!line.empty()) {
    line.remove_prefix(1);
    const std::string_view text = line.substr(0, std::min(line.find(' '), line.size()));
    line.remove_prefix(text.size());
    vs11::mesh::BufferElement element;
    if (!vs11::mesh::ParseBufferElement(text, element).ok()) return 0;
    elements.push_back(element);
  }
  vs11::mesh::RegisterData registers;
  if (!vs11::mesh::ReadInterleaved(bytes, stride, elements, "fuzz.bin", registers).ok()) return 0;
  if (registers.size() != elements.size()) __builtin_trap();
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const vs11::mesh::BufferElement& e = elements[i];
    for (std::size_t v = 0; v < registers[i].second.size(); ++v) {
      for (int c = 0; c < e.components; ++c) {
        const std::optional<std::size_t> vertex = vs11::CheckedEnd<std::size_t>(e.offset, v, stride);
        const std::optional<std::size_t> at =
            vertex ? vs11::CheckedEnd<std::size_t>(*vertex, c, sizeof(float)) : std::nullopt;
        const float expected = FloatAt(bytes, at);
        if (std::memcmp(&expected, &registers[i].second[v][c], sizeof expected) != 0) __builtin_trap();
      }
    }
  }
  return 0;
}
