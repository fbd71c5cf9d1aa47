; sh_order1.vsh - irradiance from the constant and linear SH bands (order 1): three instructions.
;
; Computes   E(n) = c0 L00 + c1 (L11 x + L1-1 y + L10 z) per channel = dp4((x, y, z, 1), cA), the
; paper's x1 without its - c3 L20 (band 2 is dropped whole; it averages to zero over the sphere, so
; this is the least-squares best linear fit of the nine-term irradiance). Exact for any
; environment whose radiance is a + b.n (a smooth gradient), whose band 2 is zero.
; Inputs:    v0 = the normal (x, y, z, 1)
; Output:    oD0.rgb = E(n) (raw). oD0.a not written.
; Constants: c0..c2 = cAr cAg cAb, cA = (c1 L11, c1 L1-1, c1 L10, c0 L00)   (PackShOrder)
; Temporaries: none. 3 instructions, 3 slots.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=order1
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

dp4 oD0.x, v0, c0
dp4 oD0.y, v0, c1
dp4 oD0.z, v0, c2
