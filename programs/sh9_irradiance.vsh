; sh9_irradiance.vsh - irradiance from nine SH coefficients per colour channel, the 11-instruction
; vertex program of Ai, Peng & Zhang 2008 (section 3.2), with its last two instructions corrected as
; in ../shared/spec/vs_1_1.md section 9.
;
; Computes   E(n) = x1 + x2 + x3  per channel (the paper's eq. (7) = eq. (6) for a unit normal):
;   x1 = dp4((x, y, z, 1), cA)                    constant and linear terms
;   x2 = dp4((xy, yz, zz, zx), cB)                four quadratic terms
;   x3 = cC.rgb * (x^2 - y^2)                     the last quadratic term
; Inputs:    v0 = the unit normal (x, y, z, 1)  (a FLOAT3 normal element arrives with w = 1)
; Output:    oD0.rgb = E(n); oD0.a is not written. D3D clamps oD0 to [0, 1] after the shader; the
;            vs11 machine reports the raw (unclamped) value, which is what is verified here.
; Constants: c0..c6 = cAr cAg cAb cBr cBg cBb cC, the paper's Table 1 (PackTable1 in
;            irradiance/sh/sh9.h): cA = (c1 L11, c1 L1-1, c1 L10, c0 L00 - c3 L20),
;            cB = (c2 L2-2, c2 L2-1, 3 c3 L20, c2 L21), cC = (c4 R22, c4 G22, c4 B22, -).
; Temporaries: r0 (where the paper writes r0), r1, r2, r3. 11 instructions, 11 slots.
;
; Differences from the printed listing: the normal is read from v0 where the listing reads r0 (in
; vs_1_1 the vertex data arrives in input registers), r0 is then only a temporary, and the result
; goes to oD0. The printed `mad r1.rgb, ...` / `add r0, r1.rgb, r2.rgb` lose x1 and add the raw
; products (xy, yz, zz) instead of x2 (see sh9_irradiance_as_printed.vsh); corrected here to
; `mad r2.rgb, ...` / `add oD0.rgb, r1.rgb, r2.rgb`.
;
; This is the irradiance part of a vertex shader only: it writes no oPos, so it is validated with
; every vs_1_1 rule except "oPos must be written" (fragment=yes). sh9_vertex_od0.vsh is the complete
; shader.
;
; vs11: reference=sh9
; vs11: packing=table1
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

#define cAr c[0]
#define cAg c[1]
#define cAb c[2]
#define cBr c[3]
#define cBg c[4]
#define cBb c[5]
#define cC  c[6]

; x1: constant and linear terms
dp4 r1.r, v0, cAr
dp4 r1.g, v0, cAg
dp4 r1.b, v0, cAb

; x2: four of the quadratic terms
mul r2, v0.xyzz, v0.yzzx          ; (xy, yz, zz, zx)
dp4 r3.r, r2, cBr
dp4 r3.g, r2, cBg
dp4 r3.b, r2, cBb

; x3: the last quadratic term, then the sum
mul r0.xy, v0.xy, v0.xy           ; (x^2, y^2)
add r0.x, r0.x, -r0.y             ; x^2 - y^2
mad r2.rgb, cC.rgb, r0.x, r3.rgb  ; x2 + x3   (printed: mad r1.rgb, ...)
add oD0.rgb, r1.rgb, r2.rgb       ; x1 + x2 + x3   (printed: add r0, r1.rgb, r2.rgb)
