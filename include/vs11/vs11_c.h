/* vs11's C interface for Direct3D 8/9 translation layers: create a vertex shader from D3D9 tokens
 * or from D3D8 tokens and declaration, validate it with D3D's rules, set its float constants and
 * run it over vertex streams, writing the destination vertices ProcessVertices writes.
 * C99; link libvs11c (`pkg-config --cflags --libs vs11c`). README, "C library".
 *
 * Conventions:
 * - Every function that can fail returns a vs11c_status; VS11C_OK is 0. Nothing is thrown, nothing
 *   exits, and a failed call changes no output buffer but the ones it documents.
 * - Handles are opaque; buffers are the caller's. Counts are explicit: no call reads a token stream
 *   or a declaration past the count it is given, whatever its end token says.
 * - The shader model comes from the version token: the same calls serve every model the library
 *   accepts (vs_1_0, vs_1_1, vs_2_0, vs_2_x and vs_3_0).
 * - Thread safety: a vs11c_shader may be used by one thread at a time (its calls change its
 *   constants and its engine's caches); distinct shaders may be used from any number of threads at
 *   once. Validation, creation (each call makes a new shader), vs11c_status_name and
 *   vs11c_version are safe from any number of threads at once.
 *   (tests/vm/capi/capi_threads_test.cc.)
 */
#ifndef VS11_VS11_C_H_
#define VS11_VS11_C_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum vs11c_status {
  VS11C_OK = 0,
  VS11C_INVALID_ARGUMENT = 1,     /* a null pointer, a count of 0 where one is needed, an unknown name */
  VS11C_MALFORMED_TOKENS = 2,     /* the token stream does not decode (vs11c_validate_* says where) */
  VS11C_INVALID_SHADER = 3,       /* the shader decodes but breaks a validation rule */
  VS11C_BAD_DECLARATION = 4,      /* a D3D8 declaration token or a D3D9 element that is not valid */
  VS11C_UNSUPPORTED = 5,          /* valid in D3D but not modelled here (a tessellator token, ...) */
  VS11C_REGISTER_OUT_OF_RANGE = 6,/* a constant register beyond the shader's bank */
  VS11C_ENGINE_FAILED = 7,        /* the engine could not be built or run (vs11c_shader_engine_error says why) */
  VS11C_OUT_OF_MEMORY = 8
} vs11c_status;

/* "ok", "invalid-argument", ... (static storage). */
const char* vs11c_status_name(vs11c_status status);
/* The library's version, "0.1.0" (static storage). */
const char* vs11c_version(void);

/* ---- Validation: what IDirect3DShaderValidator9 and D3D8's ValidateVertexShader report ---- */

typedef enum vs11c_severity { VS11C_ERROR = 0, VS11C_WARNING = 1 } vs11c_severity;

typedef struct vs11c_message {
  vs11c_severity severity;
  char code[48];     /* stable name of the rule: "undeclared-input", "bytecode-truncated", "d3d8-declaration" */
  char text[400];    /* the message, cut (and still terminated) where longer */
  long instruction;  /* index of the instruction at fault in the token stream (dcl and def count), or -1 */
  long token;        /* index of the 32-bit token at fault (declaration tokens for "d3d8-declaration"), or -1 */
} vs11c_message;

/* Constants c0..c(constant_count-1) exist (D3DCAPS9.MaxVertexShaderConst); 0 gives 96, D3D's
 * minimum for vs_1_1. At most 8192. A NULL options pointer means all defaults. */
typedef struct vs11c_shader_options {
  int constant_count;
} vs11c_shader_options;

/* Decodes and validates a D3D9 vertex shader (D3D9's rules: every v# read has a dcl_). Writes the
 * first `capacity` messages to `messages` (may be NULL when capacity is 0) and their total number
 * to `*message_count` (may be NULL). Returns VS11C_OK when the shader may be created (warnings
 * allowed), VS11C_MALFORMED_TOKENS or VS11C_INVALID_SHADER when not. */
vs11c_status vs11c_validate_d3d9(const uint32_t* tokens, size_t token_count, const vs11c_shader_options* options,
                                 vs11c_message* messages, size_t capacity, size_t* message_count);
