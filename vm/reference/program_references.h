// Scalar (double precision) references for the vertex programs in programs/: for each named reference
// (`sh9`, `directional_light`, `point_light`, `fog`, `skinning`, `all_instructions`), the API constant
// bank, the vertex inputs and the outputs the program should produce, computed in double from the
// same float constants and inputs the vertex machine receives, without running the machine.
//
// programs/README.md documents the convention and each program's layout.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "vm/core/machine.h"
#include "vm/core/result.h"
#include "vm/core/name_table.h"
#include "vm/reference/program_metadata.h"
#include "vm/reference/sh9.h"

namespace vs11 {

// The sh9 packings (`; vs11: packing=...`).
enum class Sh9Packing {
  kTable1,        // the paper's seven registers (PackTable1), 11-instruction program
  kUnitSphere10,  // PackUnitSphere10: 10 instructions, exact on unit normals only
  kMatrix,        // Ramamoorthi & Hanrahan's E(n) = n^T M n, three 4x4 matrices (PackMatrix)
  kBasis,         // the nine basis functions summed with weights A_l L_lm (PackBasis)
  kOrder0,        // reduced orders (sh_orders.h, PackShOrder): band 0 only, 1 register
  kOrder1,        // bands 0 and 1, 3 registers
  kZh3,           // bands 0 and 1 plus band 2's zonal part around the linear band's axis, 5 registers
};
inline constexpr NameTable kSh9PackingNames("sh9 packing", {
    Choice(Sh9Packing::kTable1, "table1"), Choice(Sh9Packing::kUnitSphere10, "unit_sphere10"),
    Choice(Sh9Packing::kMatrix, "matrix"), Choice(Sh9Packing::kBasis, "basis"), Choice(Sh9Packing::kOrder0, "order0"),
    Choice(Sh9Packing::kOrder1, "order1"), Choice(Sh9Packing::kZh3, "zh3")});

// Ramamoorthi & Hanrahan 2001, eq. (12): E(n) = n^T M n with n = (x, y, z, 1) and, per channel,
//
//       | k1 L22    k1 L2-2   k1 L21   k2 L11          |
//   M = | k1 L2-2  -k1 L22    k1 L2-1  k2 L1-1         |
//       | k1 L21    k1 L2-1   k3 L20   k2 L10          |
//       | k2 L11    k2 L1-1   k2 L10   k4 L00 - k5 L20 |
//
// with their constants k1 = 0.429043 = c4, k2 = 0.511664 = c1 / 2, k3 = 0.743125 = 3 c3,
// k4 = 0.886227 = c0, k5 = 0.247708 = c3 (the paper's c0..c4, sh9.h; exact here).
// Registers 4 ch + row (ch = 0 red, 1 green, 2 blue) hold row `row` of the channel's M, for
// `m4x4 r, v0, c[base + 4 ch]` followed by `dp4 out, r, v0`. Each entry is rounded to float once.
std::array<glm::vec4, 12> PackMatrix(const Sh9Rgb& sh);

// The naive packing of programs/sh9_irradiance_basis.vsh (9 registers):
//   0: (n0, n1, n2, n3)        basis normalisation constants (sh9.h)
//   1: (n4, 3, -1, 0)
//   2 + ch: (A0 L00, A1 L1-1, A1 L10, A1 L11) of channel ch   weights of (y00, y1-1, y10, y11)
//   5 + ch: (A2 L2-2, A2 L2-1, A2 L20, A2 L21) of channel ch  weights of (y2-2, y2-1, y20, y21)
//   8: (A2 R22, A2 G22, A2 B22, 0)                             weights of y22
std::array<glm::vec4, 9> PackBasis(const Sh9Rgb& sh);

// Reproducible pseudo-random coefficients: L00 in [0.5, 2.5] per channel, the other eight in
// [-0.5, 0.5]. Same result on every platform for a given seed (no std distributions).
Sh9Rgb RandomCoefficients(std::uint64_t seed);

// Parses {"coefficients": [[r, g, b] x 9]} in the order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21,
// L22 (ShIndex order). Other members are ignored. Errors (kCannotReadFile) say what is wrong.
Result<Sh9Rgb> ParseCoefficientsJson(std::string_view text);
// Reads and parses a file; errors (kCannotReadFile) name the file.
Result<Sh9Rgb> LoadCoefficientsJson(const std::filesystem::path& path);

// The values one output register must hold, per vertex, in double.
struct ExpectedOutput {
  int slot = 0;               // OutputSlot
  WriteMask lanes;            // lanes compared
  std::vector<glm::dvec4> values;  // one per vertex
  double tolerance = 1e-5;    // default pass limit on the error relative to the output's scale
};

// An input register worth printing for the worst vertex ("normal", "position", ...).
struct NamedInput {
  int reg = 0;
  std::string name;
};

// Everything needed to run a program and judge its results.
struct ReferenceCase {
  ConstantBank constants;
  VertexArrays inputs;
  std::vector<ExpectedOutput> expected;  // the primary output (metadata `output`) first
  std::vector<NamedInput> named_inputs;
  std::string description;               // "sh9 packing=table1 normal=v0 constants=c0 ..."
};

struct ReferenceOptions {
  Sh9Rgb coefficients;   // sh9 only
  int samples = 256;     // sh9: sphere normals (plus 14 fixed ones); others: random vertices
  std::uint64_t seed = 1;
  int constant_count = kDefaultConstantCount;
};

struct ReferenceInfo {
  std::string_view name;
  std::string_view summary;  // one line for --help and errors
  // Builds the case, or says why the metadata does not fit the reference (kMetadataValue).
  Result<ReferenceCase> (*build)(const ProgramMetadata&, const ReferenceOptions&);
};

// Every reference, in a fixed order.
std::span<const ReferenceInfo> References();
const ReferenceInfo* FindReference(std::string_view name);
// "sh9, directional_light, ..." for messages.
std::string ReferenceNames();

// The 14 fixed sh9 sample normals: the 6 axes, then the 8 normalised diagonals (+-1, +-1, +-1).
std::vector<glm::dvec3> AxisAndDiagonalNormals();

}  // namespace vs11
