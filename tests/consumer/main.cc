// The paper's 11-instruction program on the emulated vs_1_1 machine: assemble it, set the seven
// constants of Table 1 from nine RGB coefficients, run it over a few normals, and compare with
// eq. (7) evaluated in double.
#include <cmath>
#include <cstdio>
#include <vector>

#include <vs11/vs11.h>

constexpr const char* kPaperProgram = R"(vs.1.1
dp4 r1.r, v0, c0                  ; c0..c6: cAr cAg cAb cBr cBg cBb cC
dp4 r1.g, v0, c1
dp4 r1.b, v0, c2
mul r2, v0.xyzz, v0.yzzx          ; (xy, yz, zz, zx)
dp4 r3.r, r2, c3
dp4 r3.g, r2, c4
dp4 r3.b, r2, c5
mul r0.xy, v0.xy, v0.xy           ; (x^2, y^2)
add r0.x, r0.x, -r0.y             ; x^2 - y^2
mad r2.rgb, c6.rgb, r0.x, r3.rgb
add oD0.rgb, r1.rgb, r2.rgb
)";

int main() {
  vs11::AssembleOptions options;
  options.require_position = false;  // a piece of a shader: it writes oD0 and no oPos
  vs11::AssembleResult assembled = vs11::AssembleSource(kPaperProgram, "paper.vsh", options);
  if (!assembled.program) {
    std::fputs(assembled.diagnostics.ToString().c_str(), stderr);
    return 1;
  }

  // Nine RGB coefficients (L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22): light mostly from +y.
  vs11::Sh9Rgb sh;
  sh.at(0, 0) = {1.0, 1.0, 1.2};
  sh.at(1, -1) = {0.6, 0.6, 0.7};
  sh.at(2, 0) = {0.1, 0.1, 0.05};
  sh.at(2, 2) = {0.05, 0.0, -0.05};
  const vs11::SevenConstants packed = vs11::PackTable1(sh);
  vs11::ConstantBank constants;
  for (int i = 0; i < 7; ++i) {
    const glm::vec4& r = packed.registers[i];
    constants[i] = {r.x, r.y, r.z, r.w};
  }

  // The normal goes into v0 as (x, y, z, 1).
  const std::vector<glm::dvec3> normals = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0.6, 0.8}};
  const std::vector<int> input_registers = {0};
  vs11::VertexArrays inputs = vs11::MakeInputArrays(normals.size(), input_registers);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    for (int c = 0; c < 3; ++c) inputs.lane(0, c)[i] = static_cast<float>(normals[i][c]);
    inputs.lane(0, 3)[i] = 1.0f;
  }
  vs11::VertexArrays outputs = vs11::MakeOutputArrays(normals.size(), *assembled.program);
  if (const vs11::Status ran = vs11::MakeEngine("batch", *assembled.program, constants).value()->Run(inputs, outputs);
      !ran) {
    std::fprintf(stderr, "%s\n", ran.message().c_str());
    return 1;
  }

  const int diffuse = static_cast<int>(vs11::OutputSlot::kDiffuse);
  double worst = 0.0;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const glm::dvec3 expected = vs11::IrradianceEq7(sh, normals[i]);
    std::printf("n = (%4.1f, %4.1f, %4.1f)  E =", normals[i].x, normals[i].y, normals[i].z);
    for (int c = 0; c < 3; ++c) {
      const float e = outputs.lane(diffuse, c)[i];
      std::printf(" %9.6f", e);
      worst = std::max(worst, std::abs(e - expected[c]) / std::max(1.0, std::abs(expected[c])));
    }
    std::printf("\n");
  }
  std::printf("largest difference from eq. (7) in double: %.2e\n", worst);
  return worst < 1e-5 ? 0 : 1;
}
