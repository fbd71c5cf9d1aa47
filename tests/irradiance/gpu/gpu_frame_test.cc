// The GPU frame (irradiance/gpu) on Mesa's llvmpipe or whatever OpenGL ES 3.1 device EGL gives: its
// coefficients against irradiance/sh's CPU projection within the bound of a parallel float sum
// (GpuProjectionErrorFactor), its constants against Table 1 of them, its program against the jit with
// the same constants, a dynamic environment frame after frame, and irrmap's job with the hook. Every
// test here is skipped (ctest entry vs11_tests.gpu_frame, SKIPPED) where no OpenGL ES 3.1 context can be
// had, and fails on any other problem.
#include "irradiance/gpu/gpu_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/gpu/gpu_frame_job.h"
#include "irradiance/gpu/program_stage.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/run_tool.h"
#include "vm/gl/gl_compute.h"
#include "vm/gl/gl_engine.h"

namespace vs11::irradiance::gpu {
namespace {

constexpr double kUnitRoundoff = 0x1p-24;

// Why no OpenGL ES 3.1 context can be had here, or nullopt.
std::optional<std::string> NoEs31Context() {
  const Result<std::unique_ptr<vs11::gl::GlContext>> context = vs11::gl::GlContext::Create(std::nullopt);
  if (!context) return context.message();
  if (!vs11::gl::OffersCompute(**context)) {
    return fmt::format("'{}' offers '{}'", (*context)->renderer(), (*context)->version());
  }
  return std::nullopt;
}

#define SKIP_WITHOUT_ES31()                                                                \
  do {                                                                                     \
    static const std::optional<std::string> why_not = NoEs31Context();                      \
    if (why_not) GTEST_SKIP() << "no OpenGL ES 3.1 context: " << *why_not;                \
  } while (false)

struct Cpu {
  CubeMipChain mips;
  BasisPyramid basis;
};

Cpu CpuPyramids(const CubeMap& environment) {
  std::optional<CubeMipChain> mips = BuildEnvironmentMips(environment);
  std::optional<BasisPyramid> basis = BuildBasisPyramid(environment.face_size);
  EXPECT_TRUE(mips && basis);
  return {std::move(*mips), std::move(*basis)};
}

PaperProgram Paper() {
  Result<PaperProgram> program = PaperProgram::Load();
  EXPECT_TRUE(program) << program.message();
  return std::move(program).value();
}

std::unique_ptr<GpuFrame> MakeFrame(const BasisPyramid& basis, int level) {
  const PaperProgram paper = Paper();
  Result<std::unique_ptr<GpuFrame>> frame =
      GpuFrame::Create(std::nullopt, basis, level, paper.Constants(SevenConstants{}).size(), paper.constant_base());
  EXPECT_TRUE(frame) << frame.message();
  return frame ? std::move(frame).value() : nullptr;
}

// An environment's CPU pyramids and a GPU frame for one of its levels.
struct Setup {
  Cpu cpu;
  std::unique_ptr<GpuFrame> frame;
};

Setup SetUpFrame(const CubeMap& environment, int level) {
  Cpu cpu = CpuPyramids(environment);
  std::unique_ptr<GpuFrame> frame = MakeFrame(cpu.basis, level);
  return {std::move(cpu), std::move(frame)};
}

Sh9Rgb ProjectOnGpu(GpuFrame& frame, const CubeMap& environment) {
  const Status uploaded = frame.Upload(environment);
  EXPECT_TRUE(uploaded) << uploaded.message();
  const Status projected = frame.Project();
  EXPECT_TRUE(projected) << projected.message();
  const Result<Sh9Rgb> sh = frame.ReadCoefficients();
  EXPECT_TRUE(sh) << sh.message();
  return sh ? *sh : Sh9Rgb{};
}

// B_lm,c of GpuProjectionErrorFactor: the sum of the absolute values of every term of each
// coefficient, in double, over the CPU's pyramid level.
std::array<glm::dvec3, kSh9Coefficients> AbsoluteTermSums(const Cpu& cpu, int level) {
  const CubeMap& map = cpu.mips.levels[static_cast<std::size_t>(level)];
  const std::vector<float> moments = LevelBlockMoments(cpu.basis, level);
  const BlockMomentCombination factors = BlockMomentCombinationFactors();
  const std::size_t texels = static_cast<std::size_t>(map.face_size) * map.face_size;
  std::array<glm::dvec3, kSh9Coefficients> sums{};
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (int j = 0; j < kernels::kBlockMoments; ++j) {
      glm::dvec3 face_sum(0.0);
      for (std::size_t i = 0; i < texels; ++i) {
        face_sum += glm::abs(glm::dvec3(map.faces[f].pixels[i])) * std::abs(double(moments[j * texels + i]));
      }
      for (int lm = 0; lm < kSh9Coefficients; ++lm) sums[lm] += std::abs(factors[f][lm][j]) * face_sum;
    }
  }
  return sums;
}

// Every coefficient within GpuProjectionErrorFactor x B of the CPU's; returns the largest fraction of
// its bound that a difference used.
double ExpectWithinBound(const Sh9Rgb& gpu, const Sh9Rgb& cpu_sh, const Cpu& cpu, int level, const std::string& what) {
  const double factor = GpuProjectionErrorFactor(cpu.basis.face_size, level);
  const std::array<glm::dvec3, kSh9Coefficients> b = AbsoluteTermSums(cpu, level);
  double used = 0.0;
  for (int lm = 0; lm < kSh9Coefficients; ++lm) {
    for (int c = 0; c < 3; ++c) {
      const double difference = std::abs(gpu.coefficients[lm][c] - cpu_sh.coefficients[lm][c]);
      const double bound = factor * b[lm][c];
      EXPECT_LE(difference, bound) << what << " coefficient " << lm << " channel " << c << ": GPU "
                                   << gpu.coefficients[lm][c] << ", CPU " << cpu_sh.coefficients[lm][c];
      if (bound > 0.0) used = std::max(used, difference / bound);
    }
  }
  return used;
}

using Case = std::tuple<std::string, int, int>;  // environment, face size, level

class GpuFrameProjection : public ::testing::TestWithParam<Case> {};

TEST_P(GpuFrameProjection, AgreesWithCpuProjectionWithinTheFloatSumBound) {
  SKIP_WITHOUT_ES31();
  const auto& [name, face_size, level] = GetParam();
  const std::optional<CubeMap> environment = MakeBuiltinEnvironment(name, face_size);
  ASSERT_TRUE(environment);
  const auto [cpu, frame] = SetUpFrame(*environment, level);
  ASSERT_TRUE(frame);
  const Sh9Rgb cpu_sh = ProjectLevel(cpu.mips, cpu.basis, level);
  const Sh9Rgb gpu_sh = ProjectOnGpu(*frame, *environment);
  const double used = ExpectWithinBound(gpu_sh, cpu_sh, cpu, level, name);
  // The bound is not vacuous: against the largest coefficient it is a few parts in a million.
  const double factor = GpuProjectionErrorFactor(face_size, level);
  EXPECT_LT(factor, 1e-4);
  RecordProperty("fraction_of_bound_used", fmt::format("{:.3f}", used));
}

INSTANTIATE_TEST_SUITE_P(Builtins, GpuFrameProjection,
                         ::testing::Combine(::testing::Values("constant", "gradient", "sky", "spot", "studio"),
                                            ::testing::Values(64), ::testing::Values(0, 2, 4)));
INSTANTIATE_TEST_SUITE_P(PaperSize, GpuFrameProjection,
                         ::testing::Values(Case{"sky", 256, 0}, Case{"studio", 256, 2}, Case{"spot", 256, 4},
                                           Case{"sky", 1, 0}));

TEST(GpuFrame, ConstantsAreTable1OfItsCoefficients) {
  SKIP_WITHOUT_ES31();
  const CubeMap environment = MakeStudio(32);
  const auto [cpu, frame] = SetUpFrame(environment, 1);
  ASSERT_TRUE(frame);
  const Sh9Rgb sh = ProjectOnGpu(*frame, environment);
  const Result<SevenConstants> constants = frame->ReadConstants();
  ASSERT_TRUE(constants) << constants.message();
  // The packing's terms by absolute value: L20 negated makes cA.w c0 |L00| + c3 |L20|.
  Sh9Rgb magnitudes = sh;
  for (glm::dvec3& c : magnitudes.coefficients) c = glm::abs(c);
  magnitudes.at(2, 0) = -magnitudes.at(2, 0);
  const SevenConstants expected = PackTable1(sh), scale = PackTable1(magnitudes);
  for (int r = 0; r < 7; ++r) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(constants->registers[r][c], expected.registers[r][c], 4 * kUnitRoundoff * std::abs(scale.registers[r][c]))
          << SevenConstants::kNames[r] << " lane " << c;
    }
  }
}

