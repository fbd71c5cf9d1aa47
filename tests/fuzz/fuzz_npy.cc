// libFuzzer target: arbitrary bytes as a .npy file through mesh::ParseNpy and mesh::ParseNpyGrid (a
// vertex texture's reader), and as a raw interleaved
// buffer through mesh::ReadInterleaved (the first byte picks the stride, elements at 0 and 4).
#include <cstddef>
#include <cstdint>
#include <span>

#include "vm/mesh/npy.h"
#include "vm/mesh/vertex_buffer.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  vs11::Result<vs11::mesh::NpyArray> npy = vs11::mesh::ParseNpy(bytes, "fuzz.npy");
  if (npy.ok()) {
    // What parsed writes back and parses to the same values.
    vs11::Result<vs11::mesh::NpyArray> again = vs11::mesh::ParseNpy(vs11::mesh::FormatNpy(*npy), "again.npy");
    if (!again.ok() || again->rows != npy->rows || again->columns != npy->columns) __builtin_trap();
  }
  vs11::Result<vs11::mesh::NpyGrid> grid = vs11::mesh::ParseNpyGrid(bytes, "fuzz.npy");
  if (grid.ok()) {
    std::size_t count = 1;
    for (std::size_t dimension : grid->shape) count *= dimension;
    if (grid->values.size() != count) __builtin_trap();
  }
  if (size > 0) {
    const std::size_t stride = 1 + data[0] % 64;
    vs11::mesh::RegisterData registers;
    const std::vector<vs11::mesh::BufferElement> elements = {{0, 0, 1}, {1, 4, 3}};
    (void)vs11::mesh::ReadInterleaved(bytes.subspan(1), stride, elements, "fuzz.bin", registers);
  }
  return 0;
}
