/* The C library from C, built against the installed tree alone (tests/c_consumer/install_test.cmake):
 * a D3D9 and a D3D8 shader over two interleaved streams with packed types, each checked against the
 * reference engine through the same calls and against values computed by hand. C99; exit 0 when
 * every check passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <vs11/vs11_c.h>

static int failures = 0;
#define CHECK(condition)                                                   \
  do {                                                                     \
    if (!(condition)) {                                                    \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      ++failures;                                                          \
    }                                                                      \
  } while (0)
#define CHECK_OK(call) CHECK((call) == VS11C_OK)

static int near(float actual, float expected) { return fabsf(actual - expected) <= 1e-5f * (1.0f + fabsf(expected)); }

static float float_at(const unsigned char* bytes) {
  float value;
  memcpy(&value, bytes, sizeof value);
  return value;
}
static uint32_t dword_at(const unsigned char* bytes) {
  uint32_t value;
  memcpy(&value, bytes, sizeof value);
  return value;
}

enum { kCount = 64 };

/* vs_1_1: dcl_position v0, dcl_normal v1, dcl_color v2, dcl_texcoord0 v3, dcl_blendweight v4;
 * m4x4 oPos, v0, c0; dp3 r0.x, v1, c4; max r0.x, r0.x, c5.x; mul oD0, v2, r0.x; mov oD1, v4; mov oT0, v3 */
static const uint32_t kD3d9Tokens[] = {
    0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x0000001F, 0x80000003, 0x900F0001, 0x0000001F,
    0x8000000A, 0x900F0002, 0x0000001F, 0x80000005, 0x900F0003, 0x0000001F, 0x80000001, 0x900F0004,
    0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x00000008, 0x80010000, 0x90E40001, 0xA0E40004,
    0x0000000B, 0x80010000, 0x80000000, 0xA0000005, 0x00000005, 0xD00F0000, 0x90E40002, 0x80000000,
    0x00000001, 0xD00F0001, 0x90E40004, 0x00000001, 0xE00F0000, 0x90E40003, 0x0000FFFF};

/* Stream 0: FLOAT3 position, SHORT4N normal (20 bytes). Stream 1: D3DCOLOR, FLOAT16_2 texcoord,
 * UBYTE4N blend weight (12 bytes). */
struct d3d9_vertex0 { float position[3]; int16_t normal[4]; };
struct d3d9_vertex1 { uint32_t color; uint16_t texcoord[2]; uint8_t weight[4]; };
enum { kD3d9OutputStride = 44 }; /* POSITIONT float4, COLOR0 D3DCOLOR, COLOR1 float4, TEXCOORD0 float2 */

static vs11c_status run_d3d9(const char* engine, const struct d3d9_vertex0* s0, const struct d3d9_vertex1* s1,
                             unsigned char* out) {
  static const vs11c_vertex_element input[] = {
      {0, 0, 2, 0, 0, 0},  /* FLOAT3 POSITION */
      {0, 12, 10, 0, 3, 0}, /* SHORT4N NORMAL */
      {1, 0, 4, 0, 10, 0},  /* D3DCOLOR COLOR */
      {1, 4, 15, 0, 5, 0},  /* FLOAT16_2 TEXCOORD0 */
      {1, 8, 8, 0, 1, 0},   /* UBYTE4N BLENDWEIGHT */
      VS11C_DECL_END};
  static const vs11c_vertex_element output_declaration[] = {
      {0, 0, 3, 0, 9, 0}, {0, 16, 4, 0, 10, 0}, {0, 20, 3, 0, 10, 1}, {0, 36, 1, 0, 5, 0}, VS11C_DECL_END};
  static const float constants[] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, /* c0-c3 */
                                    0, 1, 0, 0,                                      /* c4: the light */
                                    0.25f, 0, 0, 0};                                 /* c5: ambient */
  const vs11c_viewport viewport = {0, 0, 640, 480, 0, 1};
  const vs11c_stream streams[2] = {{s0, sizeof *s0}, {s1, sizeof *s1}};
  const vs11c_output output = {out, kD3d9OutputStride, 0, output_declaration, &viewport};
  vs11c_shader* shader = NULL;
  vs11c_status status = vs11c_shader_create_d3d9(kD3d9Tokens, sizeof kD3d9Tokens / sizeof kD3d9Tokens[0], NULL, &shader);
  if (status == VS11C_OK) status = vs11c_shader_set_constants(shader, 0, constants, 6);
  if (status == VS11C_OK) status = vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_D3D9);
  if (status == VS11C_OK) status = vs11c_process_vertices(shader, input, streams, 2, kCount, &output);
  vs11c_shader_destroy(shader);
  return status;
}

