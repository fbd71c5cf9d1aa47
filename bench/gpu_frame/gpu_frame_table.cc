// vs11_gpu_frame_bench: the paper's dynamic-lighting experiment (section 3.3, its frame-rate table) on
// today's GPU through OpenGL ES 3.1 compute shaders (irradiance/gpu), one frame being
//
//   upload a 256-face environment that changed (the sun's azimuth advances 45 degrees a frame; the 8
//   skies are made before timing) -> its mips down to the level -> the projection -> the seven
//   constants -> the paper's program over the vertices -> glFinish
//
// for level 0 (256 x 256), the 64 x 64 level and the 16 x 16 level, with the vertex count of the
// paper's figure (the 11184 vertices of the Wuson mesh irrmap --mesh lights, as random unit normals)
// and with 2^20 vertices. Nothing is read back during the frames. Prints frames per second (the
// median frame's) beside the paper's GeForce FX 5200 figures, and JSON with --json.
//
// Runs on Mesa's llvmpipe by default; `--gl-device N` picks an EGL device (vm/gl's ListGlDevices, as
// `irrmap --gl-device list` prints them), an NVIDIA GPU through EGL_PLATFORM_DEVICE_EXT for one.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "irradiance/gpu/gpu_frame.h"
#include "irradiance/gpu/program_stage.h"
#include "irradiance/io/environments.h"
#include "irradiance/report/paper_program.h"
#include "vm/gl/gl_context.h"

namespace {

using namespace vs11::irradiance;
using Clock = std::chrono::steady_clock;

constexpr int kFaceSize = 256;  // the paper's environment
constexpr int kSunPositions = 8;
constexpr std::size_t kPaperFigureVertices = 11184;  // Debian's assimp-testmodels Wuson.ply
constexpr std::size_t kMillionVertices = std::size_t{1} << 20;

struct LevelCase {
  const char* name;
  int level;
  double paper_fps;  // GeForce FX 5200, 3.0 GHz PC (the paper's section 3.3)
};
constexpr LevelCase kLevels[] = {{"full 256x256", 0, 34.0}, {"64x64", 2, 45.0}, {"16x16", 4, 56.0}};
constexpr double kPaperCpuFps = 21.0;  // the paper's "traditional CPU computation"

std::vector<glm::vec3> RandomUnitNormals(std::size_t count) {
  std::mt19937_64 random(20080501);
  std::normal_distribution<float> gauss;
  std::vector<glm::vec3> normals(count);
  for (glm::vec3& n : normals) {
    do n = glm::vec3(gauss(random), gauss(random), gauss(random));
    while (glm::length(n) < 1e-3f);
    n = glm::normalize(n);
  }
  return normals;
}

struct Result {
  std::string level;
  int level_index = 0;
  std::size_t vertices = 0;
  double median_ms = 0.0, min_ms = 0.0, max_ms = 0.0;
  // Medians of the same frames run again with glFinish after each stage: where the time goes.
  double upload_ms = 0.0, projection_ms = 0.0, program_ms = 0.0;
  double paper_fps = 0.0;
};

std::optional<Result> Measure(std::optional<int> device, const BasisPyramid& basis, const PaperProgram& paper,
                              const std::vector<CubeMap>& skies, const LevelCase& level,
                              const std::vector<glm::vec3>& normals, int frames, int warmup, std::string& renderer,
                              std::string& error) {
  // Whether `status` succeeded; its message as `error` where not.
  const auto ok = [&error](const vs11::Status& status) {
    if (!status) error = status.message();
    return status.ok();
  };
  vs11::Result<std::unique_ptr<gpu::GpuFrame>> made_frame = gpu::GpuFrame::Create(
      device, basis, level.level, paper.Constants(vs11::SevenConstants{}).size(), paper.constant_base());
  if (!made_frame) {
    error = made_frame.message();
    return std::nullopt;
  }
  const std::unique_ptr<gpu::GpuFrame> frame = std::move(made_frame).value();
  renderer = frame->context().renderer() + " (" + frame->context().version() + ")";
  vs11::Result<std::unique_ptr<gpu::ProgramStage>> made_program = gpu::ProgramStage::Create(*frame, paper, normals);
  if (!made_program) {
    error = made_program.message();
    return std::nullopt;
  }
  const std::unique_ptr<gpu::ProgramStage> program = std::move(made_program).value();
  std::vector<double> times;
  std::array<std::vector<double>, 3> stage_times;  // upload, mips + projection + constants, program
  for (int i = 0; i < warmup + frames; ++i) {
    const CubeMap& sky = skies[static_cast<std::size_t>(i % kSunPositions)];
    Clock::time_point start = Clock::now();
    const auto lap = [&](std::vector<double>& into) {
      const Clock::time_point now = Clock::now();
      if (i >= warmup) into.push_back(std::chrono::duration<double, std::milli>(now - start).count());
      start = now;
    };
    if (!ok(frame->Upload(sky)) || !ok(frame->Finish())) return std::nullopt;
    lap(stage_times[0]);
    if (!ok(frame->Project()) || !ok(frame->Finish())) return std::nullopt;
    lap(stage_times[1]);
    if (!ok(program->Run()) || !ok(frame->Finish())) return std::nullopt;
    lap(stage_times[2]);
  }
  for (int i = 0; i < warmup + frames; ++i) {
    const Clock::time_point start = Clock::now();
    const CubeMap& sky = skies[static_cast<std::size_t>(i % kSunPositions)];
    if (!ok(frame->Upload(sky)) || !ok(frame->Project()) || !ok(program->Run()) || !ok(frame->Finish())) {
      return std::nullopt;
    }
    if (i >= warmup) times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  const auto median = [](std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  };
  std::sort(times.begin(), times.end());
  Result result;
  result.level = level.name;
  result.level_index = level.level;
  result.vertices = normals.size();
  result.median_ms = times[times.size() / 2];
  result.min_ms = times.front();
  result.max_ms = times.back();
  result.upload_ms = median(stage_times[0]);
  result.projection_ms = median(stage_times[1]);
  result.program_ms = median(stage_times[2]);
  result.paper_fps = level.paper_fps;
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The paper's frame-rate table on a GPU: environment upload, mips, projection, constants and the "
               "program per frame, OpenGL ES 3.1 compute (irradiance/gpu)"};
  std::string device_text;
  int frames = 30, warmup = 3;
  std::vector<std::size_t> vertex_counts = {kPaperFigureVertices, kMillionVertices};
  std::string json_file;
  app.add_option("--gl-device", device_text, "EGL device: 'list' prints them; N picks one (default: Mesa's llvmpipe)");
  app.add_option("--frames", frames, "timed frames per case (the median is reported)")->check(CLI::Range(1, 100000));
  app.add_option("--warmup", warmup, "untimed frames first")->check(CLI::Range(0, 1000));
  app.add_option("--vertices", vertex_counts, "vertex counts (default: 11184, the paper's figure's mesh, and 1048576)");
  app.add_option("--json", json_file, "also write the results as JSON here");
  CLI11_PARSE(app, argc, argv);

  if (device_text == "list") {
    const vs11::Result<std::vector<vs11::gl::GlDeviceInfo>> devices = vs11::gl::ListGlDevices();
    if (!devices) {
      fmt::print(stderr, "vs11_gpu_frame_bench: error: {}\n", devices.message());
      return 1;
    }
    fmt::print("{}", vs11::gl::FormatGlDeviceList(*devices));
    return devices->empty() ? 1 : 0;
  }
  std::optional<int> device;
  if (!device_text.empty()) {
    device = vs11::gl::GlDeviceIndex(device_text);
    if (!device) {
      fmt::print(stderr, "vs11_gpu_frame_bench: error: --gl-device {}: expected 'list' or a device number\n", device_text);
      return 2;
    }
  }
  std::string error;
  const vs11::Result<PaperProgram> paper = PaperProgram::Load();
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kFaceSize, 2);
  if (!paper || !basis) {
    fmt::print(stderr, "vs11_gpu_frame_bench: error: {}\n", paper ? "cannot build the basis pyramid" : paper.message());
    return 1;
  }
  std::vector<CubeMap> skies;
  for (int i = 0; i < kSunPositions; ++i) {
    SkyParams sky;
    sky.sun_azimuth_degrees = 360.0 * i / kSunPositions;
    skies.push_back(MakeSky(kFaceSize, sky));
  }

