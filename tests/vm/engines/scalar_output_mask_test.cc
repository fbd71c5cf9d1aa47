// oFog and oPts keep the write mask the source gives (Microsoft's assembler: `mov oFog.x, r11.x` is
// mask .x). The engines then write only those lanes; the others read as unwritten output lanes do
// (README "unwritten outputs": 0), the same bits on every engine.
#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

Program AssembleOrDie(const std::string& source) {
  AssembleOptions options;
  options.require_position = false;
  AssembleResult result = AssembleSource(source, "fog.vsh", options);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
  return result.program.value_or(Program{});
}

// The four lanes of output `slot` of vertex 0.
std::vector<std::uint32_t> LaneBits(const VertexArrays& outputs, OutputSlot slot) {
  std::vector<std::uint32_t> bits;
  for (int c = 0; c < 4; ++c) bits.push_back(std::bit_cast<std::uint32_t>(outputs.lane(static_cast<int>(slot), c)[0]));
  return bits;
}

TEST(ScalarOutputMask, EnginesWriteOnlyTheMaskedLanesAndAgree) {
  const Program program = AssembleOrDie("vs.1.1\nmov oFog.x, c0.y\nmov oPts.zw, c0.z\n");
  ConstantBank constants;
  constants[0] = {1.0f, 2.0f, 3.0f, 4.0f};
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  EXPECT_EQ(written[static_cast<int>(OutputSlot::kFog)], WriteMask(0x1));
  EXPECT_EQ(written[static_cast<int>(OutputSlot::kPointSize)], WriteMask(0xC));
  const VertexArrays inputs = MakeInputArrays(1, std::vector<int>{0});
  for (std::string kind : {"ref", "batch", "jit"}) {
    SCOPED_TRACE(std::string(kind));
    VertexArrays outputs = MakeOutputArrays(1, program);
    ASSERT_EQ(MakeEngine(kind, program, constants).value()->Run(inputs, outputs).message(), "");
    const std::uint32_t zero = 0, two = std::bit_cast<std::uint32_t>(2.0f), three = std::bit_cast<std::uint32_t>(3.0f);
    EXPECT_EQ(LaneBits(outputs, OutputSlot::kFog), (std::vector<std::uint32_t>{two, zero, zero, zero}));
    EXPECT_EQ(LaneBits(outputs, OutputSlot::kPointSize), (std::vector<std::uint32_t>{zero, zero, three, three}));
  }
}

}  // namespace
}  // namespace vs11
