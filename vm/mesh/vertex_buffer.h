// Raw interleaved float32 vertex buffers, described as D3D describes one: a stride in bytes and,
// for each element, its register, byte offset and float count:
//   --buffer verts.bin --stride 32 --element v0=0:3 --element v3=12:3
// Little-endian floats, no header. The file must hold a whole number of vertices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/result.h"
#include "vm/mesh/vertex_binding.h"

namespace vs11::mesh {

inline constexpr std::size_t kMaxBufferStride = 4096;

struct BufferElement {
  int reg = 0;              // v#
  std::size_t offset = 0;   // bytes from the start of the vertex
  int components = 4;       // 1-4 floats; the rest read from kDefaultInput (0, 0, 0, 1)
};

// "v3=12:3" -> {3, 12, 3}; an error (kBufferElement) naming the flag otherwise.
Status ParseBufferElement(std::string_view text, BufferElement& element);

// Whether the layout is one a buffer can have, whatever its bytes: a stride of 1 to
// kMaxBufferStride, at least one element, each of 1 to 4 floats ending within the stride (the
// end computed without wrapping around), no register twice. The error (kBufferLayout) names the flag
// at fault.
Status CheckBufferLayout(std::size_t stride, const std::vector<BufferElement>& elements);

// Reads every element of every vertex into `registers` (appended, one entry per element), after
// CheckBufferLayout; no read leaves `bytes`. An error (kBufferSize) for bytes that are not whole
// vertices or none.
Status ReadInterleaved(std::span<const std::uint8_t> bytes, std::size_t stride,
                       const std::vector<BufferElement>& elements, const std::string& name, RegisterData& registers);

}  // namespace vs11::mesh
