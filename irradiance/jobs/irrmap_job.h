// The `irrmap` job: the paper's whole procedure (section 3.3) on one environment map, with every
// intermediate written out and measured.
//
//   load ENV ─> environment mip pyramid ─┐
//   basis pyramid (once per face size) ──┴─> ProjectLevel(K) = 9 RGB coefficients
//   (a lat-long ENV: its own pyramid, projected in place: irradiance/jobs/irrmap_environment.h)
//     ─> PackTable1 = the 7 constant registers ─> the paper's vertex program (sh9_irradiance.vsh) on
//        the vs_1_1 machine, once per texel direction of the irradiance cube map
//   plus: the coefficients of every level compared with brute-force integration (ground truth) over
//   a dense set of normals, and a Fig. 3-like preview.
//
// The files it writes into IrrmapOptions::out_dir, all or none, and coeffs.json's fields: README.md,
// "What irrmap writes".
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/io/map_file_formats.h"
#include "irradiance/io/option_names.h"
#include "irradiance/jobs/float_range.h"
#include "irradiance/jobs/gpu_frame_hook.h"
#include "irradiance/jobs/mesh_lighting.h"
#include "irradiance/jobs/output_metadata.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/engine_sh.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_order.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The paper recommends computing the coefficients from the 64 x 64 level of a larger map (Fig. 3:
// it looks as good as full resolution at a quarter of the cost per halving).
inline constexpr int kRecommendedLevelSize = 64;
// Default face size of the irradiance cube map: the irradiance is band-limited to l <= 2 (a
// quadratic polynomial of the normal), so 32 texels per face with bilinear filtering resolve it.
inline constexpr int kDefaultMapSize = 32;
inline constexpr int kMaxMapSize = 1024;
// Default width of the hanning and lanczos windows (w1, w2 = 0.854, 0.5 and 0.900, 0.637): the width
// whose far-side dip is smallest for a point light (irrmap stability).
inline constexpr double kDefaultWindowWidth = 4.0;
// --order's name for "the cheapest program within max_error" (IrrmapOptions::order unset).
inline constexpr std::string_view kAutoOrderName = "auto";

// The level whose faces are kRecommendedLevelSize when the face is larger than that, else 0 (the
// paper's fixed choice; irrmap picks by IrrmapOptions::max_error instead unless --level is given).
// face_size a positive power of two (asserted).
int DefaultLevel(int face_size);