static void test_d3d9(void) {
  struct d3d9_vertex0 s0[kCount];
  struct d3d9_vertex1 s1[kCount];
  static unsigned char reference[kCount * kD3d9OutputStride], fastest[kCount * kD3d9OutputStride],
      batch[kCount * kD3d9OutputStride];
  for (int i = 0; i < kCount; ++i) {
    const int16_t even[4] = {0, 32767, -32768, 0}, odd[4] = {16384, -16384, 0, 32767};
    const uint8_t weight[4] = {255, 0, 51, 128};
    s0[i].position[0] = i * 0.25f;
    s0[i].position[1] = 1 - i * 0.5f;
    s0[i].position[2] = 0.5f;
    memcpy(s0[i].normal, i % 2 ? odd : even, sizeof even);
    s1[i].color = 0x80FF4020; /* A 0x80, R 0xFF, G 0x40, B 0x20 */
    s1[i].texcoord[0] = 0x3800; /* 0.5 */
    s1[i].texcoord[1] = 0xBC00; /* -1 */
    memcpy(s1[i].weight, weight, sizeof weight);
  }
  CHECK_OK(run_d3d9("reference", s0, s1, reference));
  CHECK_OK(run_d3d9(NULL, s0, s1, fastest));
  CHECK_OK(run_d3d9("batch", s0, s1, batch));
  CHECK(memcmp(fastest, reference, sizeof reference) == 0);
  CHECK(memcmp(batch, reference, sizeof reference) == 0);

  /* Vertex 0 by hand: oPos = (0, 2, 0.5, 1.5); on the 640x480 viewport x = (1 + 0) * 320,
   * y = (1 - 2 / 1.5) * 240, z = 0.5 / 1.5, rhw = 1 / 1.5. The normal (0, 1, -1.00003) lit by
   * (0, 1, 0) gives 1: oD0 is the colour itself. */
  CHECK(near(float_at(reference + 0), 320.0f));
  CHECK(near(float_at(reference + 4), -80.0f));
  CHECK(near(float_at(reference + 8), 1.0f / 3.0f));
  CHECK(near(float_at(reference + 12), 2.0f / 3.0f));
  CHECK(dword_at(reference + 16) == 0x80FF4020u);
  CHECK(near(float_at(reference + 20), 1.0f) && near(float_at(reference + 24), 0.0f));
  CHECK(near(float_at(reference + 28), 0.2f) && near(float_at(reference + 32), 128.0f / 255.0f));
  CHECK(float_at(reference + 36) == 0.5f && float_at(reference + 40) == -1.0f);
  /* Vertex 1: the normal (0.5, -0.5, 0, 1) gives -0.5, raised to the ambient 0.25: a quarter of
   * each channel, (64, 16, 8, 32) as D3DCOLOR. */
  CHECK(dword_at(reference + kD3d9OutputStride + 16) == 0x20401008u);
}

/* vs.1.1: m4x4 oPos, v0, c0; mul oT0.xy, v7, c8; mov oD0, v5 (D3D8: no dcl) */
static const uint32_t kD3d8Tokens[] = {0xFFFE0101, 0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000,
                                       0x00000005, 0xE0030000, 0x90E40007, 0xA0E40008, 0x00000001,
                                       0xD00F0000, 0x90E40005, 0x0000FFFF};
/* D3DVSD_STREAM(0), D3DVSD_REG(0, D3DVSDT_FLOAT3), D3DVSD_REG(5, D3DVSDT_D3DCOLOR), D3DVSD_STREAM(1),
 * D3DVSD_REG(7, D3DVSDT_SHORT2), D3DVSD_CONST(8, 1) with (1/256, 1/256, 0, 0), D3DVSD_END() */
