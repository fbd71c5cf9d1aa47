// Verification of vertex programs against their double-precision references
// (program_references.h), and bit-for-bit comparison of two execution engines.
//
//   vs11 verify programs/sh9_irradiance.vsh          -> LoadProgramForVerify + Verify
//   vs11 verify PROGRAM --against-engine ref         -> LoadProgramForVerify + VerifyEngines
//
// Errors are measured per output register over the compared lanes of every vertex:
//   absolute error  |actual - expected|
//   relative error  absolute error / scale, scale = the largest |expected| over all vertices and
//                   compared lanes of that output (1 if they are all 0)
// An output passes when its maximum relative error is at most its tolerance; a program passes when
// every checked output does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/reference/program_metadata.h"
#include "vm/reference/program_references.h"

namespace vs11 {

// ---- verification against a reference ---------------------------------------------------------------

inline constexpr double kDefaultVerifyTolerance = 1e-5;
inline constexpr int kDefaultVerifySamples = 256;

struct VerifyOptions {
  std::string engine = "batch";
  EngineOptions engine_options;
  std::optional<Sh9Rgb> coefficients;  // sh9; default RandomCoefficients(seed)
  std::uint64_t seed = 1;
  int samples = kDefaultVerifySamples;
  std::optional<double> tolerance;     // overrides every output's own tolerance
  int constant_count = kDefaultConstantCount;
};

struct InputValue {
  std::string name;  // "normal"
  int reg = 0;       // v#
  Vec4f value{};
};

struct OutputReport {
  int slot = 0;
  WriteMask lanes;                  // compared lanes
  WriteMask missing_lanes{0};       // compared lanes the program never writes (a failure)
  double scale = 0.0;               // largest |expected|
  double max_absolute = 0.0, rms_absolute = 0.0;
  double max_relative = 0.0, rms_relative = 0.0;
  double tolerance = kDefaultVerifyTolerance;
  bool pass = false;
  std::size_t worst_vertex = 0;
  int worst_lane = 0;
  glm::dvec4 expected{0.0};         // at the worst vertex
  Vec4f actual{};                   // at the worst vertex
  std::vector<InputValue> worst_inputs;  // the reference's named inputs at the worst vertex

  std::string Name() const;         // "oD0.xyz"
};

struct VerifyReport {
  std::string error;                 // set when nothing could be run (unknown reference, bad metadata, an
                                     // engine that could not be had or failed: the gl engine's error())
  std::string reference;
  std::string description;           // the reference's own account of registers and packing
  std::string engine = "batch";
  std::size_t vertices = 0;
  std::uint64_t seed = 0;
  std::vector<OutputReport> outputs;  // the primary output first
  bool pass = false;
};

// Runs `program` on options.engine over the reference's inputs and compares the outputs.
VerifyReport Verify(const Program& program, const ProgramMetadata& metadata, const VerifyOptions& options);

// Human-readable report (several lines) and a JSON object, as `vs11 verify` prints them.
std::string FormatVerifyReport(const VerifyReport& report);
std::string VerifyReportJson(const VerifyReport& report);

// ---- engine against engine ----------------------------------------------------------------------------

struct EngineDifference {
  std::size_t vertex = 0;
  int slot = 0;
  int lane = 0;
  float a = 0.0f, b = 0.0f;
};

struct EngineComparison {
  std::string error;
  std::string a = "ref", b = "batch";
  std::string inputs;                // where the inputs came from: a reference or random values
  std::size_t vertices = 0;
  std::size_t lanes_compared = 0;    // vertices x every lane of every written output register
  std::size_t differing_lanes = 0;   // lanes whose float bit patterns differ
  std::optional<EngineDifference> first;
  bool identical() const { return error.empty() && differing_lanes == 0; }
};

// Compares two output arrays of the same shape (same slots, same count) lane by lane, bit for bit.
EngineComparison CompareOutputArrays(const VertexArrays& a, const VertexArrays& b);

// Runs the program on both engines with the same constants and inputs and compares every lane of
// every output register it writes, bit for bit (NaNs equal only with equal bits).
EngineComparison CompareEngines(const Program& program, std::string a, std::string b, const ConstantBank& constants,
                                const VertexArrays& inputs, const EngineOptions& engine_options = {});

// The same with the inputs of the metadata's reference when it names one, otherwise reproducible
// random inputs in [-2, 2] for every input register the program reads and random constants in
// [-2, 2] for every constant register (options.seed, options.samples vertices).
EngineComparison VerifyEngines(const Program& program, const ProgramMetadata& metadata, std::string a, std::string b,
                               const VerifyOptions& options);

std::string FormatEngineComparison(const EngineComparison& comparison);
std::string EngineComparisonJson(const EngineComparison& comparison);

}  // namespace vs11
