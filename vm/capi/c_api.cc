// include/vs11/vs11_c.h's functions: argument checks and the exception boundary around
// vm/capi/shader.h. Every function catches what the C++ below may throw (std::bad_alloc), so
// nothing crosses the C ABI.
#include <vs11/vs11_c.h>

#include <algorithm>
#include <cstring>
#include <new>

#include "vm/capi/shader.h"

struct vs11c_shader {
  vs11::capi::Shader shader;
};

namespace {

using vs11::capi::Api;

template <class Body>
vs11c_status Guarded(Body body) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return VS11C_OUT_OF_MEMORY;
  } catch (...) {
    return VS11C_ENGINE_FAILED;  // no other exception is expected from below; none may cross
  }
}

// A pointer with a count: null only where the count is 0.
bool Valid(const void* pointer, std::size_t count) { return pointer != nullptr || count == 0; }

template <class T>
std::span<const T> Span(const T* pointer, std::size_t count) {
  return pointer == nullptr ? std::span<const T>() : std::span<const T>(pointer, count);
}

vs11c_status ValidateInto(Api api, const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                          size_t token_count, const vs11c_shader_options* options, vs11c_message* messages,
                          size_t capacity, size_t* message_count) {
  if (!Valid(declaration, declaration_count) || !Valid(tokens, token_count) || !Valid(messages, capacity)) {
    return VS11C_INVALID_ARGUMENT;
  }
  const std::optional<int> constant_count = vs11::capi::ConstantCountOf(options);
  if (!constant_count) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] {
    const vs11::capi::Validation validation =
        vs11::capi::ValidateShader(api, Span(declaration, declaration_count), Span(tokens, token_count), *constant_count);
    std::copy_n(validation.messages.begin(), std::min(capacity, validation.messages.size()), messages);
    if (message_count != nullptr) *message_count = validation.messages.size();
    return validation.status;
  });
}

vs11c_status Create(Api api, const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                    size_t token_count, const vs11c_shader_options* options, vs11c_shader** shader) {
  if (shader == nullptr) return VS11C_INVALID_ARGUMENT;
  *shader = nullptr;
  if (!Valid(declaration, declaration_count) || !Valid(tokens, token_count)) return VS11C_INVALID_ARGUMENT;
  const std::optional<int> constant_count = vs11::capi::ConstantCountOf(options);
  if (!constant_count) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] {
    vs11::capi::Validation validation =
        vs11::capi::ValidateShader(api, Span(declaration, declaration_count), Span(tokens, token_count), *constant_count);
    if (validation.status != VS11C_OK) return validation.status;
    *shader = new vs11c_shader{vs11::capi::Shader(api, std::move(*validation.program),
                                                  std::move(validation.d3d8_declaration), *constant_count)};
    return VS11C_OK;
  });
}

}  // namespace

extern "C" {

const char* vs11c_status_name(vs11c_status status) {
  switch (status) {
    case VS11C_OK: return "ok";
    case VS11C_INVALID_ARGUMENT: return "invalid-argument";
    case VS11C_MALFORMED_TOKENS: return "malformed-tokens";
    case VS11C_INVALID_SHADER: return "invalid-shader";
    case VS11C_BAD_DECLARATION: return "bad-declaration";
    case VS11C_UNSUPPORTED: return "unsupported";
    case VS11C_REGISTER_OUT_OF_RANGE: return "register-out-of-range";
    case VS11C_ENGINE_FAILED: return "engine-failed";
    case VS11C_OUT_OF_MEMORY: return "out-of-memory";
  }
  return "unknown-status";
}

const char* vs11c_version(void) { return VS11C_VERSION; }

vs11c_status vs11c_validate_d3d9(const uint32_t* tokens, size_t token_count, const vs11c_shader_options* options,
                                 vs11c_message* messages, size_t capacity, size_t* message_count) {
  return ValidateInto(Api::kD3d9, nullptr, 0, tokens, token_count, options, messages, capacity, message_count);
}

vs11c_status vs11c_validate_d3d8(const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                                 size_t token_count, const vs11c_shader_options* options, vs11c_message* messages,
                                 size_t capacity, size_t* message_count) {
  return ValidateInto(Api::kD3d8, declaration, declaration_count, tokens, token_count, options, messages, capacity,
                      message_count);
}

vs11c_status vs11c_shader_create_d3d9(const uint32_t* tokens, size_t token_count, const vs11c_shader_options* options,
                                      vs11c_shader** shader) {
  return Create(Api::kD3d9, nullptr, 0, tokens, token_count, options, shader);
}

vs11c_status vs11c_shader_create_d3d8(const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                                      size_t token_count, const vs11c_shader_options* options,
                                      vs11c_shader** shader) {
  return Create(Api::kD3d8, declaration, declaration_count, tokens, token_count, options, shader);
}

void vs11c_shader_destroy(vs11c_shader* shader) { delete shader; }

vs11c_status vs11c_shader_set_constants(vs11c_shader* shader, unsigned start, const float* values,
                                        size_t vector_count) {
  if (shader == nullptr) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] { return shader->shader.SetConstants(start, values, vector_count); });
}

vs11c_status vs11c_shader_set_texture(vs11c_shader* shader, unsigned sampler, int format, unsigned width,
                                      unsigned height, const float* texels, int address_u, int address_v) {
  if (shader == nullptr) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] { return shader->shader.SetTexture(sampler, format, width, height, texels, address_u, address_v); });
}

vs11c_status vs11c_shader_set_engine(vs11c_shader* shader, const char* engine, int float_rules) {
  if (shader == nullptr) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] { return shader->shader.SetEngine(engine, float_rules); });
}

vs11c_status vs11c_process_vertices(vs11c_shader* shader, const vs11c_vertex_element* declaration,
                                    const vs11c_stream* streams, size_t stream_count, size_t vertex_count,
                                    const vs11c_output* output) {
  if (shader == nullptr || output == nullptr || !Valid(streams, stream_count)) return VS11C_INVALID_ARGUMENT;
  return Guarded([&] { return shader->shader.Process(declaration, Span(streams, stream_count), vertex_count, *output); });
}

const char* vs11c_shader_engine_error(const vs11c_shader* shader) {
  return shader == nullptr ? "" : shader->shader.engine_error().c_str();
}

}  // extern "C"
