// Reads of unwritten temporaries, a0 and p0 in a program of vs_2_0, vs_2_x or vs_3_0, along its flow
// control (the validator's rule for those models: vm/asm/validator_models.cc). The D3D9 reference's temporary
// register page: "A temporary register must be initialized before it is used ... Vertex shaders that
// read a value from a temporary register before writing to it will fail the Direct3D API call to create
// the vertex shader."
//
// How the paths are followed:
// - Each read is checked against the lanes that are written on every path from the start (must) and on
//   some path (may). Lanes no path writes: an error (kUninitializedRegister when no lane of the register
//   is written on any path, kUninitializedLanes when some are), as vs_1_1's DX9 rule. Lanes only some
//   paths write: a warning (kUninitializedLanes) that says so — the reference speaks of a register read
//   before it is written, and on such a read the program may well have written it.
// - if/else/endif (on b#, p0 or a comparison): both sides are possible; without else, the skipped side is.
// - loop/endloop, rep/endrep: the body may run zero times (a count of 0), so after the loop only what was
//   written before it is certain. Reads in the body are checked against its first iteration: a register
//   the body writes only after the read is unwritten then, an error (the message says so).
// - break ends its path (to after the loop); breakc and breakp may. A predicated write may not happen.
// - call l#: each subroutine is checked once, from the lanes written before every one of its calls
//   (must: all of them; may: any of them), and a call adds what the subroutine writes on every path
//   through it (callnz: only "may"). A subroutine no call reaches is not checked (it never runs).
// - sgn's src1 and src2 are scratch registers: they are not read, and their contents are undefined
//   afterwards: a read of one before it is written again (on some path) is a warning.
// The lanes each source reads are vs_1_1's (ConsumedLanes, §6.3) for its instructions and, for the later
// ones: crs x, y, z as the cross product needs them; nrm x, y, z and the written lanes; pow and sincos's
// source the one lane its swizzle's w selects (both need a replicate swizzle); texldl every lane (w is
// the level of detail); if_comp and break_comp the lane their swizzle's x selects (README "Shader
// models": the engines compare the x lanes of the replicate-swizzled sources).
// a0 and p0 are followed the same way, as two more registers: mova writes a0's lanes, setp p0's; a
// relative operand reads the a0 lane it indexes by, a condition (if, callnz, breakp) its p0 lane, and a
// predicated instruction the p0 lanes its written lanes take through the predicate's swizzle. Their
// findings say which instruction writes them; a0's carry kAddressNotWritten (vs_1_1's code for the same
// mistake, whose straight-line check in validator.cc stays as it is).
#pragma once

#include <string>
#include <vector>

#include "vm/core/diagnostic.h"
#include "vm/core/program.h"

namespace vs11 {

struct TemporaryReadFinding {
  int index;  // the reading instruction
  Severity severity;
  DiagnosticCode code;  // kUninitializedRegister or kUninitializedLanes
  std::string message;  // what is read and why it is unwritten, without the instruction
};

// The findings in instruction order. Tolerates broken flow control (the validator reports that): an
// unmatched closer is ignored and an unclosed block ends with the program.
std::vector<TemporaryReadFinding> FindUnwrittenTemporaryReads(const Program& program);

}  // namespace vs11
