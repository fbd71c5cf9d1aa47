// Assembles a one-line program with the installed library, runs it, and checks the result.
#include <cstdio>

#include "irradiance/sh9.h"
#include "vm/assembler.h"
#include "vm/machine.h"

int main() {
  vs11::AssembleResult assembled =
      vs11::AssembleSource("vs_1_1\ndcl_position v0\nadd oPos, v0, v0\n", "consumer.vsh", {});
  if (!assembled.program) {
    std::fputs(assembled.diagnostics.ToString().c_str(), stderr);
    return 1;
  }
  std::vector<int> registers = {0};
  vs11::VertexArrays inputs = vs11::MakeInputArrays(1, registers);
  inputs.lane(0, 0)[0] = 1.5f;
  vs11::VertexArrays outputs = vs11::MakeOutputArrays(1, *assembled.program);
  vs11::MakeEngine(vs11::EngineKind::kBatch, *assembled.program, vs11::ConstantBank())->Run(inputs, outputs);
  float x = outputs.lane(0, 0)[0];
  vs11::irradiance::Sh9Rgb coefficients{};
  (void)vs11::irradiance::PackTable1(coefficients);
  std::printf("consumer: oPos.x = %g\n", x);
  return x == 3.0f ? 0 : 1;
}