/* The same for D3D8: the declaration (D3DVSD_* tokens ending in D3DVSD_END) and the function tokens
 * (D3D8's rules: no dcl_, v# bound by the declaration). A bad declaration gives
 * VS11C_BAD_DECLARATION (or VS11C_UNSUPPORTED, VS11C_REGISTER_OUT_OF_RANGE) with a "d3d8-declaration"
 * message; a register the shader reads that the declaration does not load is a warning. */
vs11c_status vs11c_validate_d3d8(const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                                 size_t token_count, const vs11c_shader_options* options, vs11c_message* messages,
                                 size_t capacity, size_t* message_count);

/* ---- Shaders ---- */

typedef struct vs11c_shader vs11c_shader;

/* Creates a shader from D3D9 function tokens (options may be NULL). Fails with the status of
 * vs11c_validate_d3d9 when the shader does not validate. */
vs11c_status vs11c_shader_create_d3d9(const uint32_t* tokens, size_t token_count, const vs11c_shader_options* options,
                                      vs11c_shader** shader);
/* Creates a shader from D3D8's two token streams, as IDirect3DDevice8::CreateVertexShader takes
 * them. The declaration's D3DVSD_CONST tokens are loaded into the constants now (later
 * vs11c_shader_set_constants calls write over them). */
vs11c_status vs11c_shader_create_d3d8(const uint32_t* declaration, size_t declaration_count, const uint32_t* tokens,
                                      size_t token_count, const vs11c_shader_options* options,
                                      vs11c_shader** shader);
void vs11c_shader_destroy(vs11c_shader* shader); /* NULL is ignored */

/* SetVertexShaderConstantF: registers start..start+vector_count-1 get 4 floats each. Registers
 * never set read 0; the shader's def constants take precedence over these, as in D3D. */
vs11c_status vs11c_shader_set_constants(vs11c_shader* shader, unsigned start, const float* values,
                                        size_t vector_count);

typedef enum vs11c_float_rules {
  VS11C_FLOAT_RULES_D3D9 = 0,  /* IEEE single precision: 0 * inf is NaN */
  VS11C_FLOAT_RULES_LEGACY = 1 /* a zero operand makes every product zero (NV2x, ATI legacy mode) */
} vs11c_float_rules;

/* The engine: "ref" (or "reference"), "batch" or "jit"; NULL: the fastest this CPU runs. Every
 * engine gives the same bits. `float_rules` is a vs11c_float_rules; it is an int so that any value a
 * caller passes is defined to read (another value is VS11C_INVALID_ARGUMENT). */
vs11c_status vs11c_shader_set_engine(vs11c_shader* shader, const char* engine, int float_rules);

/* ---- Vertex textures (vs_3_0's texldl) ---- */

typedef enum vs11c_texture_format {
  VS11C_TEXTURE_R32F = 0,          /* one float a texel; samples as (r, 1, 1, 1) */
  VS11C_TEXTURE_A32B32G32R32F = 1  /* four floats a texel, (r, g, b, a) */
} vs11c_texture_format;

/* D3DTEXTUREADDRESS values; MIRROR (2) and MIRRORONCE (5) give VS11C_UNSUPPORTED. */
typedef enum vs11c_texture_address {
  VS11C_ADDRESS_WRAP = 1,
  VS11C_ADDRESS_CLAMP = 3,
  VS11C_ADDRESS_BORDER = 4 /* the border colour is 0 (D3DSAMP_BORDERCOLOR's default) */
} vs11c_texture_address;

/* SetTexture(D3DVERTEXTEXTURESAMPLER0 + sampler) with SetSamplerState's ADDRESSU and ADDRESSV: binds
 * a copy of `texels` (width x height texels, row v = 0 first, 1 or 4 floats each by `format`, a
 * vs11c_texture_format) to sampler s<sampler> (0-3) as a one-level texture, point sampled; NULL
 * texels unbind it (it then reads (0, 0, 0, 1)). Sizes from 1, at most 2^24 texels, no power of two
 * needed. A sampler beyond s3: VS11C_REGISTER_OUT_OF_RANGE; another format, a size of 0 or too many
 * texels: VS11C_INVALID_ARGUMENT. README, "Vertex textures". */
vs11c_status vs11c_shader_set_texture(vs11c_shader* shader, unsigned sampler, int format, unsigned width,
                                      unsigned height, const float* texels, int address_u, int address_v);

/* ---- Vertices ---- */

