; sh9_irradiance_basis.vsh - SH irradiance the naive way: evaluate the nine basis functions of eq. (5)
; and sum them with the weights A_l L_lm of eq. (6). A yardstick for the paper's 11 instructions.
;
;   B0 = (y00, y1-1, y10, y11)  = (n0, n1 y, n1 z, n1 x)
;   B1 = (y2-2, y2-1, y20, y21) = (n2 xy, n2 yz, n3 (3 z^2 - 1), n2 zx)
;   y22 = n4 (x^2 - y^2)
;   E_ch = dp4(B0, W0_ch) + dp4(B1, W1_ch) + y22 W2.ch
; Inputs:    v0 = the unit normal (x, y, z, 1)
; Output:    oD0.rgb = E(n) (raw, unclamped). oD0.a not written.
; Constants (PackBasis in irradiance/report/program_references.h):
;   c0 = (n0, n1, n2, n3)   c1 = (n4, 3, -1, 0)
;   c2..c4 = W0 per channel = (A0 L00, A1 L1-1, A1 L10, A1 L11)
;   c5..c7 = W1 per channel = (A2 L2-2, A2 L2-1, A2 L20, A2 L21)
;   c8 = W2 = (A2 R22, A2 G22, A2 B22, 0)
; Temporaries: r0..r4. 15 instructions, 15 slots, 9 constants.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=basis
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

#define K0  c[0]
#define K1  c[1]
#define W0R c[2]
#define W0G c[3]
#define W0B c[4]
#define W1R c[5]
#define W1G c[6]
#define W1B c[7]
#define W2  c[8]

mul r0, v0.wyzx, K0.xyyy          ; B0 = (n0, n1 y, n1 z, n1 x)
mul r1, v0.xyzz, v0.yzzx          ; (xy, yz, zz, zx)
mad r1.z, r1.z, K1.y, K1.z        ; 3 zz - 1
mul r1, r1, K0.zzwz               ; B1 = (n2 xy, n2 yz, n3 (3 zz - 1), n2 zx)
mul r2.xy, v0, v0                 ; (x^2, y^2)
add r2.x, r2.x, -r2.y             ; x^2 - y^2
mul r2.x, r2.x, K1.x              ; y22 = n4 (x^2 - y^2)
dp4 r3.x, r0, W0R                 ; bands 0 and 1
dp4 r3.y, r0, W0G
dp4 r3.z, r0, W0B
dp4 r4.x, r1, W1R                 ; band 2 without y22
dp4 r4.y, r1, W1G
dp4 r4.z, r1, W1B
mad r3.xyz, W2, r2.x, r3          ; + y22 A2 L22
add oD0.xyz, r3, r4
