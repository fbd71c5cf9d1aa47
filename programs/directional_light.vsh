; directional_light.vsh - classic per-vertex lighting by one directional light: ambient + Lambert
; diffuse in oD0, Blinn-Phong specular (half vector, exponent) in oD1, through `lit`.
;
;   P = WORLD v0, N = normalize(WORLD3x3 v1), V = normalize(EYE - P), H = normalize(V + L)
;   lit(N.L, N.H, -, POWER) = (1, max(N.L, 0), N.L > 0 && N.H > 0 ? (N.H)^POWER : 0, 1)
;   oD0 = AMBIENT + DIFFUSE * lit.y        oD1 = SPECULAR * lit.z        oPos = WORLDVIEWPROJ v0
; WORLD is a rotation with uniform scale plus a translation, so its 3x3 part transforms normals
; (after normalisation). D3D clamps oD0/oD1 to [0, 1]; the vs11 machine reports raw values.
; Inputs:    v0 = position (x, y, z, 1), v1 = normal (x, y, z)
; Outputs:   oPos, oD0 (rgba), oD1 (rgba)
; Constants: c0..c3 WORLDVIEWPROJ, c4..c6 WORLD (4x3), c7 L (unit, towards the light),
;            c8 EYE (world), c9 DIFFUSE, c10 SPECULAR, c11 AMBIENT, c12.w POWER (specular exponent)
; Temporaries: r0..r5. Reference: directional_light (irradiance/report/program_references.cc).
; The exponent goes through lit's pow approximation (exp2(power log2 N.H)); the error stays well
; below the 1e-5 tolerance.
;
; vs11: reference=directional_light
; vs11: position=v0
; vs11: normal=v1
; vs11: output=oD0
; vs11: constants=c0

vs_1_1

dcl_position v0
dcl_normal v1

#define WORLDVIEWPROJ 0
#define WORLD 4
#define LIGHT_DIR c7
#define EYE c8
#define DIFFUSE c9
#define SPECULAR c10
#define AMBIENT c11
#define POWER c12

m4x4 oPos, v0, c[WORLDVIEWPROJ]
m4x3 r0.xyz, v0, c[WORLD]         ; P (world)
m3x3 r1.xyz, v1, c[WORLD]         ; N (world, not yet unit)
dp3 r1.w, r1, r1
rsq r1.w, r1.w
mul r1.xyz, r1, r1.w              ; N
add r2.xyz, EYE, -r0              ; P to the eye
dp3 r2.w, r2, r2
rsq r2.w, r2.w
mad r2.xyz, r2, r2.w, LIGHT_DIR   ; V + L
dp3 r2.w, r2, r2
rsq r2.w, r2.w
mul r2.xyz, r2, r2.w              ; H
dp3 r3.x, r1, LIGHT_DIR           ; N.L
dp3 r3.y, r1, r2                  ; N.H
mov r3.w, POWER.w                 ; exponent
lit r4, r3                        ; (1, diffuse, specular, 1)
mul r5, r4.y, DIFFUSE
add oD0, r5, AMBIENT
mul oD1, r4.z, SPECULAR
