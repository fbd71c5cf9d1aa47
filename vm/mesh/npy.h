// NumPy .npy files of float32 vertex data: shape (N,) or (N, k) with k 1-4, little-endian (and
// ParseNpyGrid: any array of up to three dimensions, for vertex textures).
// The reader is strict: format versions 1.0-3.0, descr '<f4' only (what numpy writes for float32
// on every common machine), C or Fortran order, the data exactly N*k*4 bytes after the header.
// Anything else is an error naming the file and what is wrong; nothing is allocated for a shape
// the file's size cannot hold or beyond kMaxNpyRows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::mesh {

inline constexpr std::size_t kMaxNpyRows = std::size_t{1} << 26;  // as kMaxMeshVertices
inline constexpr std::size_t kMaxNpyHeaderBytes = 65536;

struct NpyArray {
  std::size_t rows = 0;
  int columns = 1;           // k; 1 for shape (N,)
  std::vector<float> values;  // row-major, rows * columns
  Vec4f Row(std::size_t row) const;  // missing components from kDefaultInput (0, 0, 0, 1)
};

// The array, or an error (kCannotReadFile) naming the file (`name`) and what is wrong.
Result<NpyArray> ParseNpy(std::span<const std::uint8_t> bytes, const std::string& name);
Result<NpyArray> ReadNpy(const std::filesystem::path& path);

// Any float32 array of one to three dimensions (a vertex texture: (H, W) or (H, W, 4)), in C order
// whatever the file's order; at most 4 * kMaxNpyRows values. ParseNpy is this plus the vertex rules.
struct NpyGrid {
  std::vector<std::size_t> shape;
  std::vector<float> values;
};
Result<NpyGrid> ParseNpyGrid(std::span<const std::uint8_t> bytes, const std::string& name);
Result<NpyGrid> ReadNpyGrid(const std::filesystem::path& path);

// Version 1.0, '<f4', C order, shape (rows, columns), header padded to 64 bytes.
std::vector<std::uint8_t> FormatNpy(const NpyArray& array);
// FormatNpy's bytes before the data, for a writer that streams the rows * columns floats after it.
std::string NpyHeader(std::size_t rows, int columns);

}  // namespace vs11::mesh
