#include "vm/mesh/npy.h"

#include <bit>
#include <charconv>
#include <cstring>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "vm/asm/program_file.h"
#include "vm/core/input_file.h"

namespace vs11::mesh {
namespace {

static_assert(std::endian::native == std::endian::little, "the .npy reader and writer assume a little-endian host");

constexpr char kMagic[] = "\x93NUMPY";
constexpr std::size_t kMagicSize = 6;

// What is wrong with a file that is no .npy array of vertices vs11 reads.
Diagnostic Malformed(std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); }

// A cursor over the header's Python dict literal: {'descr': '<f4', 'fortran_order': False, 'shape': (3, 4), }
class HeaderParser {
 public:
  explicit HeaderParser(std::string_view text) : text_(text) {}

  Status Parse(std::string& descr, bool& fortran_order, std::vector<std::size_t>& shape) {
    bool seen_descr = false, seen_order = false, seen_shape = false;
    if (!Take('{')) return Malformed("the header is not a dict");
    while (true) {
      SkipSpace();
      if (Take('}')) break;
      std::optional<std::string> key = String();
      if (!key) return Malformed("expected a quoted key in the header");
      if (!Take(':')) return Malformed(fmt::format("expected ':' after '{}'", *key));
      if (*key == "descr") {
        std::optional<std::string> value = String();
        if (!value) return Malformed("'descr' is not a string");
        descr = *value;
        seen_descr = true;
      } else if (*key == "fortran_order") {
        SkipSpace();
        if (Word("True")) fortran_order = true;
        else if (Word("False")) fortran_order = false;
        else return Malformed("'fortran_order' is neither True nor False");
        seen_order = true;
      } else if (*key == "shape") {
        if (Status parsed = Tuple(shape); !parsed) return parsed;
        seen_shape = true;
      } else {
        return Malformed(fmt::format("unknown header key '{}'", *key));
      }
      SkipSpace();
      if (Take(',')) continue;
      if (Take('}')) break;
      return Malformed("expected ',' or '}' in the header");
    }
    SkipSpace();
    if (pos_ != text_.size()) return Malformed("text after the header's dict");
    if (!seen_descr || !seen_order || !seen_shape) return Malformed("the header lacks descr, fortran_order or shape");
    return {};
  }

