vs_2_x
dcl_position v0
setp_gt p0, v0, c0
(!p0) add r0, v0, c1
(p0.x) mov r0, v0
rep i0
break_ne r0.x, c0.x
breakp p0.w
endrep
if_lt r0.x, c0.y
mov r0, c1
endif
mov oPos, r0
