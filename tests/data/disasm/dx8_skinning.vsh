; A DX8-style shader: vs.1.1 without dcl, #define'd register names, c[NAME + n] spellings,
; relative addressing into a bone palette, scalar outputs and negated swizzles.
#define CV_CONSTANTS    0
#define CV_VIEWPROJ     1
#define CV_BONES        10
#define V_POSITION      v0
#define V_BONE_INDEX    v1
#define V_TEXCOORD      v2

vs.1.1
def c[CV_CONSTANTS], 0, 1, 0.5, 3
mul r0.x, V_BONE_INDEX.x, c[CV_CONSTANTS].w     // 3 registers per bone
mov a0.x, r0.x
m4x3 r1.xyz, V_POSITION, c[a0.x + CV_BONES]
mov r1.w, c[CV_CONSTANTS].y
m4x4 oPos, r1, c[CV_VIEWPROJ]
dp3 r2.x, c[CV_BONES + 0 + a0.x], c[CV_BONES + a0.x].wzyx
rcp r2.w, r1.w
mov oFog.x, r2.w
mov oPts, c[CV_CONSTANTS].z
mov oD0, c[CV_CONSTANTS].yyyx
mov oT0.xy, -V_TEXCOORD.yx