// Lanes of the program stage's last run that differ from the jit's with the constants the frame holds.
int LanesDifferingFromTheJit(GpuFrame& frame, ProgramStage& stage, const PaperProgram& paper,
                             const std::vector<glm::vec3>& normals) {
  const Result<std::vector<glm::vec3>> gpu = stage.Read();
  const Result<SevenConstants> constants = frame.ReadConstants();
  EXPECT_TRUE(gpu && constants) << gpu.message() << constants.message();
  if (!gpu || !constants) return -1;
  const std::vector<glm::dvec3> inputs(normals.begin(), normals.end());
  const Result<std::vector<glm::dvec3>> evaluated = paper.Irradiance(*constants, inputs, "jit");
  EXPECT_TRUE(evaluated) << evaluated.message();
  if (!evaluated) return -1;
  const std::vector<glm::dvec3>& jit = *evaluated;
  EXPECT_EQ(gpu->size(), jit.size());
  int differing = 0;
  for (std::size_t v = 0; v < std::min(gpu->size(), jit.size()); ++v) {
    for (int c = 0; c < 3; ++c) differing += (*gpu)[v][c] != static_cast<float>(jit[v][c]);
  }
  return differing;
}

TEST(GpuFrame, ProgramMatchesTheJitWithTheSameConstants) {
  SKIP_WITHOUT_ES31();
  const CubeMap environment = MakeSky(16);
  const auto [cpu, frame] = SetUpFrame(environment, 0);
  ASSERT_TRUE(frame);
  const PaperProgram paper = Paper();
  const std::vector<glm::dvec3> normals = SphereNormals(1000);
  const std::vector<glm::vec3> float_normals(normals.begin(), normals.end());
  Result<std::unique_ptr<ProgramStage>> made = ProgramStage::Create(*frame, paper, float_normals);
  ASSERT_TRUE(made) << made.message();
  const std::unique_ptr<ProgramStage> stage = std::move(made).value();
  ProjectOnGpu(*frame, environment);
  ASSERT_EQ(stage->Run().message(), "");
  EXPECT_EQ(LanesDifferingFromTheJit(*frame, *stage, paper, float_normals), 0) << "of " << normals.size() * 3;
}

