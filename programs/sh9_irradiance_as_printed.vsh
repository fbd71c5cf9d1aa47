; sh9_irradiance_as_printed.vsh - the paper's 11-instruction SH irradiance listing (Ai, Peng & Zhang
; 2008, section 3.2) exactly as printed, made legal vs_1_1 with the smallest change. It is WRONG on
; purpose: `vs11 verify` must show it failing, and by how much.
;
; The smallest change: vs_1_1 vertex data arrives in input registers and results must leave through
; output registers, so a first `mov r0, v0` copies the normal (x, y, z, 1) into r0, where the listing
; expects it, and a last `mov oD0, r0` sends the listing's result out. The 11 printed instructions in
; between are untouched (13 instructions in all).
;
; What it computes (../shared/spec/vs_1_1.md section 9): the `mad` overwrites r1 (the constant and
; linear terms x1), and the final `add` sums it with r2, the raw products, so the result is
;   x2 + cC.rgb (x^2 - y^2) + (xy, yz, zz)
; instead of x1 + x2 + cC.rgb (x^2 - y^2): the constant and linear bands are lost.
; Inputs:    v0 = the unit normal (x, y, z, 1)
; Output:    oD0 (rgb compared; oD0.a = r1.b + r2.b, since .rgb reads as .rgbb). Raw, not clamped.
; Constants: c0..c6 = cAr cAg cAb cBr cBg cBb cC (the paper's Table 1, PackTable1).
; Temporaries: r0, r1, r2, r3.
; Fragment: no oPos (see sh9_irradiance.vsh).
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

mov r0, v0                        ; added: the normal into r0, where the listing reads it

dp4 r1.r, r0, cAr                 ; --- the listing as printed ---
dp4 r1.g, r0, cAg
dp4 r1.b, r0, cAb
mul r2, r0.xyzz, r0.yzzx
dp4 r3.r, r2, cBr
dp4 r3.g, r2, cBg
dp4 r3.b, r2, cBb
mul r0.xy, r0.xy, r0.xy
add r0.x, r0.x, -r0.y
mad r1.rgb, cC.rgb, r0.x, r3.rgb
add r0, r1.rgb, r2.rgb            ; --- end of the listing ---

mov oD0, r0                       ; added: the listing's result out
