// Static checks a vs_1_1 program must pass before it may run: our re-implementation of what the D3D
// runtime and the D3DX assembler check (../shared/spec/vs_1_1.md §6, with §1 and §3).
//
// The validator works on a decoded Program, so it serves both the assembler (which fills
// Program::source_locs, letting diagnostics point at .vsh lines) and bytecode loaded from disk (no
// source map: messages then name the instruction index instead).
#pragma once

#include <cstdint>

#include "vm/core/diagnostic.h"
#include "vm/core/isa.h"
#include "vm/core/program.h"

namespace vs11 {

struct ValidatorOptions {
  // D3DCAPS9.MaxVertexShaderConst (§1.4): constants c0 .. c[constant_count - 1] exist. Must be >= 1.
  int constant_count = kDefaultConstantCount;
  // kDx9: every v# read needs a dcl and dcls may not repeat (§1.2, §6.2.8). kDx8: no dcl needed.
  // kAuto: DX9 rules when the program contains any dcl, DX8 rules otherwise.
  enum class Dialect { kAuto, kDx8, kDx9 } dialect = Dialect::kAuto;
  // A complete vertex shader must write oPos (§6.3). Off for a fragment: a piece of a shader checked on
  // its own, such as the paper's 11-instruction irradiance program.
  bool require_position = true;
  // A read of lanes that nothing wrote, of a temporary that was partly written (`m4x3 r4, ...` writes
  // .xyz, then `mul r4, r4, v1` reads r4.w), is a warning under DX8 rules, as the D3D8 runtime accepted
  // it; strict makes it an error. Under DX9 rules it is always an error, as in Microsoft's D3D9
  // validator (spec §1.3). A temporary that nothing wrote at all is an error either way.
  bool strict = false;
};

// Checks `program` against every rule of §6 and returns all problems found (errors and warnings);
// the program may be run when the result has no errors. Each diagnostic's loc is
// program.LocOf(instruction index), or just the file for whole-program problems (missing oPos,
// version). When an instruction has no source location the message starts with
// "instruction N (mnemonic)". Bad input never asserts.
// Programs of vs_2_0, vs_2_x and vs_3_0 get their models' rules (ValidateLaterModel).
Diagnostics Validate(const Program& program, const ValidatorOptions& options = {});

// The rules of vs_2_0, vs_2_x and vs_3_0 (vm/asm/validator_models.cc): each model's register counts,
// instruction slots and nesting depths (vm/core/shader_model.h; vs_2_x with the maximal D3DVS20CAPS),
// matched if/else/endif, loop/endloop and rep/endrep, break inside a loop, labels that exist and are
// defined once outside any block, calls neither recursive nor deeper than the model allows, ret outside
// open blocks, aL only inside a loop (in the main program), the operands each instruction takes, the
// read ports of each register type, temporaries read before any path writes them (errors; lanes only
// some paths write: warnings), every v# read declared, and oPos written (vs_3_0: an output declared with
// dcl_position).
Diagnostics ValidateLaterModel(const Program& program, const ValidatorOptions& options);

// The lanes (bit i = lane i, as in WriteMask) of the register named by source `operand` that an
// instruction described by `info` reads when it writes `dest_mask` and the operand carries
// `swizzle` (§6.3). For the matrix operand of m*x* the result is what each row register is read in.
// Used by the uninitialized-temporary check; exposed for tests and for tools that track liveness.
std::uint8_t ConsumedLanes(const OpcodeInfo& info, int operand, WriteMask dest_mask, Swizzle swizzle);

}  // namespace vs11