/* D3DVERTEXELEMENT9, the same layout (8 bytes). Type is a D3DDECLTYPE, Usage a D3DDECLUSAGE. */
typedef struct vs11c_vertex_element {
  uint16_t stream;
  uint16_t offset;
  uint8_t type;
  uint8_t method; /* D3DDECLMETHOD_DEFAULT (0) only */
  uint8_t usage;
  uint8_t usage_index;
} vs11c_vertex_element;

/* D3DDECL_END(): every declaration array ends with it. */
#define VS11C_DECL_END {0xFF, 0, 17, 0, 0, 0}

/* One vertex buffer as SetStreamSource gives it: vertex i of the call starts at
 * (const char*)data + i * stride. The bytes are read, never written. */
typedef struct vs11c_stream {
  const void* data;
  size_t stride;
} vs11c_stream;

/* D3DVIEWPORT9: where ProcessVertices puts a transformed (XYZRHW, POSITIONT) position. */
typedef struct vs11c_viewport {
  float x, y, width, height, min_z, max_z;
} vs11c_viewport;

/* Where the shader's outputs go, as the destination buffer of ProcessVertices. Exactly one of
 * `fvf` (non-zero: D3DFVF_XYZ, D3DFVF_XYZRHW or D3DFVF_XYZW, D3DFVF_PSIZE, D3DFVF_DIFFUSE,
 * D3DFVF_SPECULAR, D3DFVF_TEXn with D3DFVF_TEXCOORDSIZEn; blend weights and D3DFVF_NORMAL, which
 * no shader writes, give VS11C_UNSUPPORTED) and `declaration` (D3DVERTEXELEMENT9s of stream 0 ending in
 * VS11C_DECL_END, types FLOAT1..4 and D3DCOLOR; usages POSITION/POSITIONT, COLOR0/1, TEXCOORD0-7,
 * PSIZE, FOG) is given. Vertex i is written at data + i * stride; bytes no element names are left
 * as they were. Colours are clamped to [0, 1] and rounded to the nearest of 255 steps (NaN: 0).
 * A transformed position (XYZRHW, POSITIONT) with a viewport is D3D's screen position
 * (x + (1 + X/W) * width/2, y + (1 - Y/W) * height/2, min_z + Z/W * (max_z - min_z), 1/W); without a
 * viewport, and for an untransformed one, the shader's oPos as it is. No clipping is done. An
 * output register the shader never writes gives (1, 1, 1, 1) for oD0, (0, 0, 0, 1) for oD1 and 0
 * elsewhere (DXVK's choice; D3D leaves it undefined). */
typedef struct vs11c_output {
  void* data;
  size_t stride;
  uint32_t fvf;
  const vs11c_vertex_element* declaration;
  const vs11c_viewport* viewport; /* may be NULL */
} vs11c_output;

/* Runs the shader over vertex_count vertices. D3D9 shaders: `declaration` (D3DVERTEXELEMENT9s
 * ending in VS11C_DECL_END) maps each element by usage and usage index to the dcl_ input of the
 * same usage. D3D8 shaders: `declaration` must be NULL; their own maps streams to registers.
 * streams[s] is stream s (stream_count of them). Every D3DDECLTYPE is read: FLOAT1-4, D3DCOLOR
 * (bytes B, G, R, A to (R, G, B, A) / 255), UBYTE4, SHORT2, SHORT4, UBYTE4N, SHORT2N, SHORT4N
 * (v / 32767, so -32768 is slightly below -1), USHORT2N, USHORT4N, UDEC3, DEC3N (v / 511),
 * FLOAT16_2, FLOAT16_4; missing components read (0, 0, 0, 1), as do inputs no element supplies. */
vs11c_status vs11c_process_vertices(vs11c_shader* shader, const vs11c_vertex_element* declaration,
                                    const vs11c_stream* streams, size_t stream_count, size_t vertex_count,
                                    const vs11c_output* output);

/* Why the latest vs11c_process_vertices on `shader` that returned VS11C_ENGINE_FAILED failed: the
 * engine's message (a jit on a CPU it does not serve; a vs_2_0 loop that unrolls past what the batch
 * and jit engines run); "" before any did, and for a NULL shader. The text belongs to the shader:
 * valid until the next call on it. */
const char* vs11c_shader_engine_error(const vs11c_shader* shader);

#ifdef __cplusplus
}
#endif

#endif /* VS11_VS11_C_H_ */
