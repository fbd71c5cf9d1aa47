// `vs11 verify`: runs a program and compares it with its double-precision reference, or compares two
// engines bit for bit. The work is in vm/reference/verify.h; this file only maps flags onto it.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/engines/engine_factory.h"
#include "vm/reference/program_references.h"
#include "vm/reference/verify.h"

namespace vs11::cli {
namespace {

struct VerifyFlags {
  std::string program;
  std::string reference;
  std::string output;
  std::string coeffs;
  int samples = kDefaultVerifySamples;
  std::optional<double> tolerance;
  std::uint64_t seed = 1;
  bool json = false;
  std::string against_engine;
  ProgramFlags program_flags;
  EngineFlags engine_flags;
};

std::string ReferenceHelp() {
  std::string text;
  for (const ReferenceInfo& info : References()) {
    text += fmt::format("  {:<18} {}\n", info.name, info.summary);
  }
  return text;
}

void RunVerify(const VerifyFlags& flags) {
  if (flags.engine_flags.ListGlDevicesIfAsked(flags.against_engine)) return;
  CheckInputsAndOutputs({flags.program, flags.coeffs}, {});
  ProgramForVerify loaded = LoadProgramForVerify(flags.program, flags.program_flags.ToOptions(),
                                                                flags.program_flags.FragmentFlag());
  std::fputs(loaded.diagnostics.ToString().c_str(), stderr);
  if (!loaded.program) throw CommandFailure{1};

  ProgramMetadata metadata = loaded.metadata;
  if (!flags.reference.empty()) {
    if (!FindReference(flags.reference)) {
      Fail(fmt::format("unknown reference '{}' (known: {})", flags.reference, ReferenceNames()));
    }
    metadata.reference = flags.reference;
  }
  if (!flags.output.empty()) {
    metadata.output = OutputSlotFromName(flags.output);
    if (!metadata.output) {
      Fail(fmt::format("--output {}: not an output register (oPos, oFog, oPts, oD0, oD1, oT0..oT7)", flags.output));
    }
  }

  VerifyOptions options;
  options.engine = flags.engine_flags.Name();
  options.engine_options = flags.engine_flags.Options();
  options.seed = flags.seed;
  options.samples = flags.samples;
  options.tolerance = flags.tolerance;
  options.constant_count = flags.program_flags.constant_count;
  if (!flags.coeffs.empty()) {
    Result<Sh9Rgb> coefficients = LoadCoefficientsJson(flags.coeffs);
    if (!coefficients) Fail(coefficients.message());
    options.coefficients = *coefficients;
  }

  if (!flags.against_engine.empty()) {
    std::optional<EngineInfo> other = FindEngine(flags.against_engine);
    if (!other) Fail(fmt::format("--against-engine {}: expected {}", flags.against_engine, EngineNameList()));
    EngineComparison comparison =
        VerifyEngines(*loaded.program, metadata, options.engine, std::string(other->name), options);
    if (!comparison.error.empty()) Fail(fmt::format("{}: {}", flags.program, comparison.error));
    std::string text = flags.json
                           ? EngineComparisonJson(comparison) + "\n"
                           : fmt::format("program {}\n{}", flags.program, FormatEngineComparison(comparison));
    std::fputs(text.c_str(), stdout);
    if (!comparison.identical()) throw CommandFailure{1};
    return;
  }

  VerifyReport report = Verify(*loaded.program, metadata, options);
  if (!report.error.empty()) Fail(fmt::format("{}: {}", flags.program, report.error));
  std::string text = flags.json ? VerifyReportJson(report) + "\n"
                                : fmt::format("program {}\n{}", flags.program, FormatVerifyReport(report));
  std::fputs(text.c_str(), stdout);
  if (!report.pass) throw CommandFailure{1};
}

}  // namespace

void AddVerifyCommand(CLI::App& app) {
  auto flags = std::make_shared<VerifyFlags>();
  CLI::App* command = app.add_subcommand(
      "verify", "Run a program and compare its outputs with a double-precision reference (or two engines)");
  command->footer(fmt::format(
      "Metadata: the program's comment header names its reference and registers, one per line, e.g.\n"
      "  ; vs11: reference=sh9        ; vs11: packing=table1|unit_sphere10|matrix|basis\n"
      "  ; vs11: normal=v0            ; vs11: position=v0   ; vs11: output=oD0\n"
      "  ; vs11: constants=c0         ; vs11: transform=c7  ; vs11: fragment=yes\n"
      "(see programs/README.md). Flags override the metadata.\n"
      "\n"
      "References:\n{}"
      "\n"
      "Errors are per output register: absolute |actual - expected|, and relative to the largest |expected| of\n"
      "that register over all vertices. An output passes when its max relative error is at most the tolerance\n"
      "(default {:g}, or the reference's own, e.g. 1e-4 for expp/logp partial precision). sh9 inputs: N normals\n"
      "spread over the sphere (--samples) plus the 6 axes and 8 diagonals; other references: N random vertices.\n"
      "Coefficients for sh9: random from --seed, or --coeffs FILE.json holding\n"
      "  {{\"coefficients\": [[r,g,b] x 9]}} in the order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22.\n"
      "The machine reports raw output values (D3D would clamp oD0/oD1/oFog to [0, 1] afterwards).\n"
      "\n"
      "--against-engine E runs the program on --engine and on E with the same inputs (the reference's, or random\n"
      "ones when there is no reference) and compares every written output lane bit for bit; --float-rules\n"
      "applies to both engines.\n"
      "--engine gl (or --against-engine gl) runs the GLSL ES translation on Mesa's llvmpipe or --gl-device N\n"
      "(vs11 run --help); no EGL device with OpenGL ES 3.0 is an error (exit 1).\n"
      "\n"
      "Exit status: 0 pass (or identical), 1 fail (or different) or an error, 2 bad usage.\n"
      "\n"
      "Examples:\n"
      "  vs11 verify programs/sh9_irradiance.vsh\n"
      "  vs11 verify programs/sh9_irradiance.vsh --engine ref --coeffs grace.json --samples 1000 --json\n"
      "  vs11 verify my.vsh --reference sh9 --output oT0 --tolerance 1e-6\n"
      "  vs11 verify programs/skinning.vsh --against-engine ref\n"
      "  vs11 verify programs/skinning.vsh --engine gl --against-engine ref\n"
      "  vs11 verify programs/sh9_irradiance.vsh --engine gl\n"
      "  vs11 verify programs/skinning.vsh --against-engine ref --float-rules legacy\n",
      ReferenceHelp(), kDefaultVerifyTolerance));
  command->add_option("program", flags->program, "Program file (.vsh source or .vso bytecode)")->required();
  command->add_option("--reference", flags->reference,
                      "Reference to compare with: " + ReferenceNames() + " (default: the program's metadata)");
  command->add_option("--output", flags->output, "Output register compared first, e.g. oD0 or oT0 (default: metadata)");
  command->add_option("--coeffs", flags->coeffs,
                      "JSON file with the 9 RGB SH coefficients (sh9), {\"coefficients\": [[r,g,b] x 9]}");
  command->add_option("--samples", flags->samples, "Sample count: sphere normals (sh9) or random vertices")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  command->add_option("--tolerance", flags->tolerance,
                      fmt::format("Largest allowed relative error (default {:g}, or the reference's own)",
                                  kDefaultVerifyTolerance))
      ->check(CLI::NonNegativeNumber);
  command->add_option("--seed", flags->seed, "Seed of the random coefficients and inputs")->capture_default_str();
  command->add_flag("--json", flags->json, "Print the report as JSON");
  command->add_option("--against-engine", flags->against_engine,
                      "Compare --engine with this engine (" + EngineNameList() +
                          ") bit for bit instead of with a reference")
      ->check(CLI::IsMember(EngineSpellings()));
  flags->program_flags.AddTo(*command);
  flags->engine_flags.AddTo(*command);
  command->callback([flags] { RunVerify(*flags); });
}

}  // namespace vs11::cli
