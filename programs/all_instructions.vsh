; all_instructions.vsh - uses every vs_1_1 instruction at least once (nop mov add sub mad mul rcp rsq
; dp3 dp4 min max slt sge exp log lit dst frc m4x4 m4x3 m3x4 m3x3 m3x2 expp logp, plus dcl and def),
; each in a way whose result reaches an output, so that the reference (all_instructions in
; irradiance/report/program_references.cc, the spec's formulas of section 3.3 in double) checks it.
;
; Inputs:    v0 = position (x, y, z, 1), v1 = normal (x, y, z, 1),
;            v2 = (u, v, s, t) with u in [-2, 3] and v in [0.1, 4]
; Outputs:
;   oPos = WORLDVIEWPROJ v0                                            m4x4
;   oD0  = DIFFUSE lit.y + SPECULAR lit.z, lit(N.L, N.H, -, POWER)     m4x3 m3x3 dp3 rsq mul sub mov lit mad
;          (N = normalised WORLD3x3 normal, L towards LIGHT_POS, H = the constant HALF)
;   oD1  = min(|n| + |n|, 0.5) per lane of v1, |n| once as sign(n) n with
;          sign from slt/sge and once as max(n, -n)                    slt sge mad mul max add min
;   oT0.xy = frc(TEX v2.xyz)                                           m3x2 frc
;   oT1.xy = (2^u, log2 |v|)                                           exp log
;   oT2  = expp(u) = (2^floor(u), u - floor(u), ~2^u, 1)               expp
;   oT3  = logp(v) = (exponent, mantissa, ~log2 |v|, 1)                logp
;   oT4  = M3X4 N (four dp3)                                           m3x4
;   oT5  = (1, d, d^2, 1/d), d = |LIGHT_POS - P|                       dst rcp
;   oFog = dp4(v0, FOG_PLANE) (raw; D3D clamps oFog to [0, 1])         dp4 nop
; Constants: c0..c3 WORLDVIEWPROJ, c4..c6 WORLD, c7 LIGHT_POS, c8..c11 M3X4, c12..c13 TEX,
;            c14 DIFFUSE, c15 SPECULAR, c16.w POWER, c17 HALF (unit), c18 FOG_PLANE,
;            c20 = (0.5, 2, -1, 0) by def
; Tolerance: 1e-5 relative, but 1e-4 for oT2 and oT3: the z lanes of expp and logp are partial
; precision (the low 8 mantissa bits cleared, relative error up to 2^-15 = 3.1e-5). exp, log and
; lit's pow are approximations too, but good to about 22 bits, well inside 1e-5.
;
; vs11: reference=all_instructions
; vs11: position=v0
; vs11: normal=v1
; vs11: texcoord=v2
; vs11: output=oD0
; vs11: constants=c0

vs_1_1

dcl_position v0
dcl_normal v1
dcl_texcoord v2

def c20, 0.5, 2, -1, 0            ; (half, two, minus one, zero)

#define WORLDVIEWPROJ 0
#define WORLD 4
#define LIGHT_POS c7
#define M3X4 8
#define TEX 12
#define DIFFUSE c14
#define SPECULAR c15
#define POWER c16
#define HALF c17
#define FOG_PLANE c18
#define K c20

nop
m4x4 oPos, v0, c[WORLDVIEWPROJ]

; lighting: oD0
m4x3 r0.xyz, v0, c[WORLD]         ; P (world)
m3x3 r1.xyz, v1, c[WORLD]         ; N (world)
dp3 r1.w, r1, r1
rsq r1.w, r1.w
mul r1.xyz, r1, r1.w              ; unit N
sub r2.xyz, LIGHT_POS, r0         ; D = light - P
dp3 r2.w, r2, r2                  ; d^2
rsq r3.w, r2.w                    ; 1/d
mul r2.xyz, r2, r3.w              ; L
dp3 r6.x, r1, r2                  ; N.L
dp3 r6.y, r1, HALF                ; N.H
mov r6.w, POWER.w
lit r7, r6                        ; (1, max(N.L, 0), (N.H)^POWER or 0, 1)
mul r8, r7.y, DIFFUSE
mad oD0, r7.z, SPECULAR, r8

; distance vector and reciprocal: oT5
dst r4, r2.w, r3.w                ; (1, d, d^2, 1/d)
mov oT5.xyz, r4
rcp oT5.w, r4.y                   ; 1/d again, by rcp

; comparisons: oD1
slt r9, v1, K.w                   ; 1 where n < 0
sge r10, v1, K.w                  ; 1 where n >= 0
mad r9, r9, K.z, r10              ; sign(n) = -1 or +1
mul r9, r9, v1                    ; |n|
max r10, v1, -v1                  ; |n|
add r9, r9, r10                   ; 2 |n|
min oD1, r9, K.x                  ; min(2 |n|, 0.5)

; texture-coordinate maths: oT0 .. oT4
m3x2 r11.xy, v2, c[TEX]
frc r11.xy, r11                   ; fraction of the transformed (u, v)
mov oT0.xy, r11
exp oT1.x, v2.x                   ; 2^u (full precision)
log oT1.y, v2.y                   ; log2 |v| (full precision)
expp oT2, v2.x                    ; (2^floor(u), frac(u), 2^u partial, 1)
logp oT3, v2.y                    ; (exponent, mantissa, log2 |v| partial, 1)
m3x4 oT4, r1, c[M3X4]             ; four dp3 with N

dp4 oFog, v0, FOG_PLANE
