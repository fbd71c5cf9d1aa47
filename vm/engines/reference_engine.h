// The scalar reference interpreter: one vertex at a time, float32, exactly the spec's pseudo-code
// (§3.1: all sources fetched before the masked store). The yardstick every other engine must equal.
#pragma once

#include <memory>

#include "vm/core/machine.h"
#include "vm/core/operands.h"
#include "vm/core/texture_sampling.h"

namespace vs11 {

// The complete register state of one vertex while a program runs.
struct VertexState {
  std::array<Vec4f, kInputRegisterCount> inputs;
  std::array<Vec4f, kTempRegisterCount> temps{};
  std::array<Vec4f, kOutputSlotCount> outputs{};
  int a0 = 0;
};

// a0.x from a float: vm/core/operands.h, shared with the jit.
using semantics::AddressFromFloat;
using semantics::kAddressLimit;

// Sees the register state around every instruction RunVertex executes (the shader debugger in
// vm/engines/trace.h). It only observes: the arithmetic stays in vm/core/semantics.h, run by RunVertex.
class InstructionObserver {
 public:
  virtual ~InstructionObserver() = default;
  virtual void Before(int instruction_index, const VertexState& state) = 0;
  virtual void After(int instruction_index, const VertexState& state) = 0;
};

// Runs `program` (def constants already folded into `constants`) on one vertex, its products under
// `rules`.
void RunVertex(const Program& program, const ConstantBank& constants, VertexState& state,
               InstructionObserver* observer = nullptr, FloatRules rules = FloatRules::kD3d9);

// Vertex `vertex` of `inputs` loaded into `state` as the engine starts it: unsupplied inputs read
// kDefaultInput, temporaries and a0 0, outputs the program never writes UnwrittenOutputValue
// (`written` = WrittenOutputLanes(program)).
void StartVertex(const VertexArrays& inputs, std::size_t vertex, const std::array<WriteMask, kOutputSlotCount>& written,
                 VertexState& state);

// What the engine reads for a register (row > 0: the next registers of a matrix operand; relative
// constants through state.a0; outputs and a0 read 0), and for a source operand after its swizzle and
// negation.
Vec4f ReadRegister(const RegisterRef& reg, int row, const ConstantBank& constants, const VertexState& state);
Vec4f FetchSource(const SourceOperand& source, int row, const ConstantBank& constants, const VertexState& state);

// texldl's texture reader (vm/core/texture_sampling.h) for one vertex's float lanes: the textures
// bound in a constant bank. (Not in texture_sampling.h, which the batch kernels compile per target.)
struct BankTextures {
  const ConstantBank& bank;
  TextureShape Shape(int sampler) const {
    return sampler >= 0 && sampler < kVertexSamplerCount ? ShapeOf(bank.sampler(sampler)) : TextureShape{};
  }
  Vec4f Texel(int sampler, std::int32_t index) const {
    const VertexTexture& texture = *bank.sampler(sampler).texture;
    const int channels = ChannelCount(texture.format);
    Vec4f texel{};
    for (int c = 0; c < channels; ++c) texel[c] = texture.texels[static_cast<std::size_t>(index) * channels + c];
    return texel;
  }
};

std::unique_ptr<Engine> MakeReferenceEngine(const Program& program, const ConstantBank& api_constants,
                                            FloatRules rules = FloatRules::kD3d9);

}  // namespace vs11
