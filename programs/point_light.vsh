; point_light.vsh - classic per-vertex lighting by one point light with distance attenuation, the
; DX8 way: the distance vector comes from dst, the reciprocal distance from rsq.
;
;   P = WORLD v0, N = normalize(WORLD3x3 v1), D = LIGHT_POS - P, d = |D|, L = D / d
;   dst((d^2), (1/d)) = (1, d, d^2, 1/d);  att = 1 / dp3((1, d, d^2), ATTEN) = 1 / (a0 + a1 d + a2 d^2)
;   oD0 = AMBIENT + DIFFUSE * max(N.L, 0) * att          oPos = WORLDVIEWPROJ v0
; D3D clamps oD0 to [0, 1]; the vs11 machine reports raw values.
; Inputs:    v0 = position (x, y, z, 1), v1 = normal (x, y, z)
; Outputs:   oPos, oD0 (rgba)
; Constants: c0..c3 WORLDVIEWPROJ, c4..c6 WORLD (4x3, rotation with uniform scale + translation),
;            c7 LIGHT_POS (world), c8 ATTEN = (a0, a1, a2, 0), c9 DIFFUSE, c10 AMBIENT
; Temporaries: r0..r6. Reference: point_light (irradiance/report/program_references.cc).
;
; vs11: reference=point_light
; vs11: position=v0
; vs11: normal=v1
; vs11: output=oD0
; vs11: constants=c0

vs_1_1

dcl_position v0
dcl_normal v1

#define WORLDVIEWPROJ 0
#define WORLD 4
#define LIGHT_POS c7
#define ATTEN c8
#define DIFFUSE c9
#define AMBIENT c10

m4x4 oPos, v0, c[WORLDVIEWPROJ]
m4x3 r0.xyz, v0, c[WORLD]         ; P (world)
m3x3 r1.xyz, v1, c[WORLD]         ; N (world, not yet unit)
dp3 r1.w, r1, r1
rsq r1.w, r1.w
mul r1.xyz, r1, r1.w              ; N
add r2.xyz, LIGHT_POS, -r0        ; D = light - P
dp3 r2.w, r2, r2                  ; d^2
rsq r3.w, r2.w                    ; 1/d
mul r2.xyz, r2, r3.w              ; L
dst r4, r2.w, r3.w                ; (1, d, d^2, 1/d)
dp3 r4.w, r4, ATTEN               ; a0 + a1 d + a2 d^2
rcp r4.w, r4.w                    ; attenuation
dp3 r5.x, r1, r2                  ; N.L
max r5.x, r5.x, ATTEN.w           ; max(N.L, 0)
mul r5.x, r5.x, r4.w              ; max(N.L, 0) * att
mul r6, r5.x, DIFFUSE
add oD0, r6, AMBIENT
