// GLSL ES 3.00 (OpenGL ES 3.0, WebGL 2): highp throughout, since vs_1_1 computes in single precision.
// Outputs are matched by name; there is no `precise` (see Contraction).
#include <fmt/format.h>

#include "vm/translate/profile.h"

namespace vs11::translate {
namespace {

class GlslEs300Profile final : public Profile {
 public:
  Target target() const override { return Target::kGlslEs300; }
  std::string Header() const override {
    return "#version 300 es\n"
           "precision highp float;\n"
           "precision highp int;\n";
  }
  std::string ConstantBank(int count) const override { return fmt::format("uniform vec4 c[{}];\n", count); }
  std::string OutputQualifiers(int) const override { return ""; }
  std::string_view OutputMatching() const override {
    return "outputs match the next stage's inputs by name (GLSL ES 3.00 has no output locations)";
  }
  std::string_view Contraction() const override {
    return "GLSL ES 3.00 has no `precise` (ES 3.20 has), so a driver may fuse a product and a sum of mad,\n"
           "//   dp3, dp4 and the matrices into one fused multiply-add, which rounds once instead of twice.\n"
           "//   Where that matters, use the SPIR-V target, whose operations are all precise.";
  }
  Artifact Finish(const std::string& glsl) const override { return TextArtifact(glsl); }
};

}  // namespace

std::unique_ptr<Profile> MakeGlslEs300Profile() { return std::make_unique<GlslEs300Profile>(); }

}  // namespace vs11::translate
