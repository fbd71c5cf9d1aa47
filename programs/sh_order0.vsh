; sh_order0.vsh - irradiance from the constant SH band only (order 0): one instruction.
;
; Computes   E(n) = A0 L00 Y00 = c0 L00 per channel, the same in every direction: the best constant
; approximation (least squares over the sphere) of the nine-term irradiance, since the other bands
; average to zero. irrmap picks it when the environment's irradiance varies by less than the error
; target (a white furnace, an overcast sky seen through a diffuse surface).
; Inputs:    v0 = the normal (read by nothing; declared so the sh9 reference can feed it)
; Output:    oD0.rgb = E (raw; D3D would clamp oD0 to [0, 1]). oD0.a not written.
; Constants: c0 = (c0 R00, c0 G00, c0 B00, unused)   (PackShOrder in irradiance/sh/sh_order.h)
; Temporaries: none. 1 instruction, 1 slot.
; Fragment: no oPos (see sh9_irradiance.vsh).
;
; vs11: reference=sh9
; vs11: packing=order0
; vs11: normal=v0
; vs11: output=oD0
; vs11: constants=c0
; vs11: fragment=yes

vs.1.1

mov oD0.xyz, c0
