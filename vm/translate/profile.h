// The targets of `vs11 translate`, one file per dialect behind this interface (as MojoShader's
// profiles): profile_glsl330.cc, profile_glsles.cc (ES 3.00, 3.10 and 3.20), profile_spirv.cc. The shader
// body is the same GLSL for every target (translate.cc); a profile supplies only what its dialect
// spells differently and what it makes of the finished text.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/name_table.h"
#include "vm/core/result.h"

namespace vs11::translate {

enum class Target { kGlsl330, kGlslEs300, kGlslEs310, kGlslEs320, kSpirv };
inline constexpr NameTable kTargetNames("target", {
    Choice(Target::kGlsl330, "glsl330"), Choice(Target::kGlslEs300, "glsles300"),
    Choice(Target::kGlslEs310, "glsles310", "compute shaders; no precise"),
    Choice(Target::kGlslEs320, "glsles320", "every output precise: no fused multiply-adds"),
    Choice(Target::kSpirv, "spirv")});
inline std::string_view TargetName(Target target) { return kTargetNames.Name(target); }

// The shader the program becomes: a vertex shader (attributes in, outputs to the next stage) or a
// compute shader over storage buffers (compute_interface.h), one invocation per vertex.
enum class Stage { kVertex, kCompute };
inline constexpr NameTable kStageNames("stage", {
    Choice(Stage::kVertex, "vertex", "a vertex shader"),
    Choice(Stage::kCompute, "compute", "a compute shader over storage buffers; glsles310, glsles320 or spirv")});
inline std::string_view StageName(Stage stage) { return kStageNames.Name(stage); }
// Why `target` cannot hold a shader of `stage` (GLSL 3.30 and GLSL ES 3.00 have no compute shaders:
// kOptionValue, the options naming them being wrong); success where it can.
Status StageProblem(Target target, Stage stage);

// What a profile makes of the GLSL: the text itself, or a binary compiled from it.
struct Artifact {
  std::vector<std::uint8_t> bytes;
  bool binary = false;
};

class Profile {
 public:
  virtual ~Profile() = default;
  virtual Target target() const = 0;
  // `#version` and default precisions.
  virtual std::string Header() const = 0;
  // The declaration of the constant bank, holding `c[count]`.
  virtual std::string ConstantBank(int count) const = 0;
  // What precedes `out` in the declaration of the output at `location`: its layout where the dialect
  // matches outputs by location, and `precise` where the dialect has it, which reaches every
  // operation the output depends on (no fused multiply-add, no reordering).
  virtual std::string OutputQualifiers(int location) const = 0;
  // Whether the dialect has `precise` (GLSL ES 3.20, Vulkan GLSL 4.50): the compute stage declares
  // each output's local vec4 `precise`, as the vertex stage does its outputs.
  virtual bool HasPrecise() const = 0;
  // Sentences for the interface comment: how outputs are matched; whether the driver may contract.
  virtual std::string_view OutputMatching() const = 0;
  virtual std::string_view Contraction() const = 0;
  // The artifact, or (kGlCompile) why the text could not be turned into the target: a translator bug.
  virtual Result<Artifact> Finish(const std::string& glsl, Stage stage) const = 0;
};

std::unique_ptr<Profile> MakeGlsl330Profile();
std::unique_ptr<Profile> MakeGlslEs300Profile();
std::unique_ptr<Profile> MakeGlslEs310Profile();
std::unique_ptr<Profile> MakeGlslEs320Profile();
std::unique_ptr<Profile> MakeSpirvProfile();
std::unique_ptr<Profile> MakeProfile(Target target);

// The text as it is (the GLSL targets' Finish).
Artifact TextArtifact(const std::string& glsl);

}  // namespace vs11::translate