static const uint32_t kD3d8Declaration[] = {0x20000000, 0x40020000, 0x40040005, 0x20000001, 0x40060007,
                                            0x82000008, 0x3B800000, 0x3B800000, 0,          0,
                                            0xFFFFFFFF};
struct d3d8_vertex0 { float position[3]; uint32_t color; };
struct d3d8_output { float position[3]; uint32_t diffuse; float texcoord[2]; }; /* D3DFVF_XYZ|DIFFUSE|TEX1 */

struct short2 { int16_t x, y; };

static vs11c_status run_d3d8(const char* engine, const struct d3d8_vertex0* s0, const struct short2* s1,
                             struct d3d8_output* out) {
  static const float identity[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const vs11c_stream streams[2] = {{s0, sizeof *s0}, {s1, sizeof *s1}};
  const vs11c_output output = {out, sizeof *out, 0x002 | 0x040 | 0x100, NULL, NULL};
  vs11c_shader* shader = NULL;
  vs11c_status status = vs11c_shader_create_d3d8(kD3d8Declaration, sizeof kD3d8Declaration / sizeof kD3d8Declaration[0],
                                                 kD3d8Tokens, sizeof kD3d8Tokens / sizeof kD3d8Tokens[0], NULL, &shader);
  if (status == VS11C_OK) status = vs11c_shader_set_constants(shader, 0, identity, 4);
  if (status == VS11C_OK) status = vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_LEGACY);
  if (status == VS11C_OK) status = vs11c_process_vertices(shader, NULL, streams, 2, kCount, &output);
  vs11c_shader_destroy(shader);
  return status;
}

static void test_d3d8(void) {
  struct d3d8_vertex0 s0[kCount];
  struct short2 s1[kCount];
  struct d3d8_output reference[kCount], fastest[kCount];
  vs11c_message messages[4];
  size_t count = 99;
  for (int i = 0; i < kCount; ++i) {
    s0[i].position[0] = (float)i;
    s0[i].position[1] = -1.5f;
    s0[i].position[2] = 0.25f;
    s0[i].color = 0xFF102030u + (uint32_t)i;
    s1[i].x = (int16_t)(i * 256);
    s1[i].y = -512;
  }
  CHECK(vs11c_validate_d3d8(kD3d8Declaration, sizeof kD3d8Declaration / sizeof kD3d8Declaration[0], kD3d8Tokens,
                            sizeof kD3d8Tokens / sizeof kD3d8Tokens[0], NULL, messages, 4, &count) == VS11C_OK);
  CHECK(count == 0);
  /* The same tokens break D3D9's rule that every input has a dcl_. */
  CHECK(vs11c_validate_d3d9(kD3d8Tokens, sizeof kD3d8Tokens / sizeof kD3d8Tokens[0], NULL, messages, 4, &count) ==
        VS11C_INVALID_SHADER);
  CHECK(count >= 1 && strcmp(messages[0].code, "undeclared-input") == 0 && messages[0].instruction == 0);

  CHECK_OK(run_d3d8("ref", s0, s1, reference));
  CHECK_OK(run_d3d8(NULL, s0, s1, fastest));
  CHECK(memcmp(fastest, reference, sizeof reference) == 0);
  for (int i = 0; i < kCount; i += 21) {
    CHECK(reference[i].position[0] == (float)i && reference[i].position[1] == -1.5f);
    CHECK(reference[i].diffuse == 0xFF102030u + (uint32_t)i);
    CHECK(reference[i].texcoord[0] == (float)i && reference[i].texcoord[1] == -2.0f); /* SHORT2 / 256 */
  }
}

int main(void) {
  printf("vs11c %s\n", vs11c_version());
  test_d3d9();
  test_d3d8();
  if (failures) {
    fprintf(stderr, "%d checks failed\n", failures);
    return 1;
  }
  printf("C library: D3D8 and D3D9 checks passed\n");
  return 0;
}
