// The GLSL ES 3.10 compute shaders of the GPU frame (gpu_frame.h), one per stage. Each works on GL
// objects the previous stage left on the GPU: nothing is read back between them.
#pragma once

#include <string>

namespace vs11::irradiance::gpu {

// Threads of a projection or reduction workgroup. 27 floats each in shared memory (13.8 KB) stay
// under OpenGL ES 3.1's guaranteed 16 KB of GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, and 128 is its
// guaranteed GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS.
inline constexpr int kReductionThreads = 128;
// Threads per side of a mip workgroup (8 x 8 texels of one face).
inline constexpr int kMipTile = 8;
// Sums per face of the projection: nine block moments x three channels.
inline constexpr int kFaceSums = 27;

// One mip level from the one above: each texel the float mean of its 2 x 2 children, added in
// irradiance/sh's order (a/4 + b/4) + (c/4 + d/4), from image unit 0 (the finer level of the
// environment's cube texture, rgba32f) to image unit 1 (the coarser level). Uniform `coarse_size`.
std::string MipShaderSource();

// The first pass of the projection at one level: workgroup (g, 0, face) sums, over the texels
// g * kReductionThreads + thread + k * (groups * kReductionThreads) of the face, radiance x each of
// the nine block moments (storage buffer 0, moment-major: moment j of texel i at j * size^2 + i), each
// thread in its own float running sums, then a tree over the workgroup's threads in shared memory;
// the workgroup's 27 sums go to storage buffer 1 at (face * groups + g) * 27. Image unit 0: the
// environment's level. Uniform `size`.
std::string ProjectionShaderSource();

// The second pass, one workgroup: each face's 27 sums over the first pass's `groups` partials (one
// float running sum each), the nine coefficients per channel from them with the factors of
// BlockMomentCombinationFactors (storage buffer 2, [face][lm][moment], as floats), written to storage
// buffer 3 ([lm * 3 + channel]), and the paper's Table 1 registers packed from them (uniform `c`:
// c0, c1, c2, 3 c3; `c3`; `c4`) into storage buffer 4 (a vs_1_1 constant bank of vec4s) at register
// `constant_base` on.
std::string CoefficientsShaderSource();

}  // namespace vs11::irradiance::gpu
