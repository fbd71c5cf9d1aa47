// irrmap: irradiance environment map of one environment by the method of Ai, Peng & Zhang 2008.
// Parses the command line and calls RunIrrmap (irradiance/jobs/irrmap_job.h), which does all the work.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <new>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "irradiance/cli/subcommands.h"
#include "irradiance/gpu/gpu_frame_job.h"
#include "irradiance/io/environments.h"
#include "irradiance/io/map_file_formats.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/mesh_input/mesh_geometry_io.h"
#include "irradiance/render/preview.h"
#include "irradiance/sh/engine_sh.h"
#include "vm/cli/choice_option.h"
#include "vm/cli/parse_command_line.h"
#include "vm/core/atomic_file.h"
#include "vm/core/leak_check.h"
#include "vm/core/version.h"
#include "vm/engines/engine_factory.h"
#include "vm/gl/gl_context.h"
#include "vm/gl/gl_engine.h"

namespace {

constexpr int kProgressBarWidth = 30;
// Exit status: 1 for a failed job, 2 (vs11::cli::kUsageErrorStatus) for a command line that does not
// parse or holds a bad option value.
constexpr int kJobError = 1;
constexpr int kUsageError = 2;

std::string JoinNames() {
  std::string out;
  for (const std::string& name : vs11::irradiance::BuiltinEnvironmentNames()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

std::string Footer() {
  return fmt::format(
      "Outputs (in --out DIR, created if needed; all are written to temporaries and renamed into\n"
      "place only when all succeeded, so a failed run leaves no partial file):\n"
      "  coeffs.json     the 9 RGB SH coefficients (L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22),\n"
      "                  level (and level_choice, max_error, error_metric), window, face_size,\n"
      "                  layout, the 7 constants, every level's errors (relative, peak, rms, and\n"
      "                  per channel and luminance) and estimated error, timings_ms\n"
      "                  (order, program: name, file, slots, estimated error; every pair's estimate)\n"
      "  program.vsh     the chosen vs_1_1 program (see Orders below)\n"
      "  constants.vsh   its constant registers as def lines from c0 on; for the paper's program the\n"
      "                  Table 1 registers c0..c6 (cAr cAg cAb cBr cBg cBb cC), for `vs11 run\n"
      "                  program.vsh --fragment --consts constants.vsh --sphere 6 --sphere-reg v0`\n"
      "                  (the program writes no oPos)\n"
      "  irradiance.exr  irradiance cube map (horizontal cross, float), every texel computed by the\n"
      "                  chosen vs_1_1 program on the emulated machine; --map-format writes instead the\n"
      "                  file an engine loads as a cube map:\n"
      "                    hdr-faces  irradiance_px.hdr .. irradiance_nz.hdr, six Radiance faces: three.js\n"
      "                               (HDRCubeTextureLoader; its DDSLoader and KTX2Loader take neither\n"
      "                               file below as a float cube)\n"
      "                    ktx        irradiance.ktx, KTX 1.1 RGBA16F, mirrored in x as cmgen's cubes:\n"
      "                               Filament (ktxreader's Ktx1Reader)\n"
      "                    dds        irradiance.dds, DXGI R16G16B16A16_FLOAT with the DX10 header:\n"
      "                               Babylon.js, Direct3D, DirectXTex\n"
      "                    ktx2       irradiance.ktx2, VK_FORMAT_R16G16B16A16_SFLOAT: Vulkan loaders\n"
      "  sh_*            with --sh-export: the nine coefficients in each engine's convention and world\n"
      "                  frame, the convention stated at the top of the file: sh_three.json (three.js\n"
      "                  LightProbe), sh_filament.txt (IndirectLight irradiance, as cmgen --sh-shader),\n"
      "                  sh_unity.json (unity_SHAr..unity_SHC: the 7 constants / pi), sh_gltf.json\n"
      "                  (EXT_lights_image_based irradianceCoefficients), sh_irradiance.glsl/.hlsl\n"
      "                  (a function of the normal with the 7 constants baked in). Each is in the\n"
      "                  frame in which that engine shows the input: a lat-long panorama as the engine\n"
      "                  maps one (three.js's equirectUv and Unity's Skybox/Panoramic put the image\n"
      "                  centre at +X), a cube map as its cube texture (three.js's CubeTexture mirrored\n"
      "                  in x); sh_three.json and sh_unity.json also hold the engine's other way of\n"
      "                  showing the file under \"other_view\"\n"
      "  preview.png     diffuse spheres as in the paper's Fig. 3: exact convolution, SH9 from full\n"
      "                  resolution, from the 64x64 and 16x16 levels (and the chosen one, marked *),\n"
      "                  error images under them (in --error-metric's terms, captioned with the\n"
      "                  table's figures for that level) and the environment beside them\n"
      "\n"
      "Printed: a table of every mip level (face size, time to update the 9 coefficients from that\n"
      "level with the mips already built, errors against brute-force integration over\n"
      "--error-normals normals; * marks the chosen level), then the time of every stage. Errors,\n"
      "each the worst of r, g, b (coeffs.json also has each channel and the Rec. 709 luminance):\n"
      "  max/mean rel  per normal |SH9 - exact| / max(exact, 1% of the largest exact value): it\n"
      "                explodes where the exact value is near zero (the spot's unlit half)\n"
      "  peak          max |SH9 - exact| / max exact, as Ramamoorthi & Hanrahan state it (9.375 %\n"
      "                for one point light, at its horizon)\n"
      "  rms           RMS of SH9 - exact over the normals / mean exact (14.4 % for a point light)\n"
      "The ground truth (brute-force integration over every texel) is the slow stage (--no-ground-truth\n"
      "skips it, with the error columns and the preview); a progress bar for it, the load and the basis\n"
      "pyramid is shown when stderr is a terminal.\n"
      "\n"
      "Levels: 0 is the full face size, each level halves it, the last is 1x1. By default the coarsest\n"
      "level whose error against level 0 stays under --max-error ({1} %) in --error-metric's terms\n"
      "(default peak), estimated as 1.4 x its difference from the next finer level, every finer level\n"
      "passing too: the sky of 256x256 faces gets 16x16, the studio and the spot 32x32, a constant\n"
      "environment 1x1 (the paper fixes {0}x{0}: Fig. 3). With --error-metric relative the spot gets\n"
      "128x128: that metric is ruled by its darkest normals.\n"
      "\n"
      "Orders: the program is the cheapest (slots per vertex, then update time) whose estimated error\n"
      "against the nine terms at level 0 stays under --max-error: order0 (1 slot, constant), order1\n"
      "(3 slots, bands 0-1), zh3 (6 slots, bands 0-1 plus one zonal band-2 term) or order2 (the paper's\n"
      "11 slots). The constant environment gets order0, the gradient order1, the spot zh3, the sky\n"
      "order2.\n"
      "--window trades ringing (negative irradiance opposite a small bright light) against blur;\n"
      "`irrmap stability` measures both.\n"
      "\n"
      "Exit status: 0 success, 1 the environment, --mesh or an output failed (no output file is left),\n"
      "2 a usage error (an unknown option, a bad option value; before any work).\n"
      "\n"
      "Examples:\n"
      "  irrmap                                       # built-in sky, 256x256 faces, level by --max-error, out/\n"
      "  irrmap spot --window dering                  # the spot light without negative irradiance\n"
      "  irrmap gradient                              # a smooth gradient: the 3-slot order1 program\n"
      "  irrmap spot --coefficients-only --error-metric relative   # the level as the relative metric picks it\n"
      "  irrmap studio --face-size 128 --level 3      # built-in studio, coefficients from 16x16\n"
      "  irrmap probe.hdr --layout angular --face-size 256 --out probe-out\n"
      "  irrmap 'sky_{{face}}.exr' --engine ref         # six face files, reference engine\n"
      "  irrmap cross.exr --map-size 64 --threads 2\n"
      "  irrmap gradient --face-size 32 --engine gl --out gl-out    # evaluated on Mesa's llvmpipe\n"
      "  irrmap sky --face-size 512 --no-ground-truth   # coefficients and irradiance.exr, no error table\n"
      "  irrmap studio --face-size 64 --mesh /usr/share/assimp/models/PLY/Wuson.ply --out wuson\n"
      "  irrmap studio --face-size 64 --no-ground-truth --map-format hdr-faces --sh-export three --out three\n"
      "  irrmap studio --face-size 64 --no-ground-truth --map-format ktx --sh-export filament --out filament\n"
      "  irrmap sky --face-size 64 --coefficients-only --sh-export unity,gltf,glsl,hlsl --out sh\n"
      "  irrmap sky --face-size 16 --mesh /usr/share/assimp/models/STL/Wuson.stl --out stl  # zero normals: computed\n",
      vs11::irradiance::kRecommendedLevelSize, 100 * vs11::irradiance::kDefaultMaxLevelError);
}

// A progress bar on stderr, only when stderr is a terminal.
vs11::irradiance::IrrmapProgress TerminalProgress() {
  if (!isatty(fileno(stderr))) return {};
  return [last_percent = -1](std::string_view stage, double fraction) mutable {
    const int percent = static_cast<int>(fraction * 100.0);
    if (percent == last_percent) return;  // redraw only when the number changes
    last_percent = percent;
    const int filled = static_cast<int>(fraction * kProgressBarWidth + 0.5);
    fmt::print(stderr, "\rirrmap: {} [{}{}] {:3}%", stage, std::string(filled, '#'),
               std::string(kProgressBarWidth - filled, ' '), percent);
    if (fraction >= 1.0) fmt::print(stderr, "\n");
    std::fflush(stderr);
  };
}

// What the default job's command line sets beyond IrrmapOptions.
struct JobCommandLine {
  vs11::irradiance::IrrmapOptions options;
  std::string out_dir = options.out_dir.string();
  std::string font;
  std::string mesh_file;
  double mesh_timeout = 0;
  bool compute_normals = false;
  int level = 0;
  std::string gl_device;  // empty, "list" or a device number
};

// The default job's options (`irrmap [ENV] ...`): one add_option per flag, hence its length.
void AddJobOptions(CLI::App& app, JobCommandLine& line) {
  vs11::irradiance::IrrmapOptions& options = line.options;
  std::string& out_dir = line.out_dir;
  std::string& font = line.font;
  std::string& mesh_file = line.mesh_file;
  double& mesh_timeout = line.mesh_timeout;
  int& level = line.level;
  app.add_option("ENV", options.environment,
                 fmt::format("environment: an image file (any layout below), a six-face pattern holding "
                             "{{face}}, or a built-in: {}", JoinNames()))
      ->capture_default_str();
  vs11::cli::AddChoiceOption(app, "--layout", options.layout, vs11::irradiance::kLayoutNames,
                              "layout of a file: " + vs11::irradiance::kLayoutNames.Help());
  app.add_option("--face-size", options.face_size,
                 "face size of a built-in environment, or of the cube an angular map is resampled to; a latlong "
                 "map is projected where it lies, its level k >= 1 averaged to the grid of a face of N >> k "
                 "(4 (N >> k) x 2 (N >> k)), and resampled to an N cube only for the ground truth, preview and "
                 "--mesh; a power of two (cube files keep theirs, which must be a power of two too)")
      ->capture_default_str();
  CLI::Option* level_option = app.add_option("--level", level,
                 "mip level the coefficients are computed from: 0 = full face size, each level halves it, down to "
                 "1x1; default: picked by --max-error");
  app.add_option("--max-error", options.max_error,
                 fmt::format("unless --level is given, pick the coarsest level whose error against full resolution, "
                             "estimated from adjacent levels, stays under this fraction ({} = {} %) of --error-metric's figure",
                             vs11::irradiance::kDefaultMaxLevelError, 100 * vs11::irradiance::kDefaultMaxLevelError))
      ->capture_default_str()
      ->excludes(level_option);
  vs11::cli::AddChoiceOption(app, "--error-metric", options.error_metric, vs11::irradiance::kErrorMetricNames,
                              fmt::format("what --max-error and the estimates measure: {}, each the worst of r, g, b",
                                          vs11::irradiance::kErrorMetricNames.Help()));
  vs11::cli::AddChoiceOption(app, "--order", options.order, vs11::kShOrderNames,
                              vs11::irradiance::kAutoOrderName,
                              fmt::format("program: {} (the cheapest within --max-error; order2 when --level is given) "
                                          "or one of {}",
                                          vs11::irradiance::kAutoOrderName, vs11::kShOrderNames.List()));
  vs11::cli::AddChoiceOption(app, "--window", options.window, vs11::irradiance::kShWindowNames,
                              "window on the coefficients against ringing from small bright lights: " +
                                  vs11::irradiance::kShWindowNames.Help());
  app.add_option("--window-width", options.window_width, "width of the hanning and lanczos windows, in bands")
      ->capture_default_str();
  app.add_option("--out", out_dir, "output directory")->capture_default_str();
  app.add_option("--engine", options.engine,
                 "vertex machine engine: " + vs11::EngineDescriptions())
      ->capture_default_str();
  app.add_option("--gl-device", line.gl_device,
                 "EGL device for --engine gl: 'list' prints them; N picks one (default: Mesa's llvmpipe)")
      ->check([](const std::string& value) {
        return value == "list" || vs11::gl::GlDeviceIndex(value) ? std::string() : "expected 'list' or a device number";
      });
  app.add_option("--threads", options.threads, "worker threads (0 = every core)")->capture_default_str();
  app.add_option("--map-size", options.map_size,
                 "face size of irradiance.exr; the irradiance is a quadratic polynomial of the normal, so 32 "
                 "texels per face resolve it")
      ->capture_default_str();
  app.add_option("--error-normals", options.error_normals,
                 "normals (evenly spread) at which every level is compared with the ground truth")
      ->capture_default_str();
  app.add_option("--sphere-size", options.sphere_diameter, "diameter of the preview spheres in pixels")
      ->capture_default_str();
  app.add_flag("--coefficients-only", options.coefficients_only,
               "write only coeffs.json and constants.vsh: no irradiance map, ground truth, error table or preview "
               "(each level computed once, not timed repeatedly)");
  app.add_option("--font", font, fmt::format("TrueType font of the preview labels (default {})",
                                             vs11::irradiance::kDefaultPreviewFont));
  app.add_flag("--no-ground-truth", options.no_ground_truth,
               "skip the brute-force ground truth (most of a default run's time): no error columns and no "
               "preview.png; coeffs.json, constants.vsh and irradiance.exr are written");
  app.set_version_flag("--version", fmt::format("irrmap {}", vs11::Vs11Version()));
  app.add_option("--mesh", mesh_file,
                 "also light this mesh (any format Assimp reads) as the paper's Fig. 3: mesh.ply (8-bit vertex "
                 "colours, tone mapped as mesh.png) and mesh.png (program | exact | relative error); vertices whose "
                 "normal the file omits or gives as zero get computed smooth normals, with a warning");
  app.add_flag("--compute-normals", line.compute_normals,
               "replace every normal of --mesh with computed smooth ones (area-weighted, from its triangles), "
               "even where the file gives usable normals");
  app.add_option("--mesh-timeout", mesh_timeout,
                 "stop reading --mesh after this many seconds (default 60 plus 1 per MiB): Assimp reads in a "
                 "separate process, and some corrupt files make it loop")
      ->check(CLI::PositiveNumber);
  app.add_option("--mesh-truth-limit", options.mesh_truth_vertex_limit,
                 "meshes with more vertices get no exact irradiance (0 = no limit)")
      ->capture_default_str();
}

// --map-format and --sh-export: outputs engines load as they are.
void AddEngineExportOptions(CLI::App& app, vs11::irradiance::IrrmapOptions& options) {
  vs11::cli::AddChoiceOption(app, "--map-format", options.map_format, vs11::irradiance::kMapFileFormatNames,
                              "file of the irradiance cube map: " + vs11::irradiance::kMapFileFormatNames.Help());
  vs11::cli::AddChoiceListOption(app, "--sh-export", options.sh_exports, vs11::irradiance::kShExportFormatNames,
                                  fmt::format("also write the nine coefficients for these engines, each in its own "
                                              "convention and world frame, as that engine shows the input (a lat-long "
                                              "panorama or a cube map) (comma-separated or repeated): {}",
                                              vs11::irradiance::kShExportFormatNames.List()));
}

// Runs the job the command line asked for; the exit status.
int RunJob(const CLI::App& app, JobCommandLine& line) {
  vs11::irradiance::IrrmapOptions& options = line.options;
  options.out_dir = line.out_dir;
  options.font = line.font;
  if (app.count("--level") > 0) options.level = line.level;
  if (const vs11::Status usage = vs11::irradiance::CheckIrrmapOptions(options); !usage.ok()) {
    fmt::print(stderr, "irrmap: error: {}\nRun with --help for more information.\n", usage.message());
    return vs11::cli::kUsageErrorStatus;
  }
  if (line.gl_device == "list") {
    const vs11::Result<std::vector<vs11::gl::GlDeviceInfo>> devices = vs11::gl::ListGlDevices();
    if (!devices) {
      fmt::print(stderr, "irrmap: error: {}\n", devices.message());
      return kJobError;
    }
    fmt::print("{}", vs11::gl::FormatGlDeviceList(*devices));
    return 0;
  }
  const std::optional<int> gl_device = vs11::gl::GlDeviceIndex(line.gl_device);
  options.engine_settings.Set(vs11::gl::GlOptions{gl_device});
  // On gl the chosen level's mips, projection and constants run on the GPU too (irradiance/gpu).
  if (options.engine == "gl") options.gpu_frame = vs11::irradiance::gpu::MakeGpuFrameHook(gl_device);
  if (gl_device && options.engine != "gl") {
    fmt::print(stderr, "irrmap: warning: --gl-device applies to --engine gl only; --engine {} ignores it\n",
               options.engine);
  }
  options.face_size_given = app.count("--face-size") > 0;
  if (const vs11::Status error = vs11::irradiance::CheckOutputsAreNotInputs(options, line.mesh_file); !error.ok()) {
    fmt::print(stderr, "irrmap: error: {}\n", error.message());
    return vs11::cli::kUsageErrorStatus;
  }
  if (!line.mesh_file.empty()) {
    std::vector<std::string> mesh_warnings;
    options.mesh.emplace();
    const vs11::Status mesh_loaded = vs11::irradiance::LoadMeshGeometry(
        line.mesh_file, *options.mesh, mesh_warnings, line.mesh_timeout, line.compute_normals);
    for (const std::string& warning : mesh_warnings) fmt::print(stderr, "irrmap: warning: {}\n", warning);
    if (!mesh_loaded.ok()) {
      fmt::print(stderr, "irrmap: error: {}\n", mesh_loaded.message());
      return kJobError;
    }
  }

  const auto start = std::chrono::steady_clock::now();
  vs11::irradiance::IrrmapReport report;
  const vs11::Status ran = vs11::irradiance::RunIrrmap(options, report, TerminalProgress());
  for (const std::string& warning : report.warnings) fmt::print(stderr, "irrmap: warning: {}\n", warning);
  if (!ran.ok()) {
    fmt::print(stderr, "irrmap: error: {}\n", ran.message());
    return report.usage_error ? kUsageError : kJobError;
  }
  const double total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  fmt::print("environment {}, layout {} ({}), face size {}, coefficients from level {} ({}x{}), {} threads\n\n",
             report.environment, report.layout, report.layout_reason, report.face_size, report.level, report.levels[report.level].size,
             report.levels[report.level].size, report.threads);
  if (!options.coefficients_only) fmt::print("{}\n", vs11::irradiance::FormatLevelTable(report));
  fmt::print("stage times:\n{}  {:<15} {:>10.3f} ms\n\n", vs11::irradiance::FormatTimings(report), "total", total_ms);
  fmt::print("wrote:");
  for (const auto& file : report.files) fmt::print(" {}", file.string());
  fmt::print("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const vs11::EndOfMainLeakCheck leak_check;  // first: destroyed last, before the static objects
  vs11::RemoveTemporariesOnSignals();  // an interrupted run leaves no half-written file
  vs11::gl::RegisterGlEngine();
  CLI::App app{fmt::format(
      "irrmap: irradiance environment map of an environment, with 9 spherical-harmonic coefficients per\n"
      "channel computed from a mip level of the cube map and evaluated by the paper's 11-instruction\n"
      "vs_1_1 vertex program on the emulated machine (Ai, Peng & Zhang 2008).")};
  app.footer(Footer());
  JobCommandLine line;
  AddJobOptions(app, line);
  AddEngineExportOptions(app, line.options);
  vs11::irradiance::cli::AddSubcommands(app);
  try {
    if (std::optional<int> status = vs11::cli::ParseCommandLine(app, argc, argv, "irrmap")) return *status;
    // A subcommand (irrmap chart, irrmap stability ...) did its work in its own callback.
    if (!app.get_subcommands().empty()) return 0;
    return RunJob(app, line);
  } catch (const vs11::irradiance::cli::SubcommandFailure& failure) {
    fmt::print(stderr, "irrmap: error: {}\n", failure.what());
    return kJobError;
  } catch (const std::bad_alloc&) {
    // The jobs report their own shortage with what they were doing; this is the rest (a subcommand's
    // tables, the tool's own output).
    std::fputs("irrmap: error: out of memory\n", stderr);
    return kJobError;
  }
}
