; sh9_irradiance_unit10.vsh - SH irradiance in 10 instructions, exact on unit normals only.
;
; On the unit sphere z^2 = 1 - x^2 - y^2, so the 3 c3 L20 z^2 term of eq. (7) folds into the constant,
; the x^2 and the y^2 terms, and the quadratic terms become (xy, yz, zx, xx) plus one yy term:
;   E(n) = dp4((x, y, z, 1), cA') + dp4((xy, yz, zx, xx), cB') + cC'.rgb * yy
; with (PackUnitSphere10 in irradiance/sh/sh9.h)
;   cA' = (c1 L11, c1 L1-1, c1 L10, c0 L00 + 2 c3 L20)
;   cB' = (c2 L2-2, c2 L2-1, c2 L21, c4 L22 - 3 c3 L20)
;   cC' = (-c4 L22 - 3 c3 L20 per channel, -)
; Off the sphere it differs from the paper's program (sh9_irradiance.vsh) by exactly
;   paper - unit10 = 3 c3 L20 (x^2 + y^2 + z^2 - 1)   per channel.
; Inputs:    v0 = the unit normal (x, y, z, 1)
; Output:    oD0.rgb = E(n) (raw; D3D would clamp oD0 to [0, 1]). oD0.a not written.
; Constants: c0..c6 = cA'r cA'g cA'b cB'r cB'g cB'b cC'.
; Temporaries: r1, r2, r3, r4. 10 instructions, 10 slots.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=unit_sphere10
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

dp4 r1.x, v0, cAr                 ; constant and linear terms
dp4 r1.y, v0, cAg
dp4 r1.z, v0, cAb
mul r2, v0.xyzx, v0.yzxx          ; (xy, yz, zx, xx)
dp4 r3.x, r2, cBr
dp4 r3.y, r2, cBg
dp4 r3.z, r2, cBb
mul r4.x, v0.y, v0.y              ; yy
mad r1.xyz, cC, r4.x, r1          ; + cC' yy
add oD0.xyz, r1, r3
