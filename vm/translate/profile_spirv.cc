// SPIR-V for Vulkan 1.0: Vulkan GLSL 4.50 compiled by glslang's library. Vulkan has no free uniforms,
// so the bank is a std140 uniform block at set 0, binding 0 (its vec4 array has a 16-byte stride, the
// layout of D3D's constant registers); outputs carry the locations of the interface comment and
// `precise`, so that no driver contracts a product and a sum into one fused multiply-add.
#include <fmt/format.h>

#include "vm/translate/glslang_compiler.h"
#include "vm/translate/profile.h"

namespace vs11::translate {
namespace {

class SpirvProfile final : public Profile {
 public:
  Target target() const override { return Target::kSpirv; }
  std::string Header() const override { return "#version 450\n"; }
  std::string ConstantBank(int count) const override {
    return fmt::format("layout(std140, set = 0, binding = 0) uniform Vs11Constants {{ vec4 c[{}]; }};\n", count);
  }
  std::string OutputQualifiers(int location) const override {
    return fmt::format("layout(location = {}) precise ", location);
  }
  bool HasPrecise() const override { return true; }
  std::string_view OutputMatching() const override {
    return "output locations: vs11_oPos 0, oD0 1, oD1 2, oT0..oT7 3..10, oFog 11, oPts 12; constants: uniform block "
           "Vs11Constants (std140) at set 0, binding 0";
  }
  std::string_view Contraction() const override {
    return "every output is `precise`, which glslang carries to each operation it depends on as NoContraction:\n"
           "//   no fused multiply-add, no reordering.";
  }
  Result<Artifact> Finish(const std::string& glsl, Stage stage) const override {
    Artifact artifact;
    artifact.binary = true;
    const Result<std::vector<std::uint32_t>> compiled = CompileWithGlslang(glsl, Target::kSpirv, stage);
    if (!compiled) {
      return Failure(compiled.error().code,
                     "glslang rejected the translation (a vs11 bug; please report it with the program):\n" +
                         compiled.message());
    }
    for (std::uint32_t word : *compiled) {
      for (int byte = 0; byte < 4; ++byte) artifact.bytes.push_back(static_cast<std::uint8_t>(word >> (8 * byte)));
    }
    return artifact;
  }
};

}  // namespace

std::unique_ptr<Profile> MakeSpirvProfile() { return std::make_unique<SpirvProfile>(); }

}  // namespace vs11::translate