struct IrrmapOptions {
  std::string environment = "sky";  // a file, a {face} pattern or a BuiltinEnvironmentNames() name
  EnvironmentLayout layout = EnvironmentLayout::kAuto;  // files only
  int face_size = kDefaultFaceSize;  // built-ins; resampled angular maps; the grids of a lat-long map's levels
  std::optional<int> level;         // when set, max_error is not used
  // Otherwise the level is the coarsest whose error against level 0, estimated from adjacent
  // levels, stays under this fraction (CoarsestLevelWithin, irradiance/sh/level_choice.h).
  double max_error = kDefaultMaxLevelError;
  // What max_error bounds (irradiance/sh/ground_truth.h). The estimates, the level table's marks and
  // the preview's error images follow it too.
  ErrorMetric error_metric = kDefaultErrorMetric;
  // The program (irradiance/sh/sh_order.h): nullopt ("auto", kAutoOrderName) picks the cheapest
  // (program, level) pair within max_error (ChooseProgramAndLevel); an order fixes it (the level is
  // then still picked by max_error unless `level` is set). With `level` set, nullopt means order2,
  // the paper's program.
  std::optional<ShOrder> order;
  ShWindow window = ShWindow::kNone;  // applied to every level's coefficients
  double window_width = kDefaultWindowWidth;  // bands, for hanning and lanczos
  std::filesystem::path out_dir = "out";
  std::string engine = "jit";       // a registered engine (vm/engines/engine_factory.h); "gl" needs vm/gl's
                                    // RegisterGlEngine
  EngineSettings engine_settings{}; // the engine's own options (--engine gl --gl-device N: vm/gl's GlOptions)
  int threads = 0;                  // 0: std::thread::hardware_concurrency()
  int map_size = kDefaultMapSize;   // irradiance cube map face size, 1..kMaxMapSize
  int error_normals = kDefaultErrorNormals;
  int sphere_diameter = 192;        // preview spheres, pixels (>= 16)
  std::filesystem::path font;       // preview labels; empty = kDefaultPreviewFont
  // Only coeffs.json (without the error columns) and constants.vsh: no irradiance map, ground truth,
  // error table or preview, and each level's update is run once instead of repeated for timing.
  bool coefficients_only = false;
  // No brute-force ground truth (most of a default run's time): no error columns and no preview;
  // coeffs.json, constants.vsh and irradiance.exr are still written.
  bool no_ground_truth = false;
  // --face-size was given: a cube-map file, which keeps its own face size, then gets a warning.
  bool face_size_given = false;
  // An environment already in memory (the Python module's arrays), used instead of loading
  // `environment`, which then only names it in the report; `layout` is what it was made from.
  std::optional<CubeMap> cube;
  // Or a lat-long map in memory (sanitised, width == 2 height), projected in place as a loaded one is.
  std::optional<Image> latlong;
  // False: no file is written and out_dir is not used; the results are in the report only.
  bool write_files = true;
  // How option errors and warnings name an option: "--max-error 2" (the tool) or "max_error=2" (Python).
  OptionNaming naming = OptionNaming::kFlag;
  // --mesh: also light this mesh (irradiance/jobs/mesh_lighting.h) and write mesh.ply and mesh.png, with
  // its statistics under "mesh" in coeffs.json.
  std::optional<MeshGeometry> mesh;
  std::size_t mesh_truth_vertex_limit = kDefaultMeshTruthVertexLimit;
  int mesh_panel_size = kMeshPanelSize;  // pixels of each of mesh.png's three panels
  // --map-format: the irradiance cube map's file (kMapFileFormatNames, irradiance/io/map_file_formats.h).
  MapFileFormat map_format = MapFileFormat::kExr;
  // --sh-export: also the nine coefficients in these engines' conventions and frames, one file each
  // (ShExportFileName files, irradiance/sh/engine_sh.h); a format named twice is written once.
  std::vector<ShExportFormat> sh_exports;
  // Where set, the basis pyramid of a face size comes from here instead of being built (irrmap
  // batch shares one per face size between its inputs); null from it: cannot be built.
  std::function<std::shared_ptr<const BasisPyramid>(int face_size)> shared_basis;
  // Where set (irrmap --engine gl), the chosen level's frame runs here: the environment's mips, the
  // projection, the constants and the irradiance map's program, on the GPU; coeffs.json's
  // "coefficients" and "constants" are then the GPU's, and its "gpu" says which stages ran there.
  GpuFrameHook gpu_frame;
};

// The mesh's line in coeffs.json ("mesh": {...}).
struct MeshReport {
  std::string file;
  std::size_t vertex_count = 0;
  std::size_t triangle_count = 0;
  double ms_per_evaluation = 0.0;  // the program over every vertex, engine run only
  std::size_t unusable_normals = 0;  // zero or non-finite normals, left out of `error`
  bool has_truth = false;
  ErrorStats error;                // against the exact irradiance per vertex normal
  double exposure = 0.0;
  double error_scale = 0.0;
};

// Whether files can be created in `out_dir` (or in the folder that would hold it, when it does
// not exist yet): success if so, else why not (kCannotWriteFile). Checked before any work, so that
// a bad --out fails at once rather than after the whole job.
Status CheckOutputFolder(const std::filesystem::path& out_dir);

// Whether a file this run may write into out_dir is one of its inputs (the environment file, each
// face file of a "{face}" pattern, `mesh_file`), which it would replace: "OUTPUT is the input INPUT:
// refusing to overwrite it" (kOutputOverwritesInput), or success. Same file means same inode,
// through links and spellings.
Status CheckOutputsAreNotInputs(const IrrmapOptions& options, const std::filesystem::path& mesh_file);

// One row of the level table.
struct LevelReport {
  int level = 0;
  int size = 0;            // face size at this level
  double update_ms = 0.0;  // ProjectLevel alone (the mips are not included), mean of repeated runs
  ErrorStats error;        // the vertex program's irradiance against the ground truth
  Sh9Rgb coefficients;     // windowed when a window is set
  double estimated_error = 0.0;  // against level 0, from this level and the next finer (EstimateLevelErrors)
  std::array<double, kSh9Bands> window_factors = {1.0, 1.0, 1.0};
  bool chosen = false;
};

