; sh9_vertex_od0.vsh - a complete vs_1_1 vertex shader: transforms the position to clip space and
; lights the vertex with SH irradiance (the paper's 11 instructions, corrected, sh9_irradiance.vsh)
; into the diffuse colour.
;
; Inputs:    v0 = position (x, y, z, 1)   dcl_position
;            v1 = unit normal (x, y, z, 1) dcl_normal; a FLOAT3 normal element arrives with w = 1
;                 (vs_1_1 fills missing components from (0, 0, 0, 1)), which the dp4 with cA needs.
; Outputs:   oPos = WORLDVIEWPROJ v0 (rows c7..c10, m4x4)
;            oD0.rgb = E(n) by eq. (7); oD0.a is not written. D3D clamps oD0 to [0, 1] before the
;            rasterizer, so irradiance above 1 saturates (see sh9_vertex_ot0_hdr.vsh for HDR); the
;            vs11 machine reports the raw value.
; Constants: c0..c6 = cAr cAg cAb cBr cBg cBb cC (the paper's Table 1), c7..c10 = WORLDVIEWPROJ.
; Temporaries: r0..r3. 12 instructions, 15 slots, 11 constants.
;
; vs11: reference=sh9
; vs11: packing=table1
; vs11: position=v0
; vs11: normal=v1
; vs11: output=oD0
; vs11: constants=c0
; vs11: transform=c7

vs_1_1

dcl_position v0
dcl_normal v1

#define cAr c0
#define cAg c1
#define cAb c2
#define cBr c3
#define cBg c4
#define cBb c5
#define cC  c6
#define WORLDVIEWPROJ 7

m4x4 oPos, v0, c[WORLDVIEWPROJ]   ; clip-space position

dp4 r1.r, v1, cAr                 ; x1: constant and linear terms
dp4 r1.g, v1, cAg
dp4 r1.b, v1, cAb
mul r2, v1.xyzz, v1.yzzx          ; (xy, yz, zz, zx)
dp4 r3.r, r2, cBr                 ; x2
dp4 r3.g, r2, cBg
dp4 r3.b, r2, cBb
mul r0.xy, v1.xy, v1.xy           ; (x^2, y^2)
add r0.x, r0.x, -r0.y             ; x^2 - y^2
mad r2.rgb, cC.rgb, r0.x, r3.rgb  ; x2 + x3
add oD0.rgb, r1.rgb, r2.rgb       ; x1 + x2 + x3