// The stage binds the frame's bank where it lies (no copy at Create): a later frame's constants reach
// the program's next run.
TEST(GpuFrame, ProgramReadsTheConstantsOfTheLatestFrame) {
  SKIP_WITHOUT_ES31();
  const CubeMap sky = MakeSky(16), spot = MakeSpot(16);
  const auto [cpu, frame] = SetUpFrame(sky, 1);
  ASSERT_TRUE(frame);
  const PaperProgram paper = Paper();
  const std::vector<glm::dvec3> normals = SphereNormals(200);
  const std::vector<glm::vec3> float_normals(normals.begin(), normals.end());
  Result<std::unique_ptr<ProgramStage>> made = ProgramStage::Create(*frame, paper, float_normals);
  ASSERT_TRUE(made) << made.message();
  const std::unique_ptr<ProgramStage> stage = std::move(made).value();
  ProjectOnGpu(*frame, sky);
  ASSERT_EQ(stage->Run().message(), "");
  const Result<std::vector<glm::vec3>> under_sky = stage->Read();
  ASSERT_TRUE(under_sky) << under_sky.message();
  ProjectOnGpu(*frame, spot);
  ASSERT_EQ(stage->Run().message(), "");
  const Result<std::vector<glm::vec3>> under_spot = stage->Read();
  ASSERT_TRUE(under_spot) << under_spot.message();
  EXPECT_NE(*under_sky, *under_spot);
  EXPECT_EQ(LanesDifferingFromTheJit(*frame, *stage, paper, float_normals), 0);
}

