#include "irradiance/jobs/mesh_lighting.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/render/mesh_raster.h"
#include "irradiance/render/preview.h"
#include "irradiance/report/preview_errors.h"
#include "vm/engines/engine_factory.h"

namespace vs11::irradiance {
namespace {

using Clock = std::chrono::steady_clock;

// Engine runs timed for ms_per_evaluation: at least this many, and until this much time went by.
constexpr int kMinTimedRuns = 3;
constexpr double kMinTimedMs = 50.0;
constexpr int kMaxTimedRuns = 200;
constexpr glm::vec3 kBackground{0.04f, 0.04f, 0.045f};
constexpr int kPanelGap = 8;

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Runs the program over every vertex normal; returns the irradiance and the engine's time per run.
Result<std::vector<glm::dvec3>> EvaluateProgram(const MeshGeometry& mesh, const PaperProgram& program,
                                                const SevenConstants& constants, const MeshLightingOptions& options,
                                                double& ms_per_evaluation) {
  const std::size_t n = mesh.normals.size();
  const std::array<int, 1> registers = {program.normal_register()};
  VertexArrays inputs = MakeInputArrays(n, registers);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 normal(mesh.normals[i]);
    const double length = glm::length(normal);
    const glm::dvec3 unit = length > 0.0 ? normal / length : normal;
    for (int c = 0; c < 3; ++c) inputs.lane(program.normal_register(), c)[i] = static_cast<float>(unit[c]);
  }
  VertexArrays outputs = MakeOutputArrays(n, program.program());
  Result<std::unique_ptr<Engine>> engine =
      MakeEngine(options.engine, program.program(), program.Constants(constants), options.engine_options);
  if (!engine) return engine.error();
  std::vector<double> times;
  const Clock::time_point start = Clock::now();
  while (static_cast<int>(times.size()) < kMaxTimedRuns &&
         (static_cast<int>(times.size()) < kMinTimedRuns ||
          std::chrono::duration<double, std::milli>(Clock::now() - start).count() < kMinTimedMs)) {
    const Clock::time_point run = Clock::now();
    if (Status ran = (*engine)->Run(inputs, outputs); !ran) return ran.error();
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - run).count());
  }
  ms_per_evaluation = Median(times);
  std::vector<glm::dvec3> irradiance(n);
  for (int c = 0; c < 3; ++c) {
    const float* lane = outputs.lane(program.output_slot(), c);
    for (std::size_t i = 0; i < n; ++i) irradiance[i][c] = lane[i];
  }
  return irradiance;
}

// E / pi is the radiance of a white diffuse surface; the brightest vertex is shown at kSphereWhite.
std::vector<glm::vec3> DisplayValues(std::span<const glm::dvec3> irradiance, double exposure) {
  std::vector<glm::vec3> values;
  values.reserve(irradiance.size());
  for (const glm::dvec3& e : irradiance) values.push_back(glm::vec3(glm::clamp(exposure * e, 0.0, 1.0)));
  return values;
}

void Blit(const Image& source, Image& target, int x0) {
  for (int y = 0; y < source.height; ++y) {
    for (int x = 0; x < source.width; ++x) target.at(x0 + x, y) = source.at(x, y);
  }
}

}  // namespace

Result<MeshLighting> LightMesh(const MeshGeometry& mesh, const PaperProgram& program, const SevenConstants& constants,
                               const CubeMap& environment, const MeshLightingOptions& options) {
  assert(mesh.normals.size() == mesh.positions.size());
  MeshLighting result;
  Result<std::vector<glm::dvec3>> evaluated =
      EvaluateProgram(mesh, program, constants, options, result.ms_per_evaluation);
  if (!evaluated) return evaluated.error();
  result.irradiance = std::move(evaluated).value();

  const std::size_t n = mesh.positions.size();
  // Vertices whose normal is zero or not finite have no direction to light: they are drawn black
  // and left out of the error statistics, with a warning.
  std::vector<glm::dvec3> unit_normals(n, glm::dvec3(0.0));
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 normal(mesh.normals[i]);
    const double length = glm::length(normal);
    if (std::isfinite(length) && length > 0.0) {
      unit_normals[i] = normal / length;
      usable.push_back(i);
    } else {
      result.irradiance[i] = glm::dvec3(0.0);
    }
  }
  result.unusable_normals = n - usable.size();
  if (result.unusable_normals > 0) {
    result.warnings.push_back(fmt::format("{}: {} vertices have a zero or non-finite normal: drawn black, left out "
                                          "of the error statistics", mesh.name, result.unusable_normals));
  }

  const bool with_truth = options.truth_vertex_limit == 0 || n <= options.truth_vertex_limit;
  if (with_truth) {
    const Clock::time_point start = Clock::now();
    result.truth = GroundTruthIrradiance(environment, unit_normals, std::max(1, options.threads));
    result.truth_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    std::vector<glm::dvec3> estimate, truth, normals;
    for (std::size_t i : usable) {
      estimate.push_back(result.irradiance[i]);
      truth.push_back(result.truth[i]);
      normals.push_back(unit_normals[i]);
    }
    result.error = CompareIrradiance(estimate, truth, normals, kPreviewErrorFloor);
    double brightest = 0.0;
    for (const glm::dvec3& t : truth) brightest = std::max({brightest, std::abs(t.r), std::abs(t.g), std::abs(t.b)});
    result.relative_error.assign(n, 0.0);
    for (std::size_t i : usable) {
      result.relative_error[i] = RelativeError(result.irradiance[i], result.truth[i], kPreviewErrorFloor * brightest);
    }
  } else {
    result.warnings.push_back(fmt::format(
        "{}: {} vertices, more than the exact-irradiance limit of {}: no ground truth, mesh.png shows the lit "
        "mesh alone and coeffs.json no mesh errors (--mesh-truth-limit 0 computes it anyway)",
        mesh.name, n, options.truth_vertex_limit));
  }

  double brightest = 0.0;
  for (const auto* set : {&result.irradiance, &result.truth}) {
    for (const glm::dvec3& e : *set) brightest = std::max({brightest, e.r, e.g, e.b});
  }
  result.exposure = brightest > 0.0 ? kSphereWhite / brightest : 1.0;
  const std::vector<glm::vec3> lit = DisplayValues(result.irradiance, result.exposure);
  for (const glm::vec3& v : lit) {
    result.display_colors.push_back({static_cast<float>(LinearToSrgb(v.r)), static_cast<float>(LinearToSrgb(v.g)),
                                     static_cast<float>(LinearToSrgb(v.b)), 1.0f});
  }

  const int panel = options.panel_size;
  const MeshView view = FrameBoundingBox(mesh.positions, panel, panel);
  const int panels = with_truth ? 3 : 1;
  result.picture = Image(panels * panel + (panels - 1) * kPanelGap, panel, glm::vec3(0.0f));
  Blit(RasterizeMesh(mesh.positions, lit, mesh.indices, view, kBackground).color, result.picture, 0);
  if (with_truth) {
    Blit(RasterizeMesh(mesh.positions, DisplayValues(result.truth, result.exposure), mesh.indices, view, kBackground)
             .color,
         result.picture, panel + kPanelGap);
    result.error_scale = std::max(result.error.max_relative, kMinPreviewErrorScale);
    std::vector<glm::vec3> ramp;
    for (double e : result.relative_error) ramp.push_back(ErrorRamp(e / result.error_scale));
    Blit(RasterizeMesh(mesh.positions, ramp, mesh.indices, view, kBackground).color, result.picture,
         2 * (panel + kPanelGap));
  }
  return result;
}

}  // namespace vs11::irradiance
