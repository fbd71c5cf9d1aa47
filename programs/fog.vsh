; fog.vsh - exponential (and exponential-squared) vertex fog into oFog, the DX8 way: the eye distance
; d comes from dst, the fog factor from exp (full precision 2^x).
;
;   Q = WORLDVIEW v0 (view space), d^2 = Q.Q, dst((d^2), (1/d)) = (1, d, d^2, 1/d)
;   oFog = 2^(k1 d + k2 d^2) = 2^dp3((1, d, d^2), FOG),  FOG = (0, k1, k2, 0)
;   with k1 = -density1 / ln 2 (exp fog) and k2 = -density2^2 / ln 2 (exp2 fog).
;   oPos = WORLDVIEWPROJ v0
; D3D clamps oFog to [0, 1] (it is in (0, 1] here anyway); only oFog.x is used.
; Inputs:    v0 = position (x, y, z, 1)
; Outputs:   oPos, oFog
; Constants: c0..c3 WORLDVIEWPROJ, c4..c6 WORLDVIEW (4x3), c7 FOG = (0, k1, k2, 0)
; Temporaries: r0..r4. Reference: fog (irradiance/report/program_references.cc).
;
; vs11: reference=fog
; vs11: position=v0
; vs11: output=oFog
; vs11: constants=c0

vs_1_1

dcl_position v0

#define WORLDVIEWPROJ 0
#define WORLDVIEW 4
#define FOG c7

m4x4 oPos, v0, c[WORLDVIEWPROJ]
m4x3 r0.xyz, v0, c[WORLDVIEW]     ; view-space position Q
dp3 r1, r0, r0                    ; d^2 in every lane
rsq r2, r1.w                      ; 1/d in every lane
dst r3, r1, r2                    ; (1, d, d^2, 1/d)
dp3 r4.x, r3, FOG                 ; k1 d + k2 d^2
exp oFog, r4.x                    ; 2^(k1 d + k2 d^2)
