// Shared set-up for the vs11 benchmarks (bench/**/*_bench.cc, one executable vs11_bench): loading the
// programs of programs/*.vsh, unit-normal inputs, the Table 1 constant bank, and the plain C++
// evaluation of the paper's eq. (7) / Table 1 polynomial used as the native baseline.
//
// Set-up failures (a program that does not load) abort: a benchmark binary has no caller to report to.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/sh/sh9.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/reference/program_references.h"
#include "vm/reference/verify.h"

namespace vs11::bench {

// Seed of every pseudo-random input, so that runs are comparable.
inline constexpr std::uint64_t kBenchSeed = 20080101;

// The folder of .vsh programs the benchmarks run, found once: $VS11_PROGRAMS_DIR when it is set (and
// then only there), else programs/ beside the binary or in the source tree above a build folder
// (build/bench/vs11_bench), else the source tree vs11_bench was built from. A binary copied to
// another machine thus finds the programs copied with it. None of them: a message naming each place
// tried, exit status 2 (benchmarks register before main, so there is no caller to report to).
inline const std::filesystem::path& ProgramsFolder() {
  static const std::filesystem::path folder = [] {
    namespace fs = std::filesystem;
    std::vector<fs::path> tried;
    if (const char* chosen = std::getenv("VS11_PROGRAMS_DIR"); chosen != nullptr && *chosen != '\0') {
      tried.emplace_back(chosen);
    } else {
      std::error_code error;
      const fs::path binary = fs::read_symlink("/proc/self/exe", error);
      if (!error) {
        tried.push_back(binary.parent_path() / "programs");
        tried.push_back(binary.parent_path().parent_path().parent_path() / "programs");
      }
      tried.push_back(fs::path(VS11_SOURCE_DIR) / "programs");
    }
    for (const fs::path& candidate : tried) {
      std::error_code error;
      if (fs::is_directory(candidate, error)) return candidate;
    }
    std::fprintf(stderr, "vs11_bench: no programs folder (the .vsh files of vs11's programs/); looked in:\n");
    for (const fs::path& candidate : tried) std::fprintf(stderr, "  %s\n", candidate.string().c_str());
    std::fprintf(stderr, "set VS11_PROGRAMS_DIR to the folder that holds them\n");
    std::exit(2);
  }();
  return folder;
}

inline std::filesystem::path ProgramPath(std::string_view file_name) { return ProgramsFolder() / file_name; }

// Loads and validates a program (fragments such as sh9_irradiance.vsh included) with its metadata.
inline vs11::ProgramForVerify LoadBenchProgram(const std::filesystem::path& path) {
  vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(path);
  if (!loaded.program) {
    std::fprintf(stderr, "vs11_bench: cannot load %s\n", path.string().c_str());
    std::abort();
  }
  return loaded;
}

// Unit normals as structure of arrays.
struct SoaNormals {
  std::vector<float> x, y, z;
  std::size_t size() const { return x.size(); }
};

// `count` pseudo-random unit normals, uniform on the sphere (normalised Gaussian triples).
inline SoaNormals RandomUnitNormals(std::size_t count, std::uint64_t seed = kBenchSeed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  SoaNormals normals;
  normals.x.resize(count);
  normals.y.resize(count);
  normals.z.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    double x = 0.0, y = 0.0, z = 0.0, length = 0.0;
    do {
      x = gauss(rng);
      y = gauss(rng);
      z = gauss(rng);
      length = std::sqrt(x * x + y * y + z * z);
    } while (length < 1e-6);
    normals.x[i] = static_cast<float>(x / length);
    normals.y[i] = static_cast<float>(y / length);
    normals.z[i] = static_cast<float>(z / length);
  }
  return normals;
}

// The same normals as vertex inputs: register `reg` = (x, y, z, 1).
inline VertexArrays NormalInputs(const SoaNormals& normals, int reg = 0) {
  const int registers[] = {reg};
  VertexArrays inputs = MakeInputArrays(normals.size(), registers);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    inputs.lane(reg, 0)[i] = normals.x[i];
    inputs.lane(reg, 1)[i] = normals.y[i];
    inputs.lane(reg, 2)[i] = normals.z[i];
    inputs.lane(reg, 3)[i] = 1.0f;
  }
  return inputs;
}

// The seven Table 1 registers at c[first]..c[first + 6] of an otherwise zero bank.
inline ConstantBank Table1Bank(const vs11::SevenConstants& constants, int first = 0) {
  ConstantBank bank;
  for (int i = 0; i < 7; ++i) {
    const glm::vec4& v = constants.registers[i];
    bank[first + i] = {v.x, v.y, v.z, v.w};
  }
  return bank;
}

// Fixed coefficients of a plausible environment for the evaluation benchmarks.
inline vs11::Sh9Rgb BenchCoefficients() { return vs11::RandomCoefficients(kBenchSeed); }

// The Table 1 polynomial (eq. (7)) in plain C++, r[i], g[i], b[i] from x[i], y[i], z[i]:
//   E_c = dp4((x, y, z, 1), cA_c) + dp4((xy, yz, zz, zx), cB_c) + cC_c (x^2 - y^2)
// with the same float operations (unfused; the project builds with -ffp-contract=off) as the VM.
// Scalar: compiled with tree vectorisation off. Simd: the same loop with __restrict pointers and
// function multi-versioning (AVX-512 / AVX2 / SSE2, chosen at load time). Both are defined in
// bench/vm/irradiance_eval_bench.cc and are not inlined.
void EvalTable1Scalar(const vs11::SevenConstants& constants, const float* x, const float* y,
                      const float* z, float* r, float* g, float* b, std::size_t count);
void EvalTable1Simd(const vs11::SevenConstants& constants, const float* x, const float* y,
                    const float* z, float* r, float* g, float* b, std::size_t count);

}  // namespace vs11::bench
