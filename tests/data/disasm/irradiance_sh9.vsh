// Irradiance from nine spherical-harmonic coefficients: the listing of the paper with the errata of
// spec §9 corrected (the mad writes r2, the add reads r1 and r2). Constants as in the paper's Table 1.
#define cAr c0
#define cAg c1
#define cAb c2
#define cBr c3
#define cBg c4
#define cBb c5
#define cC  c6
#define cOne c7
#define cWorldViewProj c8

vs_1_1
dcl_position v0
dcl_normal v3
def c7, 1, 0, 0.5, -1e-3
m4x4 oPos, v0, cWorldViewProj
mov r0.xyz, v3
mov r0.w, cOne.x

dp4 r1.r, cAr, r0          ; x1 = constant + linear terms
dp4 r1.g, cAg, r0
dp4 r1.b, cAb, r0
mul r2, r0.xyzz, r0.yzzx   ; vB = (xy, yz, zz, zx)
dp4 r3.r, cBr, r2          ; x2 = four quadratic terms
dp4 r3.g, cBg, r2
dp4 r3.b, cBb, r2
mul r0.xy, r0.xy, r0.xy    ; (x^2, y^2)
add r0.x, r0.x, -r0.y      ; vC = x^2 - y^2
mad r2.rgb, cC.rgb, r0.x, r3.rgb
add r0.rgb, r1.rgb, r2.rgb
mov oD0.rgb, r0
mov oD0.a, cOne.x
