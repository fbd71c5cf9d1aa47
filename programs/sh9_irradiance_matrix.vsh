; sh9_irradiance_matrix.vsh - SH irradiance in Ramamoorthi & Hanrahan's matrix form (SIGGRAPH 2001,
; eq. 12): E(n) = n^T M n per channel, n = (x, y, z, 1), M a symmetric 4x4 matrix built from their
; constants k1..k5 and the nine coefficients (PackMatrix in irradiance/report/program_references.h):
;
;       | k1 L22    k1 L2-2   k1 L21   k2 L11          |   k1 = 0.429043  k2 = 0.511664
;   M = | k1 L2-2  -k1 L22    k1 L2-1  k2 L1-1         |   k3 = 0.743125  k4 = 0.886227
;       | k1 L21    k1 L2-1   k3 L20   k2 L10          |   k5 = 0.247708
;       | k2 L11    k2 L1-1   k2 L10   k4 L00 - k5 L20 |
;
; Each channel: m4x4 r, v0, c[M] gives M n, then dp4 with n gives n^T M n.
; Inputs:    v0 = the unit normal (x, y, z, 1)
; Output:    oD0.rgb = E(n) (raw, unclamped). oD0.a not written.
; Constants: c0..c3 = M red (rows), c4..c7 = M green, c8..c11 = M blue (12 registers).
; Temporaries: r0, r1, r2. 6 instructions, 15 slots.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=matrix
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

#define MR 0
#define MG 4
#define MB 8

m4x4 r0, v0, c[MR]                ; M_red n
dp4 oD0.x, r0, v0                 ; n^T M_red n
m4x4 r1, v0, c[MG]
dp4 oD0.y, r1, v0
m4x4 r2, v0, c[MB]
dp4 oD0.z, r2, v0
