// The C library fuzz target's input (tests/fuzz/fuzz_capi.cc), read from and written to bytes so
// that make_fuzz_seeds can write seeds the target reads as intended:
//   byte 0: bit 0 D3D8, bits 1-3 the vertex count - 1; bytes 1-2 declaration tokens, 3-4 function
//   tokens, 5 input elements, 6 output elements (counts); 7-10 the output FVF (0: the output
//   elements); 11-12 the output stride; 13-28 the 16 streams' strides; then the tokens, the
//   elements (8 bytes each) and the vertex bytes. Short inputs read zeros past their end.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include <vs11/vs11_c.h>

namespace vs11::fuzz {

struct CApiInput {
  bool d3d8 = false;
  int vertex_count = 1;  // 1-8
  std::vector<std::uint32_t> declaration, tokens;
  std::vector<vs11c_vertex_element> input, output;  // without their D3DDECL_END
  std::uint32_t fvf = 0;
  std::uint16_t output_stride = 0;
  std::array<std::uint8_t, 16> strides{};
  std::vector<std::uint8_t> vertex_bytes;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  template <class T>
  T Read() {
    std::array<std::uint8_t, sizeof(T)> raw{};
    for (std::uint8_t& byte : raw) byte = at_ < bytes_.size() ? bytes_[at_++] : 0;
    T value;
    std::memcpy(&value, raw.data(), sizeof value);
    return value;
  }
  std::span<const std::uint8_t> Rest() const { return bytes_.subspan(std::min(at_, bytes_.size())); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

inline constexpr int kMaxFuzzTokens = 1024, kMaxFuzzElements = 70;

inline CApiInput ParseCApiInput(std::span<const std::uint8_t> bytes) {
  ByteReader reader(bytes);
  CApiInput input;
  const auto flags = reader.Read<std::uint8_t>();
  input.d3d8 = flags & 1;
  input.vertex_count = ((flags >> 1) & 7) + 1;
  const int declaration_count = reader.Read<std::uint16_t>() % kMaxFuzzTokens;
  const int token_count = reader.Read<std::uint16_t>() % kMaxFuzzTokens;
  const int input_count = reader.Read<std::uint8_t>() % kMaxFuzzElements;
  const int output_count = reader.Read<std::uint8_t>() % kMaxFuzzElements;
  input.fvf = reader.Read<std::uint32_t>();
  input.output_stride = reader.Read<std::uint16_t>();
  for (std::uint8_t& stride : input.strides) stride = reader.Read<std::uint8_t>();
  for (int i = 0; i < declaration_count; ++i) input.declaration.push_back(reader.Read<std::uint32_t>());
  for (int i = 0; i < token_count; ++i) input.tokens.push_back(reader.Read<std::uint32_t>());
  for (int i = 0; i < input_count; ++i) input.input.push_back(reader.Read<vs11c_vertex_element>());
  for (int i = 0; i < output_count; ++i) input.output.push_back(reader.Read<vs11c_vertex_element>());
  const std::span<const std::uint8_t> rest = reader.Rest();
  input.vertex_bytes.assign(rest.begin(), rest.end());
  return input;
}

inline std::vector<std::uint8_t> SerializeCApiInput(const CApiInput& input) {
  std::vector<std::uint8_t> bytes;
  auto put = [&](const auto& value) {
    const auto* raw = reinterpret_cast<const std::uint8_t*>(&value);
    bytes.insert(bytes.end(), raw, raw + sizeof value);
  };
  put(static_cast<std::uint8_t>((input.d3d8 ? 1 : 0) | (input.vertex_count - 1) << 1));
  put(static_cast<std::uint16_t>(input.declaration.size()));
  put(static_cast<std::uint16_t>(input.tokens.size()));
  put(static_cast<std::uint8_t>(input.input.size()));
  put(static_cast<std::uint8_t>(input.output.size()));
  put(input.fvf);
  put(input.output_stride);
  for (std::uint8_t stride : input.strides) put(stride);
  for (std::uint32_t token : input.declaration) put(token);
  for (std::uint32_t token : input.tokens) put(token);
  for (const vs11c_vertex_element& element : input.input) put(element);
  for (const vs11c_vertex_element& element : input.output) put(element);
  bytes.insert(bytes.end(), input.vertex_bytes.begin(), input.vertex_bytes.end());
  return bytes;
}

}  // namespace vs11::fuzz
