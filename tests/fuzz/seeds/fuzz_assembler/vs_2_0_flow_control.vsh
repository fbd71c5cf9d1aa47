vs_2_0
dcl_position v0
defi i0, 3, 0, 1, 0
defb b0, true
mov r0, c0
loop aL, i0
add r0, r0, c1[aL]
endloop
rep i0
if !b0
mul r0, r0, c2
else
sincos r1.xy, r0.x, c3, c4
endif
endrep
callnz l1, b0
mov oPos, r0
ret
label l1
mova a0.y, c3
mov r1, -c4[a0.y].x
ret
