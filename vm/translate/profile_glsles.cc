// GLSL ES: 3.00 (OpenGL ES 3.0, WebGL 2), 3.10 (OpenGL ES 3.1, the first with compute shaders) and
// 3.20 (OpenGL ES 3.2), highp throughout, since vs_1_1 computes in single precision. Outputs are
// matched by name. GLSL ES 3.00 and 3.10 have no `precise` (see
// Contraction); in 3.20 every output is `precise`, which forbids a driver to fuse a product and a sum
// for every operation the output depends on (NVIDIA's does: on an H100, 5 % of the paper's program's
// output lanes differed by one unit in the last place under 3.00).
#include <fmt/format.h>

#include "vm/translate/profile.h"

namespace vs11::translate {
namespace {

class GlslEsProfile final : public Profile {
 public:
  explicit GlslEsProfile(Target target) : target_(target) {}
  Target target() const override { return target_; }
  std::string Header() const override {
    return fmt::format("#version {} es\nprecision highp float;\nprecision highp int;\n", Version());
  }
  std::string ConstantBank(int count) const override { return fmt::format("uniform vec4 c[{}];\n", count); }
  std::string OutputQualifiers(int) const override { return Precise() ? "precise " : ""; }
  bool HasPrecise() const override { return Precise(); }
  std::string_view OutputMatching() const override {
    return Precise() ? "outputs match the next stage's inputs by name"
                     : "outputs match the next stage's inputs by name (GLSL ES 3.00 has no output locations)";
  }
  std::string_view Contraction() const override {
    if (Precise()) {
      return "every output is `precise`, which reaches each operation it depends on: no driver fuses a product\n"
             "//   and a sum into one rounding. (GLSL ES still allows x / y and sqrt their stated errors.)";
    }
    if (target_ == Target::kGlslEs310) {
      return "GLSL ES 3.10 has no `precise` (ES 3.20 has), so a driver may fuse a product and a sum of mad,\n"
             "//   dp3, dp4 and the matrices into one fused multiply-add, which rounds once instead of twice.\n"
             "//   Where that matters, use the glsles320 or SPIR-V target, whose outputs are precise.";
    }
    return "GLSL ES 3.00 has no `precise` (ES 3.20 has), so a driver may fuse a product and a sum of mad,\n"
           "//   dp3, dp4 and the matrices into one fused multiply-add, which rounds once instead of twice.\n"
           "//   Where that matters, use the glsles320 or SPIR-V target, whose outputs are precise.";
  }
  Result<Artifact> Finish(const std::string& glsl, Stage) const override { return TextArtifact(glsl); }

 private:
  bool Precise() const { return target_ == Target::kGlslEs320; }
  int Version() const {
    switch (target_) {
      case Target::kGlslEs310: return 310;
      case Target::kGlslEs320: return 320;
      default: return 300;
    }
  }
  Target target_;
};

}  // namespace

std::unique_ptr<Profile> MakeGlslEs300Profile() { return std::make_unique<GlslEsProfile>(Target::kGlslEs300); }
std::unique_ptr<Profile> MakeGlslEs310Profile() { return std::make_unique<GlslEsProfile>(Target::kGlslEs310); }
std::unique_ptr<Profile> MakeGlslEs320Profile() { return std::make_unique<GlslEsProfile>(Target::kGlslEs320); }

}  // namespace vs11::translate
