// The vs_1_1 programs of programs/ as GLSL ES 3.00 vertex shaders, written as a vs_1_1 translator
// (Wine's, DXVK's) would: each instruction becomes the same float operations in the same order.
//
// Where GLSL cannot promise the same rounding as vs11 (vm/core/semantics.h):
//  * dp3/dp4 are spelled out left to right, a.x*b.x + a.y*b.y + ..., as vs11 computes them; GLSL's
//    dot() leaves the order open. GLSL ES 3.00 has no `precise` (that is ES 3.20), so the compiler
//    may still fuse a product into the following sum (one fma) or reassociate: the outputs may then
//    differ from vs11's in the last bits. compare_llvmpipe measures by how much.
//  * rsq is inversesqrt(abs(x)); vs11 computes 1 / sqrt(|x|) with both roundings, and returns
//    FLT_MAX for 0 and exactly 1 for 1. None of the inputs here reach 0.
//  * lit's power is exp2(power * log2(N.H)) with GLSL's exp2 and log2, which are not vs11's
//    polynomials: the specular term (oD1 of directional_light) differs by a few float ulps.
//  * mov a0.x is int(floor(x)) (spec/vs_1_1.md §1.5). Out-of-range relative reads are undefined in
//    GLSL (vs11 reads 0); the inputs never make one.
// Inputs the vs_1_1 program reads as (x, y, z, 1) arrive as vec3 attributes, extended with w = 1
// in the shader, as a D3D FLOAT3 element is; vs11 gets the same lanes as uniform (FillUniform).
#pragma once

namespace vs11::bench::llvmpipe {

// Helpers shared by every shader: the vs_1_1 dot products, rsq and lit.
inline constexpr char kGlslPrelude[] = R"(#version 300 es
precision highp float;
precision highp int;
float dp3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float dp4(vec4 a, vec4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
float rsq(float x) { return inversesqrt(abs(x)); }
vec4 lit(vec4 s) {
  float power = clamp(s.w, -127.9961, 127.9961);
  float specular = exp2(power * log2(s.y));
  return vec4(1.0, s.x > 0.0 ? s.x : 0.0, (s.x > 0.0 && s.y > 0.0) ? specular : 0.0, 1.0);
}
)";

// programs/sh9_irradiance.vsh, the paper's 11 instructions.
inline constexpr char kSh9IrradianceBody[] = R"(
layout(location = 0) in vec3 v0_xyz;
uniform vec4 c[7];
out vec3 oD0;
void main() {
  vec4 v0 = vec4(v0_xyz, 1.0);
  vec3 r1 = vec3(dp4(v0, c[0]), dp4(v0, c[1]), dp4(v0, c[2]));
  vec4 r2 = v0.xyzz * v0.yzzx;
  vec3 r3 = vec3(dp4(r2, c[3]), dp4(r2, c[4]), dp4(r2, c[5]));
  vec2 r0 = v0.xy * v0.xy;
  r0.x = r0.x + -r0.y;
  r2.rgb = c[6].rgb * r0.x + r3.rgb;
  oD0 = r1.rgb + r2.rgb;
}
)";

// programs/directional_light.vsh.
inline constexpr char kDirectionalLightBody[] = R"(
layout(location = 0) in vec3 v0_xyz;
layout(location = 1) in vec3 v1;
uniform vec4 c[13];
out vec4 oD0;
out vec4 oD1;
void main() {
  vec4 v0 = vec4(v0_xyz, 1.0);
  gl_Position = vec4(dp4(v0, c[0]), dp4(v0, c[1]), dp4(v0, c[2]), dp4(v0, c[3]));
  vec3 r0 = vec3(dp4(v0, c[4]), dp4(v0, c[5]), dp4(v0, c[6]));
  vec4 r1 = vec4(dp3(v1, c[4].xyz), dp3(v1, c[5].xyz), dp3(v1, c[6].xyz), 0.0);
  r1.w = dp3(r1.xyz, r1.xyz);
  r1.w = rsq(r1.w);
  r1.xyz = r1.xyz * r1.w;
  vec4 r2 = vec4(c[8].xyz + -r0, 0.0);
  r2.w = dp3(r2.xyz, r2.xyz);
  r2.w = rsq(r2.w);
  r2.xyz = r2.xyz * r2.w + c[7].xyz;
  r2.w = dp3(r2.xyz, r2.xyz);
  r2.w = rsq(r2.w);
  r2.xyz = r2.xyz * r2.w;
  vec4 r3 = vec4(dp3(r1.xyz, c[7].xyz), dp3(r1.xyz, r2.xyz), 0.0, c[12].w);
  vec4 r4 = lit(r3);
  vec4 r5 = r4.y * c[9];
  oD0 = r5 + c[11];
  oD1 = r4.z * c[10];
}
)";

// programs/skinning.vsh: two bones from a palette at c[6 + a0.x].
inline constexpr char kSkinningBody[] = R"(
layout(location = 0) in vec3 v0_xyz;
layout(location = 1) in vec2 v1;
layout(location = 2) in vec2 v2;
layout(location = 3) in vec3 v3;
uniform vec4 c[30];
out vec4 oD0;
void main() {
  vec4 v0 = vec4(v0_xyz, 1.0);
  int a0 = int(floor(v2.x)) + 6;
  vec4 r0 = vec4(dp4(v0, c[a0]), dp4(v0, c[a0 + 1]), dp4(v0, c[a0 + 2]), 0.0);
  vec4 r2 = vec4(dp3(v3, c[a0].xyz), dp3(v3, c[a0 + 1].xyz), dp3(v3, c[a0 + 2].xyz), 0.0);
  r0.xyz = r0.xyz * v1.x;
  r2.xyz = r2.xyz * v1.x;
  a0 = int(floor(v2.y)) + 6;
  vec3 r1 = vec3(dp4(v0, c[a0]), dp4(v0, c[a0 + 1]), dp4(v0, c[a0 + 2]));
  vec3 r3 = vec3(dp3(v3, c[a0].xyz), dp3(v3, c[a0 + 1].xyz), dp3(v3, c[a0 + 2].xyz));
  r0.xyz = r1 * v1.y + r0.xyz;
  r2.xyz = r3 * v1.y + r2.xyz;
  r0.w = v0.w;
  gl_Position = vec4(dp4(r0, c[0]), dp4(r0, c[1]), dp4(r0, c[2]), dp4(r0, c[3]));
  r2.w = dp3(r2.xyz, r2.xyz);
  r2.w = rsq(r2.w);
  r2.xyz = r2.xyz * r2.w;
  float r4 = dp3(r2.xyz, c[4].xyz);
  r4 = max(r4, c[4].w);
  oD0 = r4 * c[5];
}
)";

}  // namespace vs11::bench::llvmpipe
