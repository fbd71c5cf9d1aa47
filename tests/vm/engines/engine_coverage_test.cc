// What the engine tests cover on this machine. The per-target suites (EngineDifferential,
// BatchEngine, and the irradiance kernels' ProjectionKernels and RowSumKernels) run once per Highway target that this build compiled and this CPU supports; targets
// the CPU lacks (AVX-512 on an AVX2 machine) are silently not run. This test checks that each suite
// is instantiated for exactly the targets the CPU runs, and prints them, the targets left out and
// what the jit engine ran, so that a CI log says what was and was not covered (.ci/run and
// .ci/sanitize print its output after the suite).
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "vm/core/program.h"
#include "vm/engines/jit_compiler.h"

namespace vs11 {
namespace {

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : " ") + name;
  return text.empty() ? "none" : text;
}

// The targets a per-target suite was instantiated for: the "/TARGET" suffixes of its test names.
std::set<std::string> InstantiatedTargets(const std::string& suite) {
  std::set<std::string> targets;
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  for (int s = 0; s < unit.total_test_suite_count(); ++s) {
    const ::testing::TestSuite& test_suite = *unit.GetTestSuite(s);
    const std::string name = test_suite.name();  // "<suite>Group/<suite>" (hwy_gtest.h)
    if (name != suite && !name.ends_with("/" + suite)) continue;
    for (int t = 0; t < test_suite.total_test_count(); ++t) {
      const std::string test = test_suite.GetTestInfo(t)->name();
      targets.insert(test.substr(test.rfind('/') + 1));
    }
  }
  return targets;
}

TEST(EngineCoverage, PerTargetSuitesRunOnEveryTargetThisCpuSupports) {
  std::vector<std::string> compiled, run_here, not_run;
  const std::vector<std::int64_t> supported = hwy::SupportedAndGeneratedTargets();
  for (std::int64_t targets = HWY_TARGETS; targets != 0; targets &= targets - 1) {
    const std::int64_t target = targets & -targets;
    compiled.push_back(hwy::TargetName(target));
    bool runs = false;
    for (std::int64_t s : supported) runs |= s == target;
    (runs ? run_here : not_run).push_back(hwy::TargetName(target));
  }
  std::printf("[ coverage ] Highway targets compiled: %s\n", Join(compiled).c_str());
  std::printf("[ coverage ] Highway kernels (batch engine, SH projection, ground truth) tested on (this CPU): %s\n",
              Join(run_here).c_str());
  std::printf("[ coverage ] NOT tested here (this CPU lacks them): %s\n", Join(not_run).c_str());
  const std::set<std::string> expected(run_here.begin(), run_here.end());
  EXPECT_FALSE(expected.empty());
  // The engines' suites, and the irradiance kernels' (irradiance/sh/projection_kernels.h, row_sum_kernels.h).
  for (const char* suite : {"EngineDifferential", "BatchEngine", "ProjectionKernels", "RowSumKernels"}) {
    EXPECT_EQ(InstantiatedTargets(suite), expected) << suite << " does not run on every supported target";
  }

  // The jit's instruction sets JitDifferential runs here (both on an AVX-512 machine), as named.
  std::string why_not;
  const bool jit_runs = jit::Compile(Program(), why_not) != nullptr;
  std::vector<std::string> jit_isas;
  for (JitIsa isa : jit::SupportedIsas()) jit_isas.emplace_back(kJitIsaNames.Name(isa));
  const std::set<std::string> jit_instantiated = InstantiatedTargets("JitDifferential");
  EXPECT_EQ(jit_instantiated, std::set<std::string>(jit_isas.begin(), jit_isas.end()));
  EXPECT_EQ(jit_runs, !jit_isas.empty());
  std::printf("[ coverage ] jit engine: %s\n",
              jit_runs ? (Join(jit_isas) + " machine code tested (JitDifferential)").c_str()
                       : ("NOT tested here: " + why_not).c_str());
}

}  // namespace
}  // namespace vs11
