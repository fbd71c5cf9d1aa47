// Cost per environment change of making the nine terms non-negative (wall time, UseRealTime), from
// the coefficients of a spot light of the given radius (64 x 64 faces, projected once):
//
//   BM_NonNegativeFit/<radius>   FitNonNegative (irradiance/sh/nonneg_fit.h): the constrained fit
//   BM_Dering/<radius>           DeringLambda + ApplyShWindow: Sloan's deringing window, for scale
//   BM_NonNegativeFit/0          the default sky, which needs no fit (the check alone)
//   BM_ProgramChoice             EstimateProgramLevelErrors + ChooseProgramAndLevel for the levels
//                                of the 256 sky (what --max-error adds to an update)

#include <benchmark/benchmark.h>

#include <vector>

#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/nonneg_fit.h"
#include "irradiance/sh/sh_order.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::bench {
namespace {

constexpr int kFaceSize = 64;

vs11::Sh9Rgb Coefficients(double radius) {
  if (radius <= 0.0) return irradiance::ProjectDirect(irradiance::MakeSky(kFaceSize));
  irradiance::SpotParams params;
  params.angular_radius_degrees = radius;
  return irradiance::ProjectDirect(irradiance::MakeSpot(kFaceSize, params));
}

void BM_NonNegativeFit(benchmark::State& state) {
  const vs11::Sh9Rgb sh = Coefficients(static_cast<double>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance::FitNonNegative(sh));
}
BENCHMARK(BM_NonNegativeFit)->Arg(0)->Arg(20)->Arg(3)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Dering(benchmark::State& state) {
  const vs11::Sh9Rgb sh = Coefficients(static_cast<double>(state.range(0)));
  const std::vector<glm::dvec3> normals = vs11::SphereNormals(irradiance::kNonNegativeFitNormals);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        irradiance::ApplyShWindow(sh, irradiance::LaplacianWindowFactors(irradiance::DeringLambda(sh, normals))));
  }
}
BENCHMARK(BM_Dering)->Arg(0)->Arg(20)->Arg(3)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_ProgramChoice(benchmark::State& state) {
  const std::optional<irradiance::CubeMipChain> mips = irradiance::BuildEnvironmentMips(irradiance::MakeSky(256));
  const std::optional<irradiance::BasisPyramid> basis = irradiance::BuildBasisPyramid(256);
  std::vector<vs11::Sh9Rgb> levels;
  for (int k = 0; k < irradiance::LevelCount(256); ++k) levels.push_back(irradiance::ProjectLevel(*mips, *basis, k));
  const std::vector<glm::dvec3> normals = vs11::SphereNormals(irradiance::kLevelErrorNormals);
  for (auto _ : state) {
    const std::vector<double> estimated = irradiance::EstimateLevelErrors(levels, normals, irradiance::kDefaultErrorMetric);
    const std::vector<irradiance::ProgramLevelEstimate> pairs =
        irradiance::EstimateProgramLevelErrors(levels, estimated, normals, irradiance::kDefaultErrorMetric);
    benchmark::DoNotOptimize(irradiance::ChooseProgramAndLevel(pairs, estimated, irradiance::kDefaultMaxLevelError));
  }
}
BENCHMARK(BM_ProgramChoice)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vs11::bench
