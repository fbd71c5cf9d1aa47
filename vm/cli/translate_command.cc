// vs11 translate: a program to GLSL 3.30, GLSL ES 3.00-3.20 or SPIR-V, as a vertex or compute shader (vm/translate/translate.h).
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "vm/cli/choice_option.h"
#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/cli/parse_command_line.h"
#include "vm/core/atomic_file.h"
#include "vm/translate/translate.h"

namespace vs11::cli {

void AddTranslateCommand(CLI::App& app) {
  struct Args {
    std::string input, output = "-";
    translate::Target target = translate::Target::kGlsl330;
    std::optional<translate::ClipSpace> clip;  // nullopt: the target API's
    translate::Stage stage = translate::Stage::kVertex;
    ProgramFlags flags;
    FloatRulesFlag float_rules;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand(
      "translate", "Translate a .vsh or .vso program to GLSL 3.30, GLSL ES 3.00-3.20 or SPIR-V with vs11's semantics");
  command->footer(
      "The program is assembled and validated as by `vs11 asm` (same diagnostics, exit 1 on an error).\n"
      "The output begins with its interface: vN at location N, the constants as vec4 c[--max-constants],\n"
      "oPos to gl_Position (--clip) and to vs11_oPos as written, oD0 oD1 oT0..oT7 oFog oPts as outputs of\n"
      "those names; the README's \"vs11 translate\" section has the details. SPIR-V (Vulkan 1.0, compiled\n"
      "by glslang) is binary and is written to a file only. --float-rules legacy writes every product of\n"
      "mul, mad, dp3, dp4, m*x*, dst and lit's power as (b == 0 ? 0 : a) * (a == 0 ? 0 : b), as the engines\n"
      "compute it under the same flag. --stage compute writes a compute shader instead (glsles310,\n"
      "glsles320 or spirv): one invocation per vertex, the constants in uniform block Vs11Constants\n"
      "(binding 0), where each input and output lies in block Vs11Layout (binding 1), inputs and outputs\n"
      "in storage buffers (bindings 2 and 3) in any layout, structure of arrays or interleaved; the\n"
      "interface comment and the README say how to fill them.\n\n"
      "Examples:\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to glsl330\n"
      "  vs11 translate programs/skinning.vsh --to glsles300 --clip d3d -o skinning.vert\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to glsles320 -o sh9.vert\n"
      "  vs11 translate programs/point_light.vsh --to spirv -o point_light.spv\n"
      "  vs11 translate programs/skinning.vsh --to spirv --float-rules legacy -o skinning_legacy.spv\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to glsles310 --stage compute -o sh9.comp\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to spirv --stage compute -o sh9_comp.spv");
  command->add_option("input", args->input, "Program (.vsh source or .vso bytecode; - reads standard input)")->required();
  AddChoiceOption(*command, "--to", args->target, translate::kTargetNames, "Target: " + translate::kTargetNames.Help())
      ->required()
      ->default_str("");
  AddChoiceOption(*command, "--stage", args->stage, translate::kStageNames, "Stage: " + translate::kStageNames.Help())
      ->capture_default_str();
  command->add_option("-o,--output", args->output, "File to write; - for stdout (GLSL only)")->capture_default_str();
  AddChoiceOption(*command, "--clip", args->clip, translate::kClipSpaceNames, "",
                  "gl_Position's clip space: " + translate::kClipSpaceNames.Help() +
                      "; default: gl for the GLSL targets, vulkan for spirv");
  args->flags.AddTo(*command);
  args->float_rules.AddTo(*command);
  command->callback([args] {
    translate::TranslateOptions options;
    options.target = args->target;
    if (options.target == translate::Target::kSpirv && args->output == "-") {
      std::fputs("vs11: error: --to spirv writes a binary: name a file with -o\n", stderr);
      throw CommandFailure{kUsageErrorStatus};
    }
    options.stage = args->stage;
    if (const Status problem = translate::StageProblem(options.target, options.stage); !problem.ok()) {
      std::fprintf(stderr, "vs11: error: --stage compute: %s\n", problem.message().c_str());
      throw CommandFailure{kUsageErrorStatus};
    }
    if (options.stage == translate::Stage::kCompute && args->clip) {
      std::fputs("warning: --clip applies to the vertex stage only; a compute shader writes oPos as the program does\n",
                 stderr);
    }
    CheckInputsAndOutputs({args->input}, {args->output});
    Program program = LoadProgramOrFail(args->input, args->flags);
    options.constant_count = args->flags.constant_count;
    if (args->clip) options.clip = *args->clip;
    options.float_rules = args->float_rules.Rules();
    options.source_name = args->input;
    const Result<translate::Artifact> artifact = translate::Translate(program, options);
    if (!artifact) Fail(artifact.message());
    if (args->output == "-") {
      std::fwrite(artifact->bytes.data(), 1, artifact->bytes.size(), stdout);
    } else if (const Status written = WriteFileAtomically(args->output, artifact->bytes); !written) {
      Fail(written.message());
    }
  });
}

}  // namespace vs11::cli
