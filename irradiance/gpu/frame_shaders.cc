#include "irradiance/gpu/frame_shaders.h"

#include <fmt/format.h>

namespace vs11::irradiance::gpu {

std::string MipShaderSource() {
  return fmt::format(R"(#version 310 es
precision highp float;
precision highp int;
layout(local_size_x = {0}, local_size_y = {0}) in;
layout(rgba32f, binding = 0) readonly uniform highp imageCube fine;
layout(rgba32f, binding = 1) writeonly uniform highp imageCube coarse;
uniform int coarse_size;
void main() {{
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (p.x >= coarse_size || p.y >= coarse_size) return;
  ivec2 f = 2 * p.xy;
  vec4 a = imageLoad(fine, ivec3(f, p.z));
  vec4 b = imageLoad(fine, ivec3(f + ivec2(1, 0), p.z));
  vec4 c = imageLoad(fine, ivec3(f + ivec2(0, 1), p.z));
  vec4 d = imageLoad(fine, ivec3(f + ivec2(1, 1), p.z));
  imageStore(coarse, p, (a * 0.25 + b * 0.25) + (c * 0.25 + d * 0.25));
}}
)",
                     kMipTile);
}

std::string ProjectionShaderSource() {
  return fmt::format(R"(#version 310 es
precision highp float;
precision highp int;
layout(local_size_x = {0}) in;
layout(rgba32f, binding = 0) readonly uniform highp imageCube environment;
layout(std430, binding = 0) readonly buffer Moments {{ float moment[]; }};
layout(std430, binding = 1) writeonly buffer Partials {{ float partial[]; }};
uniform int size;
shared float sums[{1} * {0}];
void main() {{
  uint thread = gl_LocalInvocationID.x;
  uint group = gl_WorkGroupID.x;
  uint groups = gl_NumWorkGroups.x;
  int face = int(gl_WorkGroupID.z);
  uint texels = uint(size * size);
  float running[{1}];
  for (int k = 0; k < {1}; ++k) running[k] = 0.0;
  for (uint i = group * {0}u + thread; i < texels; i += groups * {0}u) {{
    vec3 radiance = imageLoad(environment, ivec3(int(i % uint(size)), int(i / uint(size)), face)).rgb;
    for (int j = 0; j < 9; ++j) {{
      float w = moment[uint(j) * texels + i];
      running[3 * j] += radiance.r * w;
      running[3 * j + 1] += radiance.g * w;
      running[3 * j + 2] += radiance.b * w;
    }}
  }}
  for (int k = 0; k < {1}; ++k) sums[uint(k) * {0}u + thread] = running[k];
  barrier();
  for (uint half_count = {0}u / 2u; half_count > 0u; half_count /= 2u) {{
    if (thread < half_count) {{
      for (int k = 0; k < {1}; ++k) sums[uint(k) * {0}u + thread] += sums[uint(k) * {0}u + thread + half_count];
    }}
    memoryBarrierShared();
    barrier();
  }}
  if (thread < {1}u) partial[(uint(face) * groups + group) * {1}u + thread] = sums[thread * {0}u];
}}
)",
                     kReductionThreads, kFaceSums);
}

std::string CoefficientsShaderSource() {
  return fmt::format(R"(#version 310 es
precision highp float;
precision highp int;
layout(local_size_x = {0}) in;
layout(std430, binding = 1) readonly buffer Partials {{ float partial[]; }};
layout(std430, binding = 2) readonly buffer Combination {{ float combination[]; }};
layout(std430, binding = 3) writeonly buffer Coefficients {{ float coefficient[]; }};
layout(std430, binding = 4) writeonly buffer Bank {{ vec4 bank[]; }};
uniform int groups;
uniform vec4 c;  // c0, c1, c2, 3 c3 (paper section 3.2)
uniform float c3;
uniform float c4;
uniform int constant_base;
shared float face_sums[6 * {1}];
shared float sh[27];
void main() {{
  uint thread = gl_LocalInvocationID.x;
  for (uint k = thread; k < 6u * {1}u; k += {0}u) {{
    uint face = k / {1}u;
    uint slot = k % {1}u;
    float sum = 0.0;
    for (uint g = 0u; g < uint(groups); ++g) sum += partial[(face * uint(groups) + g) * {1}u + slot];
    face_sums[k] = sum;
  }}
  memoryBarrierShared();
  barrier();
  if (thread < 27u) {{
    uint lm = thread / 3u;
    uint channel = thread % 3u;
    float value = 0.0;
    for (uint face = 0u; face < 6u; ++face) {{
      for (uint j = 0u; j < 9u; ++j) {{
        value += combination[(face * 9u + lm) * 9u + j] * face_sums[face * {1}u + j * 3u + channel];
      }}
    }}
    sh[thread] = value;
    coefficient[thread] = value;
  }}
  memoryBarrierShared();
  barrier();
  if (thread < 3u) {{
    // Table 1: index lm * 3 + channel; L00 0, L1-1 1, L10 2, L11 3, L2-2 4, L2-1 5, L20 6, L21 7, L22 8.
    uint ch = thread;
    bank[constant_base + int(ch)] = vec4(c.y * sh[9u + ch], c.y * sh[3u + ch], c.y * sh[6u + ch],
                                         c.x * sh[ch] - c3 * sh[18u + ch]);
    bank[constant_base + 3 + int(ch)] = vec4(c.z * sh[12u + ch], c.z * sh[15u + ch], c.w * sh[18u + ch],
                                             c.z * sh[21u + ch]);
  }}
  if (thread == 0u) bank[constant_base + 6] = vec4(c4 * sh[24], c4 * sh[25], c4 * sh[26], 0.0);
}}
)",
                     kReductionThreads, kFaceSums);
}

}  // namespace vs11::irradiance::gpu
