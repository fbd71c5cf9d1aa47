// The shader debugger behind `vs11 run --trace`: one vertex through a program on the reference
// engine, instruction by instruction, with what each instruction read and wrote. The record is taken
// by observing the register state before and after each instruction (InstructionObserver in
// vm/engines/reference_engine.h); the arithmetic itself is the engine's, so a trace cannot disagree with it.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/machine.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {

// One register an instruction read: a source operand, or one row of a matrix operand.
struct TracedRead {
  static constexpr int kPredicateOperand = -1;  // `source` of a predicated instruction's (p0) read
  int source = 0;          // which source operand (0-2), or kPredicateOperand
  int row = 0;             // matrix row: register source.reg + row
  RegisterRef register_read;  // the register actually read (a relative constant resolved with a0)
  Vec4f raw{};             // that register as stored
  Vec4f value{};           // what the instruction used: swizzled and negated
  // Later models: b# or p0 (lanes 1 true, 0 false): a condition's value in every lane, the
  // predicate's per lane, `!` applied; raw: b# in lane x, or p0's four lanes.
  bool boolean = false;
  std::string address;     // later models: what a relative operand was read through ("aL = 4")
};

// The destination an instruction wrote. `written` holds the lanes the mask and the instruction's
// result allowed; the other lanes kept their value (before == after there).
struct TracedWrite {
  WriteMask written;
  Vec4f before{};
  Vec4f after{};  // for a0: lane x holds the integer address (later models: each lane its own)
  WriteMask predicated_off{0};  // lanes the mask allowed but the predicate turned off (kept)
};

struct TraceStep {
  int instruction_index = 0;  // into Program::instructions
  std::vector<TracedRead> reads;
  std::optional<TracedWrite> write;
  std::string note;  // later models' flow control: what it decided ("3 iterations", "calls l0 at line 9")
};

// An output register at the end of the vertex, by the reference engine and by the engine compared.
struct TracedOutput {
  int slot = 0;  // OutputSlot order
  Vec4f reference{};
  Vec4f engine{};
  bool identical() const;  // bit for bit, lane by lane
};

struct VertexTrace {
  std::size_t vertex = 0;
  std::vector<int> input_registers;  // the inputs supplied, in register order
  VertexState start;                 // the state before the first instruction
  std::vector<TraceStep> steps;      // executed instructions only (dcl and def are skipped)
  VertexState end;
  std::vector<TracedOutput> outputs;  // filled by CompareOutputs
  bool identical() const;            // every output equal to the engine's
};

// Runs vertex `vertex` of `inputs` (vertex < inputs.count()) on the reference engine, its products
// under `rules`, and records it. `api_constants` are the API's constants (def lines are applied here,
// as every engine does). A later model's program is traced by TraceFlowVertex (vm/engines/flow_trace.h):
// every instruction in the order it runs, loops once per iteration, branches not taken left out.
VertexTrace TraceVertex(const Program& program, const ConstantBank& api_constants, const VertexArrays& inputs,
                        std::size_t vertex, FloatRules rules = FloatRules::kD3d9);

// Fills trace.outputs from another engine's run over the same inputs (outputs from MakeOutputArrays).
void CompareOutputs(const VertexArrays& engine_outputs, VertexTrace& trace);

// Lines of the source files named in a program's source locations, read from disk once each.
class SourceLines {
 public:
  // The line without its line break; nullopt when the file cannot be read or is shorter.
  std::optional<std::string> Line(const SourceLoc& loc);

 private:
  std::map<std::string, std::optional<std::vector<std::string>>> files_;
};

// The trace as text for a person: each executed instruction as its source line (file:line, and the
// instruction it assembled to when the text differs, e.g. through a macro; the disassembly alone for
// bytecode), its reads (swizzled and negated value, then the raw register) and its write (lanes the
// mask kept shown as "kept"), then the outputs of both engines side by side.
std::string FormatTraceText(const Program& program, const VertexTrace& trace, std::string_view engine_name,
                            SourceLines& sources);

// "(1, 0.5, -2, 1)" with the shortest text that reads back to each float.
std::string FormatVec4(const Vec4f& value);
// The source text an instruction came from, comments and surrounding blanks removed ("" if unknown).
std::string SourceStatement(std::string_view line);

// The trace as one JSON object (the text of one entry of `vs11 run --trace-json`'s "vertices"):
// {"vertex", "identical", "inputs": {"v0": [x, y, z, w]}, "steps": [{"index", "instruction", "file",
// "line", "source" (when assembled from text), "reads": [...], "write": {...}}], "outputs": [...]}.
// NaN and infinite lanes are the strings "nan", "inf" and "-inf" (JSON numbers cannot hold them).
std::string TraceJson(const Program& program, const VertexTrace& trace, SourceLines& sources);

}  // namespace vs11
