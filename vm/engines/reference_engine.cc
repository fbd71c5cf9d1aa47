#include "vm/engines/reference_engine.h"

#include <cmath>

#include "vm/core/semantics.h"

namespace vs11 {
namespace {

// Writes the lanes of `value` selected by the mask (and, for matrices, by the row count).
void StoreDest(const DestOperand& dest, const Vec4f& value, int lane_count, VertexState& state) {
  Vec4f* target = nullptr;
  switch (dest.reg.file) {
    case RegisterFile::kTemp:
      if (dest.reg.index < kTempRegisterCount) target = &state.temps[dest.reg.index];
      break;
    case RegisterFile::kAddress:
      if (dest.mask.has(0)) state.a0 = AddressFromFloat(value[0]);
      return;
    default:
      if (std::optional<int> slot = OutputSlotOf(dest.reg)) target = &state.outputs[*slot];
  }
  if (target == nullptr) return;
  for (int lane = 0; lane < lane_count; ++lane) {
    if (dest.mask.has(lane)) (*target)[lane] = value[lane];
  }
}

float DotOfWidth(int width, const Vec4f& a, const Vec4f& b) {
  return width == 3 ? semantics::Dot<float, 3>(a, b) : semantics::Dot<float, 4>(a, b);
}

template <class Semantics>
void Execute(const Instruction& instruction, const ConstantBank& constants, VertexState& state) {
  const OpcodeInfo& info = instruction.info();
  std::array<Vec4f, 3> src{};
  for (int s = 0; s < info.source_count(); ++s) src[s] = FetchSource(instruction.sources[s], 0, constants, state);
  Vec4f result{};
  if constexpr (requires { Semantics::Lane(0.0f, 0.0f, 0.0f); }) {
    for (int lane = 0; lane < 4; ++lane) result[lane] = Semantics::Lane(src[0][lane], src[1][lane], src[2][lane]);
  } else if constexpr (requires { Semantics::Scalar(0.0f); }) {
    result.fill(Semantics::Scalar(src[0][3]));
  } else if constexpr (requires { Semantics::Vector(Vec4f{}, Vec4f{}); }) {
    result = Semantics::Vector(src[0], src[1]);
  } else if (info.kind == ResultKind::kDotProduct) {
    result.fill(DotOfWidth(info.dot_width, src[0], src[1]));
  } else if (info.kind == ResultKind::kMatrix) {
    for (int row = 0; row < info.matrix_rows; ++row) {
      result[row] = DotOfWidth(info.dot_width, src[0], FetchSource(instruction.sources[1], row, constants, state));
    }
  } else {
    return;  // nop, dcl, def
  }
  StoreDest(instruction.dest, result, info.result_lanes(), state);
}

// Checks at compile time that each row's kernel has the form its ResultKind says.
template <class Semantics>
constexpr bool KernelMatchesKind(ResultKind kind) {
  if constexpr (requires { Semantics::Lane(0.0f, 0.0f, 0.0f); }) return kind == ResultKind::kComponentwise;
  if constexpr (requires { Semantics::Scalar(0.0f); }) return kind == ResultKind::kScalar;
  if constexpr (requires { Semantics::Vector(Vec4f{}, Vec4f{}); }) return kind == ResultKind::kVector;
  return kind == ResultKind::kDotProduct || kind == ResultKind::kMatrix || kind == ResultKind::kNoResult;
}
#define VS11_CHECK_KERNEL(name, mnemonic, token, shape, kind, ...) \
  static_assert(KernelMatchesKind<semantics::name##Semantics>(ResultKind::kind), mnemonic);
VS11_OPCODES(VS11_CHECK_KERNEL)
#undef VS11_CHECK_KERNEL

class ReferenceEngine final : public Engine {
 public:
  ReferenceEngine(const Program& program, const ConstantBank& api_constants)
      : program_(program), constants_(ApplyDefinitions(program, api_constants)),
        written_(WrittenOutputLanes(program)) {}

  void SetConstants(const ConstantBank& api_constants) override {
    constants_ = ApplyDefinitions(program_, api_constants);
  }

  void Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    std::vector<int> output_slots = outputs.registers();
    VertexState state;
    for (std::size_t i = 0; i < inputs.count(); ++i) {
      StartVertex(inputs, i, written_, state);
      RunVertex(program_, constants_, state);
      for (int slot : output_slots) {
        for (int c = 0; c < 4; ++c) outputs.lane(slot, c)[i] = state.outputs[slot][c];
      }
    }
  }

 private:
  Program program_;
  ConstantBank constants_;
  std::array<WriteMask, kOutputSlotCount> written_;
};

}  // namespace

Vec4f ReadRegister(const RegisterRef& reg, int row, const ConstantBank& constants, const VertexState& state) {
  long index = static_cast<long>(reg.index) + row;
  switch (reg.file) {
    case RegisterFile::kConst: return constants.Read(index + (reg.relative ? state.a0 : 0));
    case RegisterFile::kTemp: return index < kTempRegisterCount ? state.temps[index] : Vec4f{};
    case RegisterFile::kInput: return index < kInputRegisterCount ? state.inputs[index] : Vec4f{};
    default: return Vec4f{};  // outputs and a0 are not readable (the validator rejects such sources)
  }
}

Vec4f FetchSource(const SourceOperand& source, int row, const ConstantBank& constants, const VertexState& state) {
  Vec4f base = ReadRegister(source.reg, row, constants, state);
  Vec4f value;
  for (int lane = 0; lane < 4; ++lane) {
    float v = base[source.swizzle[lane]];
    if (source.negate) {
      v = -v;
#if defined(__x86_64__)
      // As the batch kernels' Negate: keeps the compiler from folding a + (-b) into a - b, which
      // would return b's NaN with its sign unflipped (seen once FetchSource became visible to
      // the tracer and GCC inlined it differently).
      asm("" : "+x"(v));
#endif
    }
    value[lane] = v;
  }
  return value;
}

void StartVertex(const VertexArrays& inputs, std::size_t vertex, const std::array<WriteMask, kOutputSlotCount>& written,
                 VertexState& state) {
  state.inputs.fill(kDefaultInput);
  for (int reg : inputs.registers()) {
    for (int c = 0; c < 4; ++c) state.inputs[reg][c] = inputs.lane(reg, c)[vertex];
  }
  state.temps = {};
  state.a0 = 0;
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    state.outputs[slot] = written[slot].bits() ? Vec4f{} : UnwrittenOutputValue(slot);
  }
}

int AddressFromFloat(float x) {
  float whole = std::floor(x);
  if (!(whole > -kAddressLimit)) return -kAddressLimit;  // NaN lands here too
  if (!(whole < kAddressLimit)) return kAddressLimit;
  return static_cast<int>(whole);
}

void RunVertex(const Program& program, const ConstantBank& constants, VertexState& state,
               InstructionObserver* observer) {
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    const Instruction& instruction = program.instructions[i];
    if (observer != nullptr) observer->Before(static_cast<int>(i), state);
    switch (instruction.opcode) {
#define VS11_EXECUTE_CASE(name, ...) \
  case Opcode::k##name: Execute<semantics::name##Semantics>(instruction, constants, state); break;
      VS11_OPCODES(VS11_EXECUTE_CASE)
#undef VS11_EXECUTE_CASE
    }
    if (observer != nullptr) observer->After(static_cast<int>(i), state);
  }
}

std::unique_ptr<Engine> MakeReferenceEngine(const Program& program, const ConstantBank& api_constants) {
  return std::make_unique<ReferenceEngine>(program, api_constants);
}

}  // namespace vs11
