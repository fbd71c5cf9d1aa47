// libFuzzer target: the C library's untrusted inputs (include/vs11/vs11_c.h), D3D8 declaration
// tokens, function tokens, D3D9 input and output declarations and FVF codes, with vertex bytes
// (the layout: tests/fuzz/fuzz_capi_input.h). Properties: no crash, no read outside the buffers the
// call was given (ASan), validation and creation agree, and a shader that runs writes the same
// bytes on the reference engine as on the fastest.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <vs11/vs11_c.h>

#include "tests/fuzz/fuzz_capi_input.h"

namespace {

// Every element offset (16 bits) plus the largest type (16 bytes) plus 7 strides of 255 bytes
// lies inside; all 16 streams read this one buffer.
constexpr std::size_t kStreamBytes = 65536 + 16 + 7 * 255;
constexpr std::size_t kMaxOutputStride = 4096;

[[noreturn]] void Fail(const char* what, vs11c_status status) {
  std::fprintf(stderr, "fuzz_capi: %s (%s)\n", what, vs11c_status_name(status));
  std::abort();
}

std::vector<std::uint8_t> Run(vs11c_shader* shader, const char* engine, const vs11::fuzz::CApiInput& input,
                              const std::vector<vs11c_vertex_element>& declaration, const vs11c_stream* streams,
                              const vs11c_output& layout_template, vs11c_status& status) {
  std::vector<std::uint8_t> output(static_cast<std::size_t>(layout_template.stride) * input.vertex_count + 1, 0x5A);
  vs11c_output layout = layout_template;
  layout.data = output.data();
  status = vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_D3D9);
  if (status != VS11C_OK) Fail("set_engine refused a registered engine", status);
  status = vs11c_process_vertices(shader, input.d3d8 ? nullptr : declaration.data(), streams, 16,
                                  static_cast<std::size_t>(input.vertex_count), &layout);
  if (output.back() != 0x5A) Fail("a write past the last vertex", status);
  return output;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const vs11::fuzz::CApiInput input = vs11::fuzz::ParseCApiInput({data, size});
  std::vector<vs11c_message> messages(4);
  std::size_t count = 0;
  const vs11c_status valid =
      input.d3d8 ? vs11c_validate_d3d8(input.declaration.data(), input.declaration.size(), input.tokens.data(),
                                       input.tokens.size(), nullptr, messages.data(), messages.size(), &count)
                 : vs11c_validate_d3d9(input.tokens.data(), input.tokens.size(), nullptr, messages.data(),
                                       messages.size(), &count);
  vs11c_shader* shader = nullptr;
  const vs11c_status created =
      input.d3d8 ? vs11c_shader_create_d3d8(input.declaration.data(), input.declaration.size(), input.tokens.data(),
                                            input.tokens.size(), nullptr, &shader)
                 : vs11c_shader_create_d3d9(input.tokens.data(), input.tokens.size(), nullptr, &shader);
  if (created != valid) Fail("creation and validation disagree", created);
  if (valid != VS11C_OK && count == 0) Fail("a refused shader without a message", valid);
  if (shader == nullptr) return 0;

  static std::vector<std::uint8_t> stream_bytes(kStreamBytes);
  for (std::size_t i = 0; i < kStreamBytes; ++i) {
    stream_bytes[i] = input.vertex_bytes.empty() ? static_cast<std::uint8_t>(i) : input.vertex_bytes[i % input.vertex_bytes.size()];
  }
  vs11c_stream streams[16];
  for (int s = 0; s < 16; ++s) streams[s] = {stream_bytes.data(), input.strides[static_cast<std::size_t>(s)]};
  constexpr vs11c_vertex_element kEnd = VS11C_DECL_END;
  std::vector<vs11c_vertex_element> declaration = input.input, output_declaration = input.output;
  declaration.push_back(kEnd);
  output_declaration.push_back(kEnd);
  const vs11c_output layout{nullptr, input.output_stride % (kMaxOutputStride + 1), input.fvf,
                            input.fvf == 0 ? output_declaration.data() : nullptr, nullptr};
  vs11c_status reference_status, fastest_status;
  const std::vector<std::uint8_t> reference = Run(shader, "ref", input, declaration, streams, layout, reference_status);
  const std::vector<std::uint8_t> fastest = Run(shader, nullptr, input, declaration, streams, layout, fastest_status);
  vs11c_shader_destroy(shader);
  // The later models' programs (vs_2_0 on) run on ref; the fastest engine refuses those without static flow.
  const bool later_model = !input.tokens.empty() && (input.tokens[0] & 0xFF00u) >= 0x0200u;
  if (later_model && fastest_status == VS11C_ENGINE_FAILED) return 0;
  if (reference_status != fastest_status) Fail("the engines' statuses differ", fastest_status);
  if (reference_status == VS11C_OK && reference != fastest) Fail("the engines wrote different bytes", fastest_status);
  return 0;
}
