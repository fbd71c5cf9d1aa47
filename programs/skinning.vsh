; skinning.vsh - matrix-palette skinning with two bones per vertex, the DX8 way: each bone's index
; goes to a0.x and selects a 4x3 matrix with relative addressing, c[a0.x + PALETTE].
;
;   P = w0 B[i0] v0 + w1 B[i1] v0 (B = 4x3 bone matrices), N = normalize(w0 B3[i0] v3 + w1 B3[i1] v3)
;   oPos = VIEWPROJ (P, 1)       oD0 = DIFFUSE * max(N.L, 0)
; Inputs:    v0 = position (x, y, z, 1), v1 = blend weights (w0, w1), v2 = blend indices premultiplied
;            by 3 (3 i0, 3 i1), as floats (mov a0.x floors them), v3 = normal (x, y, z)
; Outputs:   oPos, oD0 (rgba; raw, D3D would clamp to [0, 1])
; Constants: c0..c3 VIEWPROJ, c4 L (unit, towards the light, w = 0), c5 DIFFUSE,
;            c6..c29 PALETTE: bone b in c[6 + 3b] .. c[8 + 3b], 8 bones
; Temporaries: r0..r4. Reference: skinning (irradiance/report/program_references.cc).
;
; vs11: reference=skinning
; vs11: position=v0
; vs11: weights=v1
; vs11: indices=v2
; vs11: normal=v3
; vs11: output=oD0
; vs11: constants=c0

vs_1_1

dcl_position v0
dcl_blendweight v1
dcl_blendindices v2
dcl_normal v3

#define VIEWPROJ 0
#define LIGHT_DIR c4
#define DIFFUSE c5
#define PALETTE 6

mov a0.x, v2.x                    ; first bone
m4x3 r0.xyz, v0, c[a0.x + PALETTE]
m3x3 r2.xyz, v3, c[a0.x + PALETTE]
mul r0.xyz, r0, v1.x
mul r2.xyz, r2, v1.x
mov a0.x, v2.y                    ; second bone
m4x3 r1.xyz, v0, c[a0.x + PALETTE]
m3x3 r3.xyz, v3, c[a0.x + PALETTE]
mad r0.xyz, r1, v1.y, r0          ; blended position
mad r2.xyz, r3, v1.y, r2          ; blended normal
mov r0.w, v0.w                    ; w = 1
m4x4 oPos, r0, c[VIEWPROJ]
dp3 r2.w, r2, r2
rsq r2.w, r2.w
mul r2.xyz, r2, r2.w              ; N
dp3 r4.x, r2, LIGHT_DIR           ; N.L
max r4.x, r4.x, LIGHT_DIR.w       ; max(N.L, 0)
mul oD0, r4.x, DIFFUSE
