#include "irradiance/sh/sh_order.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/program.h"
#include "vm/reference/program_references.h"

namespace vs11::irradiance {
namespace {

// The vertex machine's float arithmetic against the double polynomial of its registers.
constexpr double kProgramTolerance = 1e-5;

double Largest(const std::vector<glm::dvec3>& values) {
  double largest = 0.0;
  for (const glm::dvec3& v : values) largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest;
}

TEST(ShOrder, ProgramsHaveTheirSlotsAndComputeTheirRegistersPolynomial) {
  const std::vector<glm::dvec3> normals = SphereNormals(300);
  const Sh9Rgb sh = RandomCoefficients(3);
  for (ShOrder order : kAllShOrders) {
    const Result<PaperProgram> program = PaperProgram::LoadOrder(order);
    ASSERT_TRUE(program) << program.message();
    EXPECT_EQ(ComputeStats(program->program()).slots, Info(order).slots) << ShOrderName(order);
    const std::vector<NamedRegister> registers = PackShOrder(sh, order);
    for (std::string engine : {"ref", "batch"}) {
      const Result<std::vector<glm::dvec3>> evaluated =
          program->Irradiance(program->Constants(registers), normals, engine);
      ASSERT_TRUE(evaluated) << evaluated.message();
      const std::vector<glm::dvec3>& actual = *evaluated;
      std::vector<glm::dvec3> expected;
      for (const glm::dvec3& n : normals) expected.push_back(EvaluateShOrder(registers, order, n));
      const double scale = Largest(expected);
      for (std::size_t i = 0; i < normals.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(actual[i][c], expected[i][c], kProgramTolerance * scale) << ShOrderName(order);
        }
      }
    }
  }
}

TEST(ShOrder, ChoiceTakesTheFewestSlotsThenTheCoarsestLevel) {
  const std::vector<double> levels = {0.0, 0.001, 0.004, 0.02};
  std::vector<ProgramLevelEstimate> pairs;
  // order0 never fits, order1 fits at levels 0 and 1 only, zh3 and order2 wherever the level fits.
  const std::vector<double> order_differences = {0.5, 0.002, 0.001, 0.0};
  for (std::size_t o = 0; o < kAllShOrders.size(); ++o) {
    for (int k = 0; k < 4; ++k) {
      const double extra = kAllShOrders[o] == ShOrder::kOrder1 && k >= 2 ? 0.01 : 0.0;
      pairs.push_back({kAllShOrders[o], k, order_differences[o] + extra, levels[k] + order_differences[o] + extra});
    }
  }
  ProgramChoice choice = ChooseProgramAndLevel(pairs, levels, 0.005);
  EXPECT_EQ(choice.order, ShOrder::kOrder1);
  EXPECT_EQ(choice.level, 1);
  const std::vector<ShOrder> only_two = {ShOrder::kOrder2};
  choice = ChooseProgramAndLevel(pairs, levels, 0.005, only_two);
  EXPECT_EQ(choice.order, ShOrder::kOrder2);
  EXPECT_EQ(choice.level, 2);  // level 3's estimate exceeds 0.5 %
  // A target nothing cheap meets: order 2 at level 0.
  choice = ChooseProgramAndLevel(pairs, levels, 1e-9);
  EXPECT_EQ(choice.order, ShOrder::kOrder2);
  EXPECT_EQ(choice.level, 0);
  // An allowed order that never fits: its level 0, with its estimate.
  const std::vector<ShOrder> only_zero = {ShOrder::kOrder0};
  choice = ChooseProgramAndLevel(pairs, levels, 0.005, only_zero);
  EXPECT_EQ(choice.order, ShOrder::kOrder0);
  EXPECT_EQ(choice.level, 0);
  EXPECT_DOUBLE_EQ(choice.estimated, 0.5);
}

struct PickCase {
  const char* environment;
  ShOrder expected;
};

// The done criterion, at two face sizes: constant -> order0, gradient -> order1, the studio
// and the sky -> order2, the spot -> zh3 (one round light: its band 2 is zonal around it, so ZH3 is
// exact); and each pick meets the target against order 2 at full resolution.
TEST(ShOrder, MaxErrorPicksTheOrderEachBuiltinNeeds) {
  for (int face_size : {64, 128}) {
    for (const PickCase& pick : {PickCase{"constant", ShOrder::kOrder0}, PickCase{"gradient", ShOrder::kOrder1},
                                 PickCase{"sky", ShOrder::kOrder2}, PickCase{"studio", ShOrder::kOrder2},
                                 PickCase{"spot", ShOrder::kZh3}}) {
      IrrmapOptions options;
      options.environment = pick.environment;
      options.face_size = face_size;
      options.coefficients_only = true;
      options.out_dir = std::filesystem::path(testing::TempDir()) / "sh_order_test_out";
      options.threads = 2;
      IrrmapReport report;
      ASSERT_EQ(RunIrrmap(options, report).message(), "");
      EXPECT_EQ(report.order, pick.expected) << pick.environment << " at " << face_size;
      EXPECT_LE(report.program_vs_full_order2, options.max_error) << pick.environment << " at " << face_size;
      std::filesystem::remove_all(options.out_dir);
    }
  }
}

// --order fixes the program (the level still by --max-error); --level alone means the paper's program.
TEST(ShOrder, OrderOptionFixesTheProgram) {
  IrrmapOptions options;
  options.environment = "sky";
  options.face_size = 32;
  options.coefficients_only = true;
  options.out_dir = std::filesystem::path(testing::TempDir()) / "sh_order_test_option";
  options.threads = 2;
  IrrmapReport report;
  options.order = ShOrder::kOrder1;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  EXPECT_EQ(report.order, ShOrder::kOrder1);
  EXPECT_GT(report.order_estimated_error, options.max_error);  // the sky needs band 2: reported, not hidden
  options.order = std::nullopt;
  options.level = 1;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  EXPECT_EQ(report.order, ShOrder::kOrder2);
  std::filesystem::remove_all(options.out_dir);
}

// Without ZH3, the spot needs all of band 2.
TEST(ShOrder, SpotNeedsOrderTwoWhenZh3IsLeftOut) {
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(64);
  ASSERT_TRUE(basis);
  const std::optional<CubeMipChain> mips = BuildEnvironmentMips(*MakeBuiltinEnvironment("spot", 64));
  ASSERT_TRUE(mips);
  std::vector<Sh9Rgb> levels;
  for (int k = 0; k < LevelCount(64); ++k) levels.push_back(ProjectLevel(*mips, *basis, k));
  const std::vector<glm::dvec3> normals = SphereNormals(kLevelErrorNormals);
  const std::vector<double> estimated = EstimateLevelErrors(levels, normals, kDefaultErrorMetric);
  const std::vector<ProgramLevelEstimate> pairs =
      EstimateProgramLevelErrors(levels, estimated, normals, kDefaultErrorMetric);
  const std::vector<ShOrder> bands = {ShOrder::kOrder0, ShOrder::kOrder1, ShOrder::kOrder2};
  EXPECT_EQ(ChooseProgramAndLevel(pairs, estimated, kDefaultMaxLevelError, bands).order, ShOrder::kOrder2);
}

}  // namespace
}  // namespace vs11::irradiance
