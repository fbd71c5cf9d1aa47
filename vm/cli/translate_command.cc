// vs11 translate: a program to GLSL 3.30, GLSL ES 3.00 or SPIR-V (vm/translate/translate.h).
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/cli/parse_command_line.h"
#include "vm/core/atomic_file.h"
#include "vm/translate/translate.h"

namespace vs11::cli {

void AddTranslateCommand(CLI::App& app) {
  struct Args {
    std::string input, output = "-", target, clip;
    ProgramFlags flags;
    FloatRulesFlag float_rules;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand(
      "translate", "Translate a .vsh or .vso program to GLSL 3.30, GLSL ES 3.00 or SPIR-V with vs11's semantics");
  command->footer(
      "The program is assembled and validated as by `vs11 asm` (same diagnostics, exit 1 on an error).\n"
      "The output begins with its interface: vN at location N, the constants as vec4 c[--max-constants],\n"
      "oPos to gl_Position (--clip) and to vs11_oPos as written, oD0 oD1 oT0..oT7 oFog oPts as outputs of\n"
      "those names; the README's \"vs11 translate\" section has the details. SPIR-V (Vulkan 1.0, compiled\n"
      "by glslang) is binary and is written to a file only. --float-rules legacy writes every product of\n"
      "mul, mad, dp3, dp4, m*x*, dst and lit's power as (b == 0 ? 0 : a) * (a == 0 ? 0 : b), as the engines\n"
      "compute it under the same flag.\n\n"
      "Examples:\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to glsl330\n"
      "  vs11 translate programs/skinning.vsh --to glsles300 --clip d3d -o skinning.vert\n"
      "  vs11 translate programs/sh9_irradiance.vsh --to glsles320 -o sh9.vert\n"
      "  vs11 translate programs/point_light.vsh --to spirv -o point_light.spv\n"
      "  vs11 translate programs/skinning.vsh --to spirv --float-rules legacy -o skinning_legacy.spv");
  command->add_option("input", args->input, "Program (.vsh source or .vso bytecode; - reads standard input)")->required();
  command->add_option("--to", args->target,
                      "Target: glsl330, glsles300, glsles320 (every output precise: no fused multiply-adds) or spirv")
      ->required()
      ->check(CLI::IsMember({"glsl330", "glsles300", "glsles320", "spirv"}));
  command->add_option("-o,--output", args->output, "File to write; - for stdout (GLSL only)")->capture_default_str();
  command->add_option("--clip", args->clip,
                      "gl_Position's clip space: d3d (as written), gl (z' = 2z - w) or vulkan (y' = -y); default: gl "
                      "for the GLSL targets, vulkan for spirv")
      ->check(CLI::IsMember({"d3d", "gl", "vulkan"}));
  args->flags.AddTo(*command);
  args->float_rules.AddTo(*command);
  command->callback([args] {
    translate::TranslateOptions options;
    options.target = *translate::TargetFromName(args->target);
    if (options.target == translate::Target::kSpirv && args->output == "-") {
      std::fputs("vs11: error: --to spirv writes a binary: name a file with -o\n", stderr);
      throw CommandFailure{kUsageErrorStatus};
    }
    CheckInputsAndOutputs({args->input}, {args->output});
    Program program = LoadProgramOrFail(args->input, args->flags);
    options.constant_count = args->flags.constant_count;
    if (!args->clip.empty()) options.clip = *translate::ClipSpaceFromName(args->clip);
    options.float_rules = args->float_rules.Rules();
    options.source_name = args->input;
    translate::Artifact artifact = translate::Translate(program, options);
    if (!artifact.error.empty()) Fail(artifact.error);
    if (args->output == "-") {
      std::fwrite(artifact.bytes.data(), 1, artifact.bytes.size(), stdout);
    } else if (const Status written = WriteFileAtomically(args->output, artifact.bytes); !written) {
      Fail(written.message());
    }
  });
}

}  // namespace vs11::cli