struct Timing {
  std::string name;
  double ms = 0.0;
};

struct IrrmapReport {
  ErrorMetric error_metric = kDefaultErrorMetric;  // what the estimates and max_error measure
  int error_normals = 0;         // the normals of every level's `error` (when errors_measured)
  bool errors_measured = false;  // the levels' errors against the ground truth (not with --no-ground-truth)
  std::string environment;  // "sky (built-in)" or the path
  std::string layout;       // "builtin" or the layout read
  std::string layout_reason;  // why that layout (LoadedEnvironment::layout_reason)
  // The job failed for something the caller must fix in its options, not in the input (a square
  // image whose layout must be named): a usage error.
  bool usage_error = false;
  // How engines see that input, which decides each --sh-export's frame (irradiance/sh/engine_sh.h).
  ShSourceKind sh_source = ShSourceKind::kCube;
  int face_size = 0;
  std::vector<InputFileDigest> input_files;  // every file read (none for a built-in or an array)
  TexelRange texel_range;   // of the environment's cube map, named when a result is beyond float range
  int level = 0;            // the chosen level
  int threads = 0;          // worker threads used
  Sh9Rgb coefficients;      // of the chosen level
  SevenConstants constants;  // PackTable1 of them
  // The chosen program and its constants (PackShOrder of `coefficients`), what its estimate said,
  // and every (program, level) estimate.
  ShOrder order = ShOrder::kOrder2;
  double order_estimated_error = 0.0;
  std::vector<NamedRegister> program_constants;
  std::vector<ProgramLevelEstimate> program_estimates;
  // The chosen program's irradiance against the ground truth (not with coefficients_only), and
  // against order 2 at level 0 (IrradianceDifference, always).
  ErrorStats program_error;
  double program_vs_full_order2 = 0.0;
  std::vector<LevelReport> levels;  // every level, 0 first
  std::vector<Timing> timings;      // in the order the stages ran
  std::vector<std::filesystem::path> files;  // written, once everything succeeded
  std::vector<std::string> warnings;
  std::optional<MeshReport> mesh;
  std::optional<GpuFrameReport> gpu;  // with IrrmapOptions::gpu_frame
  // The preview's estimate panels: the label above each sphere and the caption under its error
  // image, which states the level table's figures for that level (report/preview_errors.h).
  struct PreviewPanelText {
    std::string label;
    std::string caption;
  };
  std::vector<PreviewPanelText> preview_panels;
  CubeMap irradiance_map;  // the chosen program's irradiance cube map (empty with coefficients_only)

  // The time of a stage, or 0 when it did not run.
  double TimingMs(std::string_view name) const;
};

// Progress of the long stages: `stage` is a short name ("ground truth"), `fraction` in [0, 1] never
// decreases within a stage and reaches 1.
using IrrmapProgress = std::function<void(std::string_view stage, double fraction)>;

// What is wrong with the options' own values (a usage error: an unknown name, a number out of
// range; kOptionValue or kFaceSize), or success; RunIrrmap checks them first, then the environment
// and the output folder.
Status CheckIrrmapOptions(const IrrmapOptions& options);

// Runs the job. Returns success, or the error that says what is wrong (bad option, unreadable or
// unusable environment, write failure), in which case no output file is left behind (out_dir may
// have been created). Options are checked before any work starts. Whether the caller must fix its
// options rather than the input is report.usage_error.
Status RunIrrmap(const IrrmapOptions& options, IrrmapReport& report, const IrrmapProgress& progress = {});

// The level table, one row per level (the chosen one marked with '*'):
//   level   size     update ms   max rel err   mean rel err   peak err   rms err   est vs lvl 0
// (the errors against the ground truth, as ErrorStats; the estimates in the run's error metric,
// which the line under the table names).
std::string FormatLevelTable(const IrrmapReport& report);
// "load 12.3 ms, env_mips 4.5 ms, ..." one stage per line.
std::string FormatTimings(const IrrmapReport& report);

}  // namespace vs11::irradiance
