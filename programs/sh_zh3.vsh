; sh_zh3.vsh - order 1 plus one zonal quadratic term (ZH3, Roughton, Sloan, Silvennoinen, Iwanicki
; and Shirley, "ZH3: Quadratic Zonal Harmonics", i3D 2024): six instructions.
;
; Band 2 is replaced by its zonal part around one axis a shared by the three channels: the
; direction of the luminance of the linear band (Rec. 709 weights of L11, L1-1, L10). Per channel
; the zonal coefficient z = sqrt(4 pi / 5) sum_m L2m y2m(a) is band 2 projected on the zonal
; harmonic along a, whose irradiance is A2 z n3 (3 (a.n)^2 - 1). So
;   E(n) = dp4((x, y, z, 1), cA) + cZ.rgb * (a.n)^2
;   cA = (c1 L11, c1 L1-1, c1 L10, c0 L00 - A2 n3 z),  cZ = 3 A2 n3 z per channel,  cAxis = (a, 0)
; (PackShOrder in irradiance/sh/sh_order.h). Exact when band 2 is zonal around a (one light, or a
; sky around its sun's axis); loses band 2's other parts.
; Inputs:    v0 = the unit normal (x, y, z, 1)
; Output:    oD0.rgb = E(n) (raw). oD0.a not written.
; Constants: c0..c2 = cAr cAg cAb, c3 = cAxis, c4 = cZ.
; Temporaries: r0, r1. 6 instructions, 6 slots.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=zh3
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

dp3 r0.x, v0, c3                  ; t = a.n
mul r0.x, r0.x, r0.x              ; t^2
dp4 r1.x, v0, c0                  ; constant and linear terms
dp4 r1.y, v0, c1
dp4 r1.z, v0, c2
mad oD0.xyz, c4, r0.x, r1         ; + cZ t^2