  std::vector<Result> results;
  std::string renderer;
  for (std::size_t count : vertex_counts) {
    const std::vector<glm::vec3> normals = RandomUnitNormals(count);
    for (const LevelCase& level : kLevels) {
      const std::optional<Result> result =
          Measure(device, *basis, *paper, skies, level, normals, frames, warmup, renderer, error);
      if (!result) {
        fmt::print(stderr, "vs11_gpu_frame_bench: error: {} ({} vertices): {}\n", level.name, count, error);
        return 1;
      }
      results.push_back(*result);
    }
  }

  fmt::print("Dynamic frame, 256x256 faces changing every frame, on {}\n", renderer);
  fmt::print("median of {} frames after {} untimed; upload + mips + projection + constants + program + glFinish\n\n",
             frames, warmup);
  fmt::print("| coefficients from | vertices | paper fps (FX 5200) | fps today | ms per frame (median) | min ms | max ms "
             "| upload ms | mips + projection + constants ms | program ms |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|\n");
  fmt::print("| CPU, full (paper's direct method) | paper's | {} | see BM_Frame/direct_cpu | | | | | | |\n", kPaperCpuFps);
  for (const Result& r : results) {
    fmt::print("| {} | {} | {} | {:.1f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n", r.level, r.vertices,
               r.paper_fps, 1000.0 / r.median_ms, r.median_ms, r.min_ms, r.max_ms, r.upload_ms, r.projection_ms,
               r.program_ms);
  }
  fmt::print("\n(the last three columns: the same frames again with glFinish after each stage, medians)\n");
  if (!json_file.empty()) {
    nlohmann::ordered_json json = {{"renderer", renderer}, {"frames", frames}, {"warmup", warmup}, {"face_size", kFaceSize}};
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const Result& r : results) {
      rows.push_back({{"level", r.level_index}, {"level_name", r.level}, {"vertices", r.vertices},
                      {"median_ms", r.median_ms}, {"min_ms", r.min_ms}, {"max_ms", r.max_ms},
                      {"fps", 1000.0 / r.median_ms}, {"paper_fps", r.paper_fps}, {"upload_ms", r.upload_ms},
                      {"projection_ms", r.projection_ms}, {"program_ms", r.program_ms}});
    }
    json["cases"] = std::move(rows);
    std::ofstream(json_file) << json.dump(2) << "\n";
  }
  return 0;
}