 private:
  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n' || text_[pos_] == '\t')) ++pos_;
  }
  bool Take(char c) {
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool Word(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }
  std::optional<std::string> String() {
    SkipSpace();
    if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) return std::nullopt;
    const char quote = text_[pos_++];
    const std::size_t end = text_.find(quote, pos_);
    if (end == std::string_view::npos) return std::nullopt;
    std::string value(text_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return value;
  }
  Status Tuple(std::vector<std::size_t>& shape) {
    shape.clear();
    if (!Take('(')) return Malformed("'shape' is not a tuple");
    while (true) {
      SkipSpace();
      if (Take(')')) return {};
      std::size_t value = 0;
      auto [ptr, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), value);
      if (ec != std::errc()) return Malformed("'shape' holds something other than a non-negative integer");
      pos_ = static_cast<std::size_t>(ptr - text_.data());
      shape.push_back(value);
      if (shape.size() > 3) return Malformed("'shape' has more than three dimensions");
      if (Take(',')) continue;
      if (Take(')')) return {};
      return Malformed("expected ',' or ')' in 'shape'");
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

// "(3, 4)", "(5,)": as NumPy prints a shape.
std::string ShapeText(const std::vector<std::size_t>& shape) {
  if (shape.size() == 1) return fmt::format("({},)", shape[0]);
  return fmt::format("({})", fmt::join(shape, ", "));
}

std::uint32_t ReadLittle(const std::uint8_t* p, int bytes) {
  std::uint32_t value = 0;
  for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | p[i];
  return value;
}

}  // namespace

Vec4f NpyArray::Row(std::size_t row) const {
  Vec4f out = kDefaultInput;
  for (int c = 0; c < columns; ++c) out[c] = values[row * static_cast<std::size_t>(columns) + c];
  return out;
}

namespace {

// The limits of ParseNpyGrid: every dimension and their product at most kMaxGridValues.
constexpr std::size_t kMaxGridValues = kMaxNpyRows * 4;
Status GridShapeProblem(const std::vector<std::size_t>& shape) {
  std::size_t count = 1;
  for (std::size_t size : shape) {
    if (size > kMaxGridValues) return Malformed(fmt::format("shape {}: a dimension over the limit of {}", ShapeText(shape), kMaxGridValues));
    count *= size;  // both factors at most 2^28: no overflow
    if (count > kMaxGridValues) return Malformed(fmt::format("shape {}: over the limit of {} values", ShapeText(shape), kMaxGridValues));
  }
  return {};
}

// An array of vertices: (N,) or (N, k), k 1-4, N at most kMaxNpyRows.
Status VertexShapeProblem(const std::vector<std::size_t>& shape) {
  if (shape.size() > 2) return Malformed(fmt::format("shape {} has more than two dimensions (an array of vertices has one or two)", ShapeText(shape)));
  const std::size_t rows = shape[0];
  const std::size_t columns = shape.size() == 2 ? shape[1] : 1;
  if (columns < 1 || columns > 4) return Malformed(fmt::format("shape ({}, {}): each row needs 1 to 4 values", rows, columns));
  if (rows > kMaxNpyRows) return Malformed(fmt::format("{} rows, over the limit of {}", rows, kMaxNpyRows));
  return {};
}

// The array, once `shape_problem` accepts its shape (before anything is allocated for it).
Result<NpyGrid> ParseNpyChecked(std::span<const std::uint8_t> bytes, const std::string& name,
                                Status (*shape_problem)(const std::vector<std::size_t>&)) {
  auto fail = [&](const std::string& message) { return Malformed(fmt::format("{}: {}", name, message)); };
  if (bytes.size() < kMagicSize + 4 || std::memcmp(bytes.data(), kMagic, kMagicSize) != 0) {
    return fail("not a .npy file (no \\x93NUMPY magic)");
  }
  const int major = bytes[6];
  if (major < 1 || major > 3) return fail(fmt::format("unsupported .npy format version {}.{}", major, bytes[7]));
  const int length_bytes = major == 1 ? 2 : 4;
  const std::size_t prefix = kMagicSize + 2 + static_cast<std::size_t>(length_bytes);
  if (bytes.size() < prefix) return fail("truncated header");
  const std::size_t header_length = ReadLittle(bytes.data() + 8, length_bytes);
  if (header_length > kMaxNpyHeaderBytes || header_length > bytes.size() - prefix) return fail("truncated or oversized header");
  const std::string_view header(reinterpret_cast<const char*>(bytes.data() + prefix), header_length);
  std::string descr;
  bool fortran_order = false;
  NpyGrid grid;
  if (Status parsed = HeaderParser(header).Parse(descr, fortran_order, grid.shape); !parsed) return fail(parsed.message());
  if (descr != "<f4") return fail(fmt::format("dtype '{}' is not float32 ('<f4'): convert with .astype('<f4')", descr));
  if (grid.shape.empty()) return fail("a scalar, not an array");
  if (Status problem = shape_problem(grid.shape); !problem) return fail(problem.message());
  std::size_t count = 1;
  for (std::size_t size : grid.shape) count *= size;  // the check bounded it
  const std::size_t data_bytes = count * sizeof(float);
  const std::size_t available = bytes.size() - prefix - header_length;
  if (available != data_bytes) {
    return fail(fmt::format("shape {} needs {} bytes of data, the file has {}", ShapeText(grid.shape), data_bytes, available));
  }
  grid.values.resize(count);
  const std::uint8_t* data = bytes.data() + prefix + header_length;
  if (!fortran_order || grid.shape.size() == 1) {
    if (data_bytes > 0) std::memcpy(grid.values.data(), data, data_bytes);
    return grid;
  }
  // Fortran order: the first index varies fastest in the file; C order (values) the last.
  const std::size_t n0 = grid.shape[0], n1 = grid.shape[1], n2 = grid.shape.size() == 3 ? grid.shape[2] : 1;
  for (std::size_t i = 0; i < n0; ++i) {
    for (std::size_t j = 0; j < n1; ++j) {
      for (std::size_t k = 0; k < n2; ++k) {
        std::memcpy(&grid.values[(i * n1 + j) * n2 + k], data + (i + n0 * (j + n1 * k)) * sizeof(float), sizeof(float));
      }
    }
  }
  return grid;
}

}  // namespace

Result<NpyGrid> ParseNpyGrid(std::span<const std::uint8_t> bytes, const std::string& name) {
  return ParseNpyChecked(bytes, name, GridShapeProblem);
}

Result<NpyArray> ParseNpy(std::span<const std::uint8_t> bytes, const std::string& name) {
  Result<NpyGrid> grid = ParseNpyChecked(bytes, name, VertexShapeProblem);
  if (!grid) return grid.error();
  NpyArray array;
  array.rows = grid->shape[0];
  array.columns = grid->shape.size() == 2 ? static_cast<int>(grid->shape[1]) : 1;
  array.values = std::move(grid->values);
  return array;
}

namespace {

// The file's bytes, or why not (a size no array within the limits has).
Result<std::string> ReadNpyBytes(const std::filesystem::path& path) {
  if (const Status why = InputFileProblem(path, /*pipes_allowed=*/false); !why.ok()) {
    return Failure(why.error().code, fmt::format("{}: {}", path.string(), why.message()));
  }
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return Malformed(fmt::format("{}: cannot read the file", path.string()));
  if (size > kMaxNpyHeaderBytes + 16 + kMaxNpyRows * 16) {
    return Malformed(fmt::format("{}: {} bytes, larger than any array within the row limit", path.string(), size));
  }
  std::optional<std::string> text = ReadWholeFile(path);
  if (!text) return Malformed(fmt::format("{}: cannot read the file", path.string()));
  return std::move(*text);
}

std::span<const std::uint8_t> BytesOf(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

}  // namespace

Result<NpyArray> ReadNpy(const std::filesystem::path& path) {
  Result<std::string> bytes = ReadNpyBytes(path);
  if (!bytes) return bytes.error();
  return ParseNpy(BytesOf(*bytes), path.string());
}

Result<NpyGrid> ReadNpyGrid(const std::filesystem::path& path) {
  Result<std::string> bytes = ReadNpyBytes(path);
  if (!bytes) return bytes.error();
  return ParseNpyGrid(BytesOf(*bytes), path.string());
}

std::string NpyHeader(std::size_t rows, int columns) {
  std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", rows, columns);
  const std::size_t unpadded = kMagicSize + 4 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  std::string bytes(kMagic, kMagicSize);
  bytes.push_back(1);
  bytes.push_back(0);
  bytes.push_back(static_cast<char>(header.size() & 0xFF));
  bytes.push_back(static_cast<char>(header.size() >> 8));
  return bytes + header;
}

std::vector<std::uint8_t> FormatNpy(const NpyArray& array) {
  const std::string header = NpyHeader(array.rows, array.columns);
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  const auto* data = reinterpret_cast<const std::uint8_t*>(array.values.data());
  bytes.insert(bytes.end(), data, data + array.values.size() * sizeof(float));
  return bytes;
}

}  // namespace vs11::mesh
