// The paper's dynamic-lighting experiment (section 3.3), one frame per iteration (wall time):
//
//   the sky changes (the sun's azimuth advances 45 degrees a frame)
//   -> [mip methods] its mip pyramid, refilled in place (RefillEnvironmentMips: no allocation)
//   -> nine coefficients -> the seven Table 1 constants -> the program over a 100 000-vertex mesh
//
//   BM_Frame/direct_cpu  ProjectScalarDouble at full resolution + EvalTable1Scalar per vertex (no VM);
//                        recomputes every texel's direction, basis and solid angle each frame
//   BM_Frame/plain_cpu   ProjectPlainLoop (full resolution, the precomputed solid angles vm_full
//                        reads) + EvalTable1Scalar per vertex (no VM)
//   BM_Frame/vm_full     ProjectLevel level 0 (no mip pyramid needed) + batch engine running
//                        programs/sh9_irradiance.vsh
//   BM_Frame/vm_64       mip pyramid + ProjectLevel of the 64 x 64 level + batch engine
//   BM_Frame/vm_16       mip pyramid + ProjectLevel of the 16 x 16 level + batch engine
//
// Regenerating the sky (MakeSky at 256, about 60 ms; BM_SkyGeneration/256) would dominate every
// frame, so kSunPositions skies are generated before timing and the frames cycle through them.
// Counter error_mean_rel: mean relative irradiance error (CompareIrradiance, floor 1 %) of what the
// case computes for the first sky, on 1000 sphere normals, against GroundTruthIrradiance;
// computed once, outside the timed loop.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "bench/irradiance/projection_fixture.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"

namespace vs11::bench {
namespace {

constexpr int kFrameFaceSize = 256;
constexpr int kSunPositions = 8;
constexpr double kSunStepDegrees = 360.0 / kSunPositions;
constexpr std::size_t kMeshVertices = 100000;
constexpr int kErrorNormals = 1000;
constexpr int kGroundTruthThreads = 2;

enum class FrameCase { kDirectCpu, kPlainCpu, kVmFull, kVm64, kVm16 };

bool RunsTheVm(FrameCase c) { return c != FrameCase::kDirectCpu && c != FrameCase::kPlainCpu; }

struct FrameFixture {
  std::vector<irradiance::CubeMap> skies;              // one per sun position
  std::vector<irradiance::CubeMipChain> single_level;  // {sky}: all that level 0 needs
  irradiance::BasisPyramid basis;
  Program program;
  std::vector<glm::dvec3> error_normals;
  std::vector<glm::dvec3> truth;  // ground truth of skies[0] at error_normals
};

const FrameFixture& GetFrameFixture() {
  static const FrameFixture fixture = [] {
    FrameFixture f;
    for (int i = 0; i < kSunPositions; ++i) {
      irradiance::SkyParams params;
      params.sun_azimuth_degrees = i * kSunStepDegrees;
      f.skies.push_back(irradiance::MakeSky(kFrameFaceSize, params));
      f.single_level.push_back(irradiance::CubeMipChain{{f.skies.back()}});
    }
    f.basis = SkyFixture(kFrameFaceSize).basis;
    f.program = *LoadBenchProgram(ProgramPath("sh9_irradiance.vsh")).program;
    f.error_normals = vs11::SphereNormals(kErrorNormals);
    f.truth = irradiance::GroundTruthIrradiance(f.skies[0], f.error_normals, kGroundTruthThreads);
    return f;
  }();
  return fixture;
}

int LevelOf(FrameCase c) {
  switch (c) {
    case FrameCase::kVm64:
      return irradiance::LevelCount(kFrameFaceSize) - irradiance::LevelCount(64);
    case FrameCase::kVm16:
      return irradiance::LevelCount(kFrameFaceSize) - irradiance::LevelCount(16);
    default:
      return 0;
  }
}

// The coefficient step of one frame for sky `index`; `mips` is the pyramid the mip cases refill
// every frame.
vs11::Sh9Rgb FrameCoefficients(const FrameFixture& f, FrameCase c, int index, irradiance::CubeMipChain& mips) {
  const int level = LevelOf(c);
  if (c == FrameCase::kDirectCpu) return ProjectScalarDouble(f.skies[index]);
  if (c == FrameCase::kPlainCpu) return ProjectPlainLoop(f.skies[index], f.basis.finest);
  if (level == 0) return irradiance::ProjectLevel(f.single_level[index], f.basis, 0);
  irradiance::RefillEnvironmentMips(f.skies[index], mips);
  return irradiance::ProjectLevel(mips, f.basis, level);
}

// The per-vertex step: the program on the batch engine, or the scalar C++ polynomial.
class VertexStep {
 public:
  VertexStep(const FrameFixture& f, FrameCase c, const SoaNormals& normals)
      : vm_(RunsTheVm(c)), normals_(normals) {
    if (vm_) {
      inputs_ = NormalInputs(normals);
      outputs_ = MakeOutputArrays(normals.size(), f.program);
      engine_ = MakeEngine("batch", f.program, ConstantBank(), EngineOptions{.threads = 1}).value();
    } else {
      r_.resize(normals.size());
      g_.resize(normals.size());
      b_.resize(normals.size());
    }
  }