TEST(GpuFrame, EachFrameProjectsTheEnvironmentUploadedForIt) {
  SKIP_WITHOUT_ES31();
  const CubeMap sky = MakeSky(32), spot = MakeSpot(32);
  const auto [cpu, frame] = SetUpFrame(spot, 2);
  ASSERT_TRUE(frame);
  const Sh9Rgb first = ProjectOnGpu(*frame, sky);
  const Sh9Rgb second = ProjectOnGpu(*frame, spot);
  EXPECT_NE(first.coefficients[0], second.coefficients[0]);
  ExpectWithinBound(second, ProjectLevel(cpu.mips, cpu.basis, 2), cpu, 2, "spot after sky");
}

IrrmapOptions GlJobOptions() {
  IrrmapOptions options;
  options.environment = "studio";
  options.face_size = 32;
  options.order = ShOrder::kOrder2;
  options.level = 1;
  options.engine = "gl";
  options.no_ground_truth = true;
  options.write_files = false;
  options.gpu_frame = MakeGpuFrameHook(std::nullopt);
  return options;
}

TEST(GpuFrameJob, IrrmapRunsTheFrameOnTheGpu) {
  SKIP_WITHOUT_ES31();
  vs11::gl::RegisterGlEngine();
  IrrmapOptions options = GlJobOptions();
  IrrmapReport gpu_report;
  ASSERT_EQ(RunIrrmap(options, gpu_report).message(), "");
  ASSERT_TRUE(gpu_report.gpu);
  EXPECT_EQ(gpu_report.gpu->stages,
            (std::vector<std::string>{"upload", "env_mips", "projection", "constants", "program"}));
  EXPECT_LT(gpu_report.gpu->max_coefficient_difference, 1e-5);
  options.engine = "jit";
  options.gpu_frame = nullptr;
  IrrmapReport cpu_report;
  ASSERT_EQ(RunIrrmap(options, cpu_report).message(), "");
  EXPECT_FALSE(cpu_report.gpu);
  // The GPU's map: the same polynomial from constants a few float roundings apart.
  double largest = 0.0, difference = 0.0;
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (std::size_t i = 0; i < cpu_report.irradiance_map.faces[f].pixels.size(); ++i) {
      const glm::vec3 a = gpu_report.irradiance_map.faces[f].pixels[i], b = cpu_report.irradiance_map.faces[f].pixels[i];
      largest = std::max(largest, double(std::max({std::abs(b.r), std::abs(b.g), std::abs(b.b)})));
      difference = std::max(difference, double(std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)})));
    }
  }
  EXPECT_LT(difference, 1e-5 * largest);
}

TEST(GpuFrameJob, SaysWhyAWindowedJobProjectsOnTheCpu) {
  SKIP_WITHOUT_ES31();
  vs11::gl::RegisterGlEngine();
  IrrmapOptions options = GlJobOptions();
  options.window = ShWindow::kHanning;
  IrrmapReport report;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  ASSERT_TRUE(report.gpu);
  EXPECT_EQ(report.gpu->stages, std::vector<std::string>{"program"});
  EXPECT_NE(report.gpu->cpu_reason.find("window"), std::string::npos);
  EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(),
                          [](const std::string& w) { return w.find("--engine gl") != std::string::npos; }));
}

// The tool's side: --engine gl sets the hook, and coeffs.json names the stages that ran on the GPU.
TEST(GpuFrameJob, IrrmapToolWritesTheGpuStagesIntoCoeffsJson) {
  SKIP_WITHOUT_ES31();
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) / "gpu_frame_tool";
  std::filesystem::remove_all(out);
  const testing::CommandResult run =
      testing::RunIrrmap("sky --face-size 32 --level 1 --engine gl --no-ground-truth --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(out / "coeffs.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  ASSERT_TRUE(json.contains("gpu")) << json.dump();
  EXPECT_EQ(json["gpu"]["stages"],
            nlohmann::json::array({"upload", "env_mips", "projection", "constants", "program"}));
  EXPECT_LT(json["gpu"]["max_coefficient_difference"].get<double>(), 1e-5);
}

}  // namespace
}  // namespace vs11::irradiance::gpu
