// Read ports: how many different registers of one type a single instruction may read, per model. One
// implementation for every model's validator (vm/asm/validator.cc for vs_1_1, validator_models.cc for
// the later ones), driven by the table below.
// Sources: vs_1_1, ../shared/spec/vs_1_1.md §1.7 and §3.4 (one constant and one input per instruction,
// a macro's rows counted one at a time); vs_2_0, vs_2_x and vs_3_0, the "read ports" column of the
// D3D9 asm reference's register pages (dx9-graphics-reference-asm-vs-registers-vs-2-0, -vs-2-x,
// -vs-3-0): the number of different registers of the type that one instruction may read, and the
// "# reads/inst" column beside it.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/program.h"
#include "vm/core/shader_model.h"

namespace vs11 {

// Ports of each register type in each model, in ShaderModel order; 0: not counted (vs_1_1 counts only
// its constants and inputs, as its validator always has; the types a model lacks). `reads`: the reference
// tables' "# reads/inst" column, how many operands of the type one instruction may have, the same
// register or not (0: unlimited). Only operands count: the a0 or aL that indexes a relative operand is
// not counted (two relative operands already take two c# ports).
struct ReadPortLimit {
  RegisterFile file;
  std::string_view role;  // "constant", as messages say it
  std::array<int, kShaderModelCount> ports;
  std::array<int, kShaderModelCount> reads;
};
inline constexpr std::array kReadPortLimits = {
    //                                                   ports: vs_1_1 vs_2_0 vs_2_x vs_3_0, reads/inst
    ReadPortLimit{RegisterFile::kConst, "constant", {1, 1, 1, 1}, {0, 2, 2, 0}},
    ReadPortLimit{RegisterFile::kInput, "input", {1, 1, 1, 1}, {0, 0, 0, 0}},
    ReadPortLimit{RegisterFile::kTemp, "temporary", {0, 3, 3, 3}, {0, 0, 0, 0}},
    ReadPortLimit{RegisterFile::kAddress, "address", {0, 1, 1, 1}, {0, 2, 2, 0}},
    ReadPortLimit{RegisterFile::kConstBool, "boolean constant", {0, 1, 1, 1}, {0, 1, 1, 1}},
    ReadPortLimit{RegisterFile::kConstInt, "integer constant", {0, 1, 1, 1}, {0, 1, 1, 1}},
    ReadPortLimit{RegisterFile::kLoop, "loop counter", {0, 1, 1, 1}, {0, 2, 2, 0}},
    ReadPortLimit{RegisterFile::kPredicate, "predicate", {0, 0, 1, 1}, {0, 0, 1, 1}},
    ReadPortLimit{RegisterFile::kSampler, "sampler", {0, 0, 0, 1}, {0, 0, 0, 1}},
};

// One register type read through more ports than the model has, in one instruction (or in one row of
// a matrix macro's expansion).
struct ReadPortViolation {
  const ReadPortLimit* limit;
  bool reads;                          // over the reads/inst limit (else the ports)
  int allowed;                         // the model's limit for the type
  int row;                             // the macro row, 0 for ordinary instructions
  bool in_macro;                       // m*x*: the rows are counted one at a time
  std::vector<RegisterRef> registers;  // ports: the different registers read; reads: every operand
};

// At most one violation per register type, the first row that breaks it (ports before reads). Registers are different when
// their RegisterRefs differ: c0[a0.x] and c1[a0.y] are two registers (Wine's vs_2_0 case 11, which
// Microsoft's validator refuses), c0 and c0[a0.x] are two, and a relative operand repeated exactly
// (same offset, same index register and lane) is one. vs_2_0/vs_2_x sincos's src1 and src2 are the
// macro's constant operands (D3DSINCOSCONST1/2, two different constants by definition) and are not
// counted; the source it computes from is.
std::vector<ReadPortViolation> FindReadPortViolations(const Instruction& instruction, ShaderModel model);

// "reads two different constant registers (c0, c1); vs_1_1 allows one per instruction — copy one of them
// into a temporary first", or "reads constants 3 times (c0, c0, c0); vs_2_0 allows 2 constant reads per
// instruction ...", with the macro row when there is one; a later model's message names the reference
// page its limit comes from.
std::string DescribeReadPortViolation(const ReadPortViolation& violation, ShaderModel model);

}  // namespace vs11
