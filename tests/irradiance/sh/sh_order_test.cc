#include "irradiance/sh/sh_order.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/io/environments.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/program_references.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/program.h"

namespace vs11::irradiance {
namespace {

// Float registers against double polynomials: a few float roundings of values of order 1.
constexpr double kPackTolerance = 2e-6;
// The vertex machine's float arithmetic against the double polynomial of its registers.
constexpr double kProgramTolerance = 1e-5;

// The coefficients of a radiance concentrated in direction `d` (a delta of power `power` per channel).
Sh9Rgb DeltaLight(glm::dvec3 d, glm::dvec3 power) {
  const std::array<double, kSh9Coefficients> basis = ShBasis(glm::normalize(d));
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] = basis[i] * power;
  return sh;
}

double Band2Distance(const Sh9Rgb& a, const Sh9Rgb& b, int channel) {
  double sum = 0.0;
  for (int m = -2; m <= 2; ++m) {
    const double d = a.at(2, m)[channel] - b.at(2, m)[channel];
    sum += d * d;
  }
  return std::sqrt(sum);
}

double Largest(const std::vector<glm::dvec3>& values) {
  double largest = 0.0;
  for (const glm::dvec3& v : values) largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest;
}

TEST(ShOrder, NamesRoundTripAndAreOrderedBySlots) {
  int previous_slots = 0;
  for (ShOrder order : kAllShOrders) {
    EXPECT_EQ(ParseShOrder(Info(order).name), order);
    EXPECT_GT(Info(order).slots, previous_slots);
    previous_slots = Info(order).slots;
  }
  EXPECT_FALSE(ParseShOrder("order3").has_value());
  EXPECT_EQ(ShOrderNames(), "order0, order1, zh3, order2");
}

TEST(ShOrder, ReductionDropsWholeBands) {
  const Sh9Rgb sh = RandomCoefficients(7);
  const Sh9Rgb zero = ReduceToOrder(sh, ShOrder::kOrder0);
  const Sh9Rgb one = ReduceToOrder(sh, ShOrder::kOrder1);
  const Sh9Rgb two = ReduceToOrder(sh, ShOrder::kOrder2);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    EXPECT_EQ(two.coefficients[i], sh.coefficients[i]);
    EXPECT_EQ(one.coefficients[i], i < 4 ? sh.coefficients[i] : glm::dvec3(0.0)) << i;
    EXPECT_EQ(zero.coefficients[i], i < 1 ? sh.coefficients[i] : glm::dvec3(0.0)) << i;
  }
}

// One light: band 2 is zonal around the light, and ZH3 finds that axis from band 1 and keeps it all.
TEST(ShOrder, Zh3IsExactForASingleLight) {
  const glm::dvec3 direction = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const Sh9Rgb sh = DeltaLight(direction, {2.0, 1.5, 0.5});
  const glm::dvec3 axis = Zh3Axis(sh);
  EXPECT_NEAR(glm::dot(axis, direction), 1.0, 1e-12);
  const Sh9Rgb zh3 = ReduceToOrder(sh, ShOrder::kZh3);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(zh3.coefficients[i][c], sh.coefficients[i][c], 1e-12) << i;
  }
}

// The zonal coefficient is band 2's projection: scaling it either way moves band 2 further away.
TEST(ShOrder, Zh3CoefficientIsTheBestZonalFitAroundItsAxis) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Sh9Rgb sh = RandomCoefficients(seed);
    const Sh9Rgb zh3 = ReduceToOrder(sh, ShOrder::kZh3);
    for (double scale : {0.98, 1.02}) {
      Sh9Rgb scaled = zh3;
      for (int m = -2; m <= 2; ++m) scaled.at(2, m) *= scale;
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(Band2Distance(zh3, sh, c), Band2Distance(scaled, sh, c) + 1e-15) << seed;
      }
    }
  }
}

TEST(ShOrder, PackedRegistersGiveTheReducedIrradiance) {
  const std::vector<glm::dvec3> normals = SphereNormals(200);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Sh9Rgb sh = RandomCoefficients(seed);
    for (ShOrder order : kAllShOrders) {
      const std::vector<NamedRegister> registers = PackShOrder(sh, order);
      ASSERT_EQ(static_cast<int>(registers.size()), Info(order).constant_registers);
      const Sh9Rgb reduced = ReduceToOrder(sh, order);
      for (const glm::dvec3& n : normals) {
        const glm::dvec3 expected = IrradianceEq7(reduced, n);
        const glm::dvec3 packed = EvaluateShOrder(registers, order, n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(packed[c], expected[c], kPackTolerance) << Info(order).name;
      }
    }
  }
}

TEST(ShOrder, ProgramsHaveTheirSlotsAndComputeTheirRegistersPolynomial) {
  const std::vector<glm::dvec3> normals = SphereNormals(300);
  const Sh9Rgb sh = RandomCoefficients(3);
  for (ShOrder order : kAllShOrders) {
    const Result<PaperProgram> program = PaperProgram::LoadOrder(order);
    ASSERT_TRUE(program) << program.message();
    EXPECT_EQ(ComputeStats(program->program()).slots, Info(order).slots) << Info(order).name;
    const std::vector<NamedRegister> registers = PackShOrder(sh, order);
    for (std::string engine : {"ref", "batch"}) {
      const std::vector<glm::dvec3> actual = program->Irradiance(program->Constants(registers), normals, engine);
      std::vector<glm::dvec3> expected;
      for (const glm::dvec3& n : normals) expected.push_back(EvaluateShOrder(registers, order, n));
      const double scale = Largest(expected);
      for (std::size_t i = 0; i < normals.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(actual[i][c], expected[i][c], kProgramTolerance * scale) << Info(order).name;
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
      ASSERT_EQ(RunIrrmap(options, report), std::nullopt);
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
  options.order = "order1";
  ASSERT_EQ(RunIrrmap(options, report), std::nullopt);
  EXPECT_EQ(report.order, ShOrder::kOrder1);
  EXPECT_GT(report.order_estimated_error, options.max_error);  // the sky needs band 2: reported, not hidden
  options.order = "auto";
  options.level = 1;
  ASSERT_EQ(RunIrrmap(options, report), std::nullopt);
  EXPECT_EQ(report.order, ShOrder::kOrder2);
  options.order = "order3";
  const std::optional<std::string> error = RunIrrmap(options, report);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("unknown order 'order3'"), std::string::npos) << *error;
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
