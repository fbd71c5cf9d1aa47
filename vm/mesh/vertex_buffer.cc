#include "vm/mesh/vertex_buffer.h"

#include <charconv>
#include <cstring>

#include <fmt/format.h>

#include "vm/core/checked_arithmetic.h"
#include "vm/core/register_names.h"

namespace vs11::mesh {
namespace {

template <typename T>
bool ParseNumber(std::string_view text, T& value) {
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace

Status ParseBufferElement(std::string_view text, BufferElement& element) {
  const std::size_t equals = text.find('=');
  const std::size_t colon = text.find(':', equals == std::string_view::npos ? 0 : equals);
  if (equals == std::string_view::npos || colon == std::string_view::npos) {
    return Failure(DiagnosticCode::kBufferElement,
                   fmt::format("--element '{}': expected v#=OFFSET:COUNT, e.g. v3=12:3", text));
  }
  std::optional<int> reg = ParseInputRegister(text.substr(0, equals));
  if (!reg) {
    return Failure(DiagnosticCode::kBufferElement,
                   fmt::format("--element '{}': '{}' is not an input register v0-v15", text, text.substr(0, equals)));
  }
  element.reg = *reg;
  if (!ParseNumber(text.substr(equals + 1, colon - equals - 1), element.offset)) {
    return Failure(DiagnosticCode::kBufferElement, fmt::format("--element '{}': the offset is not a byte count", text));
  }
  if (!ParseNumber(text.substr(colon + 1), element.components) || element.components < 1 || element.components > 4) {
    return Failure(DiagnosticCode::kBufferElement,
                   fmt::format("--element '{}': the count must be 1 to 4 floats", text));
  }
  return {};
}

Status CheckBufferLayout(std::size_t stride, const std::vector<BufferElement>& elements) {
  if (stride == 0 || stride > kMaxBufferStride) {
    return Failure(DiagnosticCode::kBufferLayout,
                   fmt::format("--stride {}: must be 1 to {} bytes", stride, kMaxBufferStride));
  }
  if (elements.empty()) {
    return Failure(DiagnosticCode::kBufferLayout, "--buffer needs at least one --element v#=OFFSET:COUNT");
  }
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const BufferElement& e = elements[i];
    if (e.reg < 0 || e.reg >= kInputRegisterCount) {
      return Failure(DiagnosticCode::kBufferLayout, fmt::format("--element v{}: not an input register v0-v15", e.reg));
    }
    if (e.components < 1 || e.components > 4) {
      return Failure(DiagnosticCode::kBufferLayout, fmt::format("--element v{}={}:{}: the count must be 1 to 4 floats",
                                                                e.reg, e.offset, e.components));
    }
    const std::optional<std::size_t> end = CheckedEnd<std::size_t>(e.offset, e.components, sizeof(float));
    if (!end || *end > stride) {
      return Failure(DiagnosticCode::kBufferLayout,
                     fmt::format("--element v{}={}:{} ends past the {}-byte stride (at byte {})", e.reg, e.offset,
                                 e.components, stride, end ? fmt::format("{}", *end) : std::string("2^64 or more")));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (elements[j].reg == e.reg) {
        return Failure(DiagnosticCode::kBufferLayout,
                       fmt::format("--element v{} is given twice: give each register once", e.reg));
      }
    }
  }
  return {};
}

Status ReadInterleaved(std::span<const std::uint8_t> bytes, std::size_t stride,
                       const std::vector<BufferElement>& elements, const std::string& name, RegisterData& registers) {
  if (Status layout = CheckBufferLayout(stride, elements); !layout) return layout;
  if (bytes.size() % stride != 0) {
    return Failure(DiagnosticCode::kBufferSize,
                   fmt::format("{}: {} bytes is not a whole number of {}-byte vertices", name, bytes.size(), stride));
  }
  const std::size_t count = bytes.size() / stride;
  if (count == 0) return Failure(DiagnosticCode::kBufferSize, fmt::format("{}: the buffer is empty", name));
  for (const BufferElement& e : elements) {
    std::vector<Vec4f> values(count, kDefaultInput);
    for (std::size_t v = 0; v < count; ++v) {
      std::memcpy(values[v].data(), bytes.data() + v * stride + e.offset, 4 * static_cast<std::size_t>(e.components));
    }
    std::erase_if(registers, [&](const auto& entry) { return entry.first == e.reg; });
    registers.emplace_back(e.reg, std::move(values));
  }
  return {};
}

}  // namespace vs11::mesh
