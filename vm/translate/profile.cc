#include "vm/translate/profile.h"

namespace vs11::translate {

std::unique_ptr<Profile> MakeProfile(Target target) {
  switch (target) {
    case Target::kGlsl330: return MakeGlsl330Profile();
    case Target::kGlslEs300: return MakeGlslEs300Profile();
    case Target::kGlslEs320: return MakeGlslEs320Profile();
    case Target::kSpirv: return MakeSpirvProfile();
  }
  return MakeGlsl330Profile();
}

Artifact TextArtifact(const std::string& glsl) {
  Artifact artifact;
  artifact.bytes.assign(glsl.begin(), glsl.end());
  return artifact;
}

}  // namespace vs11::translate
