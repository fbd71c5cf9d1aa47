#include "vm/translate/profile.h"

namespace vs11::translate {

std::unique_ptr<Profile> MakeProfile(Target target) {
  switch (target) {
    case Target::kGlsl330: return MakeGlsl330Profile();
    case Target::kGlslEs300: return MakeGlslEs300Profile();
    case Target::kGlslEs310: return MakeGlslEs310Profile();
    case Target::kGlslEs320: return MakeGlslEs320Profile();
    case Target::kSpirv: return MakeSpirvProfile();
  }
  return MakeGlsl330Profile();
}

Status StageProblem(Target target, Stage stage) {
  if (stage == Stage::kCompute && (target == Target::kGlsl330 || target == Target::kGlslEs300)) {
    return Failure(DiagnosticCode::kOptionValue,
                   std::string(TargetName(target)) +
                       " has no compute shaders (they need GLSL ES 3.10 or later): use glsles310, glsles320 or spirv");
  }
  return {};
}

Artifact TextArtifact(const std::string& glsl) {
  Artifact artifact;
  artifact.bytes.assign(glsl.begin(), glsl.end());
  return artifact;
}

}  // namespace vs11::translate
