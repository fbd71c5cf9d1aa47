vs_1_1
dcl_position v0
def c0, 1, 0, 0, 1
mov oPos, v0
