#include "vm/translate/profile.h"

namespace vs11::translate {

std::optional<Target> TargetFromName(std::string_view name) {
  for (Target target : {Target::kGlsl330, Target::kGlslEs300, Target::kGlslEs310, Target::kGlslEs320, Target::kSpirv}) {
    if (TargetName(target) == name) return target;
  }
  return std::nullopt;
}

std::string_view TargetName(Target target) {
  switch (target) {
    case Target::kGlsl330: return "glsl330";
    case Target::kGlslEs300: return "glsles300";
    case Target::kGlslEs310: return "glsles310";
    case Target::kGlslEs320: return "glsles320";
    case Target::kSpirv: return "spirv";
  }
  return "glsl330";
}

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

std::optional<Stage> StageFromName(std::string_view name) {
  if (name == "vertex") return Stage::kVertex;
  if (name == "compute") return Stage::kCompute;
  return std::nullopt;
}

std::string_view StageName(Stage stage) { return stage == Stage::kCompute ? "compute" : "vertex"; }

std::optional<std::string> StageProblem(Target target, Stage stage) {
  if (stage == Stage::kCompute && (target == Target::kGlsl330 || target == Target::kGlslEs300)) {
    return std::string(TargetName(target)) +
           " has no compute shaders (they need GLSL ES 3.10 or later): use glsles310, glsles320 or spirv";
  }
  return std::nullopt;
}

Artifact TextArtifact(const std::string& glsl) {
  Artifact artifact;
  artifact.bytes.assign(glsl.begin(), glsl.end());
  return artifact;
}

}  // namespace vs11::translate
