// GLSL 3.30 core (OpenGL 3.3): outputs are matched by name, since 3.30 has no output locations, and
// there is no `precise` (see Contraction).
#include <fmt/format.h>

#include "vm/translate/profile.h"

namespace vs11::translate {
namespace {

class Glsl330Profile final : public Profile {
 public:
  Target target() const override { return Target::kGlsl330; }
  std::string Header() const override {
    return "#version 330 core\n";
  }
  std::string ConstantBank(int count) const override { return fmt::format("uniform vec4 c[{}];\n", count); }
  std::string OutputQualifiers(int) const override { return ""; }
  bool HasPrecise() const override { return false; }
  std::string_view OutputMatching() const override {
    return "outputs match the next stage's inputs by name (GLSL 3.30 has no output locations)";
  }
  std::string_view Contraction() const override {
    return "GLSL 3.30 has no `precise` (GLSL 4.00 has), so a driver may fuse a product and a sum of mad,\n"
           "//   dp3, dp4 and the matrices into one fused multiply-add, which rounds once instead of twice.\n"
           "//   Where that matters, use the SPIR-V target, whose operations are all precise.";
  }
  Result<Artifact> Finish(const std::string& glsl, Stage) const override { return TextArtifact(glsl); }
};

}  // namespace

std::unique_ptr<Profile> MakeGlsl330Profile() { return std::make_unique<Glsl330Profile>(); }

}  // namespace vs11::translate
