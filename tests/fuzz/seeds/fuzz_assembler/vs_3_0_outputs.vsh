vs_3_0
dcl_position v0
dcl_position o0
dcl_texcoord3 o3
dcl_2d s0
texldl r0, v0, s0
mov o0, -r0_abs
mov_sat o3, r0
sincos r1.xy, r0.x
mov o[a0.x + 3], r1