  void Run(const vs11::SevenConstants& constants) {
    if (vm_) {
      // The batch engine never fails: its calls return the empty Status.
      (void)engine_->SetConstants(Table1Bank(constants));
      (void)engine_->Run(inputs_, outputs_);
    } else {
      EvalTable1Scalar(constants, normals_.x.data(), normals_.y.data(), normals_.z.data(), r_.data(), g_.data(),
                       b_.data(), normals_.size());
    }
  }

  glm::dvec3 Result(std::size_t i) const {
    if (!vm_) return {r_[i], g_[i], b_[i]};
    const int slot = static_cast<int>(OutputSlot::kDiffuse);
    return {outputs_.lane(slot, 0)[i], outputs_.lane(slot, 1)[i], outputs_.lane(slot, 2)[i]};
  }

 private:
  bool vm_;
  const SoaNormals& normals_;
  VertexArrays inputs_, outputs_;
  std::unique_ptr<Engine> engine_;
  std::vector<float> r_, g_, b_;
};

double MeanRelativeError(const FrameFixture& f, FrameCase c) {
  SoaNormals normals;
  for (const glm::dvec3& n : f.error_normals) {
    normals.x.push_back(static_cast<float>(n.x));
    normals.y.push_back(static_cast<float>(n.y));
    normals.z.push_back(static_cast<float>(n.z));
  }
  VertexStep step(f, c, normals);
  irradiance::CubeMipChain mips;
  step.Run(vs11::PackTable1(FrameCoefficients(f, c, 0, mips)));
  std::vector<glm::dvec3> estimate(normals.size());
  for (std::size_t i = 0; i < estimate.size(); ++i) estimate[i] = step.Result(i);
  return irradiance::CompareIrradiance(estimate, f.truth).mean_relative;
}

void BM_Frame(benchmark::State& state, FrameCase c) {
  const FrameFixture& f = GetFrameFixture();
  const double error = MeanRelativeError(f, c);
  const SoaNormals mesh = RandomUnitNormals(kMeshVertices);
  VertexStep step(f, c, mesh);
  irradiance::CubeMipChain mips;  // shaped by the first frame, refilled by every later one
  int frame = 0;
  for (auto _ : state) {
    step.Run(vs11::PackTable1(FrameCoefficients(f, c, frame, mips)));
    frame = (frame + 1) % kSunPositions;
    benchmark::ClobberMemory();
  }
  state.counters["error_mean_rel"] = error;
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Frame, direct_cpu, FrameCase::kDirectCpu)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, plain_cpu, FrameCase::kPlainCpu)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, vm_full, FrameCase::kVmFull)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, vm_64, FrameCase::kVm64)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, vm_16, FrameCase::kVm16)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vs11::bench
