// GLSL ES 3.20 (OpenGL ES 3.2): GLSL ES 3.00 with every output `precise`. A driver may otherwise fuse a
// product and a sum into one fused multiply-add (NVIDIA's does: on an H100, 5 % of the paper's
// program's output lanes differed by one unit in the last place); `precise` forbids that for every
// operation an output depends on, so the products and sums round as vs_1_1's do.
#include <fmt/format.h>

#include "vm/translate/profile.h"

namespace vs11::translate {
namespace {

class GlslEs320Profile final : public Profile {
 public:
  Target target() const override { return Target::kGlslEs320; }
  std::string Header() const override {
    return "#version 320 es\n"
           "precision highp float;\n"
           "precision highp int;\n";
  }
  std::string ConstantBank(int count) const override { return fmt::format("uniform vec4 c[{}];\n", count); }
  std::string OutputQualifiers(int) const override { return "precise "; }
  std::string_view OutputMatching() const override {
    return "outputs match the next stage's inputs by name";
  }
  std::string_view Contraction() const override {
    return "every output is `precise`, which reaches each operation it depends on: no driver fuses a product\n"
           "//   and a sum into one rounding. (GLSL ES still allows x / y and sqrt their stated errors.)";
  }
  Artifact Finish(const std::string& glsl) const override { return TextArtifact(glsl); }
};

}  // namespace

std::unique_ptr<Profile> MakeGlslEs320Profile() { return std::make_unique<GlslEs320Profile>(); }

}  // namespace vs11::translate
