#include <stdio.h>
#include <vs11/vs11_c.h>

int main(void) {
  /* vs_1_1  dcl_position v0  dcl_color v1  mov oPos, v0  mov oD0, v1: D3D9's tokens */
  static const uint32_t tokens[] = {0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x0000001F,
                                    0x8000000A, 0x900F0001, 0x00000001, 0xC00F0000, 0x90E40000,
                                    0x00000001, 0xD00F0000, 0x90E40001, 0x0000FFFF};
  struct vertex { float x, y, z; uint32_t color; } in[2] = {{1, 2, 3, 0xFF0080FF}, {4, 5, 6, 0x80FF0000}}, out[2];
  /* D3DVERTEXELEMENT9s: FLOAT3 POSITION at 0, D3DCOLOR COLOR at 12 */
  const vs11c_vertex_element declaration[] = {{0, 0, 2, 0, 0, 0}, {0, 12, 4, 0, 10, 0}, VS11C_DECL_END};
  const vs11c_stream stream = {in, sizeof in[0]};
  const vs11c_output output = {out, sizeof out[0], 0x002 | 0x040 /* D3DFVF_XYZ | D3DFVF_DIFFUSE */, NULL, NULL};
  vs11c_shader* shader = NULL;
  vs11c_status status = vs11c_shader_create_d3d9(tokens, sizeof tokens / sizeof tokens[0], NULL, &shader);
  if (status == VS11C_OK) status = vs11c_process_vertices(shader, declaration, &stream, 1, 2, &output);
  vs11c_shader_destroy(shader);
  if (status != VS11C_OK) {
    fprintf(stderr, "vs11c: %s\n", vs11c_status_name(status));
    return 1;
  }
  for (int i = 0; i < 2; ++i) printf("%g %g %g %08x\n", out[i].x, out[i].y, out[i].z, (unsigned)out[i].color);
  return 0;
}
