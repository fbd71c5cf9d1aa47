// Double-precision references for programs/*.vsh. See program_references.h.
//
// Every reference first writes the constants and inputs the machine will see (rounded to float),
// then computes the expected outputs in double from those same float values read back, so the only
// differences left are the machine's float arithmetic and approximations.
#include "vm/reference/program_references.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/asm/program_file.h"
#include "vm/reference/sh_orders.h"
#include "vm/reference/sphere_normals.h"

namespace vs11 {
namespace {

// Default pass limit of every reference: the error relative to the largest |expected| of the output.
constexpr double kDefaultTolerance = 1e-5;
// expp/logp z lanes keep 15 significant bits (§3.3: low 8 mantissa bits cleared): relative error up
// to 2^-15 = 3.1e-5, so outputs that carry them are checked at 1e-4.
constexpr double kPartialPrecisionTolerance = 1e-4;
// Random vertices closer than this to a discontinuity of the program (lit's N.L > 0 switch, frc's
// wrap at integers) are drawn again: float rounding could put them on the other side.
constexpr double kDiscontinuityMargin = 1e-3;
constexpr int kMaxRedraws = 1000;

constexpr int kRed = 0, kBlue = 2;  // channel numbers (green is 1)
constexpr WriteMask kXyz(0x7), kXy(0x3), kX(0x1), kXyzw(0xF);
constexpr int kDiffuseSlot = static_cast<int>(OutputSlot::kDiffuse);
constexpr int kSpecularSlot = static_cast<int>(OutputSlot::kSpecular);
constexpr int kPositionSlot = static_cast<int>(OutputSlot::kPosition);
constexpr int kFogSlot = static_cast<int>(OutputSlot::kFog);
constexpr int kTexCoord0Slot = static_cast<int>(OutputSlot::kTexCoord0);
// lit's exponent clamp, 127.9961f = 0x42FFFE01 (§3.3 lit).
constexpr double kLitMaxPower = static_cast<double>(127.9961f);

// SplitMix64: tiny, portable and the same on every platform (std distributions are not).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(Next() >> 11) * 0x1p-53; }
  glm::dvec3 UnitVector() {
    for (;;) {
      glm::dvec3 v(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
      double length = glm::length(v);
      if (length > 0.1 && length <= 1.0) return v / length;
    }
  }
  glm::dvec4 Colour() { return {Uniform(0.1, 1), Uniform(0.1, 1), Uniform(0.1, 1), Uniform(0.5, 1)}; }

 private:
  std::uint64_t state_;
};

// Writes constants and inputs as float and reads them back as double.
class CaseWriter {
 public:
  CaseWriter(ReferenceCase& rc, int base) : rc_(rc), base_(base) {}
  // Register base + offset.
  glm::dvec4 SetConstant(int offset, glm::dvec4 value) {
    const glm::vec4 f(value);
    rc_.constants[base_ + offset] = {f.x, f.y, f.z, f.w};
    return glm::dvec4(f);
  }
  glm::dvec4 Constant(int offset) const {
    const Vec4f& v = rc_.constants[base_ + offset];
    return {v[0], v[1], v[2], v[3]};
  }
  glm::dvec4 SetInput(int reg, std::size_t vertex, glm::dvec4 value) {
    const glm::vec4 f(value);
    for (int c = 0; c < 4; ++c) rc_.inputs.lane(reg, c)[vertex] = f[c];
    return glm::dvec4(f);
  }
  // A random 4x4 matrix of entries in [-1, 1] in registers offset..offset+3.
  std::array<glm::dvec4, 4> RandomMatrix4(int offset, Random& random) {
    std::array<glm::dvec4, 4> rows;
    for (int i = 0; i < 4; ++i) {
      rows[i] = SetConstant(offset + i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1),
                                         random.Uniform(-1, 1)});
    }
    return rows;
  }
  // A rotation times a uniform scale in [0.5, 2], plus a translation in [-1, 1]^3, as 3 rows (4x3).
  std::array<glm::dvec4, 3> RandomWorld(int offset, Random& random) {
    const glm::dvec3 axis = random.UnitVector();
    const double angle = random.Uniform(0, 2 * std::numbers::pi);
    const double scale = random.Uniform(0.5, 2.0);
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const double x = axis.x, y = axis.y, z = axis.z;
    const glm::dmat3 r(t * x * x + c, t * x * y - s * z, t * x * z + s * y,   // row 0 (read as rows)
                       t * x * y + s * z, t * y * y + c, t * y * z - s * x,   // row 1
                       t * x * z - s * y, t * y * z + s * x, t * z * z + c);  // row 2
    std::array<glm::dvec4, 3> rows;
    for (int i = 0; i < 3; ++i) {
      rows[i] = SetConstant(offset + i, {scale * r[i][0], scale * r[i][1], scale * r[i][2], random.Uniform(-1, 1)});
    }
    return rows;
  }

 private:
  ReferenceCase& rc_;
  int base_;
};

// Row-wise products as the matrix macros compute them (§3.3): dp4 or dp3 with each row.
template <std::size_t kRows>
glm::dvec4 Rows4(const std::array<glm::dvec4, kRows>& rows, glm::dvec4 v) {
  glm::dvec4 r(0.0);
  for (std::size_t i = 0; i < kRows; ++i) r[static_cast<int>(i)] = glm::dot(rows[i], v);
  return r;
}
template <std::size_t kRows>
glm::dvec4 Rows3(const std::array<glm::dvec4, kRows>& rows, glm::dvec3 v) {
  glm::dvec4 r(0.0);
  for (std::size_t i = 0; i < kRows; ++i) r[static_cast<int>(i)] = glm::dot(glm::dvec3(rows[i]), v);
  return r;
}

// lit (§3.3) in double: (1, max(x, 0), x > 0 && y > 0 ? y^clamp(w) : 0, 1).
glm::dvec4 Lit(double n_dot_l, double n_dot_h, double power) {
  power = std::clamp(power, -kLitMaxPower, kLitMaxPower);
  glm::dvec4 r(1.0, 0.0, 0.0, 1.0);
  if (n_dot_l > 0) {
    r.y = n_dot_l;
    if (n_dot_h > 0) r.z = std::pow(n_dot_h, power);
  }
  return r;
}

double Fraction(double x) { return x - std::floor(x); }
bool NearInteger(double x, double margin) { return std::abs(x - std::round(x)) < margin; }

// Common preamble: bank, register checks, input arrays.
struct Setup {
  ReferenceCase rc;
  int base = 0;
};

// What is wrong with the metadata for this reference.
Diagnostic Unfit(std::string message) { return Failure(DiagnosticCode::kMetadataValue, std::move(message)); }

Result<Setup> Begin(const ProgramMetadata& meta, const ReferenceOptions& options, int constant_registers,
                    std::vector<int> input_registers, std::size_t vertices) {
  Setup setup;
  setup.base = meta.constants.value_or(0);
  if (setup.base < 0 || setup.base + constant_registers > options.constant_count) {
    return Unfit(fmt::format("the reference needs constants c{}..c{}, beyond the {} constant registers", setup.base,
                             setup.base + constant_registers - 1, options.constant_count));
  }
  std::sort(input_registers.begin(), input_registers.end());
  if (std::adjacent_find(input_registers.begin(), input_registers.end()) != input_registers.end()) {
    return Unfit("two inputs of the reference name the same register");
  }
  for (int reg : input_registers) {
    if (reg < 0 || reg >= kInputRegisterCount) {
      return Unfit(fmt::format("input register v{} does not exist", reg));
    }
  }
  if (options.samples < 1) {
    return Unfit("the sample count must be at least 1");
  }
  setup.rc.constants = ConstantBank(options.constant_count);
  // Builders hold references to several ExpectedOutputs at once: no reallocation may move them.
  setup.rc.expected.reserve(kOutputSlotCount);
  setup.rc.inputs = MakeInputArrays(vertices, input_registers);
  return setup;
}

// What the body of a lit case works with: the case it fills, a writer of its constants and inputs,
// `count` vertices (the sample count, at least one), the tolerance its outputs are checked to and
// its own random stream.
struct LitCase {
  ReferenceCase& rc;
  CaseWriter w;
  std::size_t count;
  double tolerance;
  Random& random;
};

ExpectedOutput& AddOutput(ReferenceCase& rc, int slot, WriteMask lanes, std::size_t vertices, double tolerance) {
  assert(rc.expected.size() < rc.expected.capacity());  // see Begin: references stay valid
  rc.expected.push_back({slot, lanes, std::vector<glm::dvec4>(vertices, glm::dvec4(0.0)), tolerance});
  return rc.expected.back();
}

// Moves the output of `primary_slot` to the front, as ReferenceCase promises.
void PutPrimaryFirst(ReferenceCase& rc, int primary_slot) {
  auto it = std::find_if(rc.expected.begin(), rc.expected.end(),
                         [&](const ExpectedOutput& e) { return e.slot == primary_slot; });
  if (it != rc.expected.end()) std::rotate(rc.expected.begin(), it, it + 1);
}

std::string RegisterList(const ProgramMetadata& meta, int base) {
  std::string text;
  auto add = [&](const char* key, std::optional<int> reg, char file) {
    if (reg) text += fmt::format(" {}={}{}", key, file, *reg);
  };
  add("position", meta.position, 'v');
  add("normal", meta.normal, 'v');
  add("weights", meta.weights, 'v');
  add("indices", meta.indices, 'v');
  add("texcoord", meta.texcoord, 'v');
  text += fmt::format(" constants=c{}", base);
  return text;
}

// The frame every lit case shares: the constants and `inputs` checked and reserved (Begin), the
// body that draws the constants, inputs and expected outputs, then the inputs named, the case
// described as `name`, and `primary_slot` (unless the metadata names another output) put first.
template <class Body>
Result<ReferenceCase> BuildLitCase(const ProgramMetadata& meta, const ReferenceOptions& options,
                                   std::string_view name, int constant_registers, std::vector<NamedInput> inputs,
                                   int primary_slot, Body body) {
  const std::size_t count = static_cast<std::size_t>(std::max(options.samples, 1));
  std::vector<int> input_registers;
  for (const NamedInput& input : inputs) input_registers.push_back(input.reg);
  Result<Setup> setup = Begin(meta, options, constant_registers, std::move(input_registers), count);
  if (!setup) return setup.error();
  Random random(options.seed);
  ReferenceCase& rc = setup->rc;
  LitCase lit{rc, CaseWriter(rc, setup->base), count, meta.tolerance.value_or(kDefaultTolerance), random};
  body(lit);
  rc.named_inputs = std::move(inputs);
  rc.description = std::string(name) + RegisterList(meta, setup->base);
  PutPrimaryFirst(rc, meta.output.value_or(primary_slot));
  return std::move(rc);
}

// ---- sh9 --------------------------------------------------------------------------------------------

std::optional<ShOrder> ReducedOrder(Sh9Packing packing) {
  switch (packing) {
    case Sh9Packing::kOrder0: return ShOrder::kOrder0;
    case Sh9Packing::kOrder1: return ShOrder::kOrder1;
    case Sh9Packing::kZh3: return ShOrder::kZh3;
    default: return std::nullopt;
  }
}

// A packing's constant registers from the program's first constant on: their count is the vector's
// size, so each packing states how many registers it takes in one place (its Pack function).
std::vector<glm::vec4> PackSh9(Sh9Packing packing, const Sh9Rgb& sh) {
  if (const std::optional<ShOrder> reduced = ReducedOrder(packing)) {
    std::vector<glm::vec4> values;
    for (const NamedRegister& reg : PackShOrder(sh, *reduced)) values.push_back(reg.value);
    return values;
  }
  const auto as_vector = [](const auto& registers) { return std::vector<glm::vec4>(registers.begin(), registers.end()); };
  switch (packing) {
    case Sh9Packing::kTable1: return as_vector(PackTable1(sh).registers);
    case Sh9Packing::kUnitSphere10: return as_vector(PackUnitSphere10(sh).registers);
    case Sh9Packing::kMatrix: return as_vector(PackMatrix(sh));
    case Sh9Packing::kBasis: return as_vector(PackBasis(sh));
    default: return {};  // the reduced orders, above
  }
}

Result<ReferenceCase> BuildSh9(const ProgramMetadata& meta, const ReferenceOptions& options) {
  Sh9Packing packing = Sh9Packing::kTable1;
  if (!meta.packing.empty()) {
    std::optional<Sh9Packing> parsed = kSh9PackingNames.Find(meta.packing);
    if (!parsed) {
      return Unfit(kSh9PackingNames.UnknownName(meta.packing));
    }
    packing = *parsed;
  }
  const int normal_reg = meta.normal.value_or(0);
  const int output_slot = meta.output.value_or(kDiffuseSlot);
  std::vector<glm::dvec3> normals = SphereNormals(options.samples);
  for (const glm::dvec3& n : AxisAndDiagonalNormals()) normals.push_back(n);
  const std::size_t count = normals.size();

  std::vector<int> registers = {normal_reg};
  if (meta.transform) {
    if (!meta.position) {
      return Unfit("sh9 with transform= also needs position= (the input register of the position)");
    }
    registers.push_back(*meta.position);
  }
  const std::vector<glm::vec4> packed = PackSh9(packing, options.coefficients);
  Result<Setup> setup = Begin(meta, options, static_cast<int>(packed.size()), registers, count);
  if (!setup) return setup.error();
  ReferenceCase& rc = setup->rc;
  CaseWriter writer(rc, setup->base);
  for (std::size_t i = 0; i < packed.size(); ++i) writer.SetConstant(static_cast<int>(i), glm::dvec4(packed[i]));
  // A reduced order's program computes the irradiance of the reduced coefficients.
  const std::optional<ShOrder> reduced = ReducedOrder(packing);
  const Sh9Rgb sh = reduced ? ReduceToOrder(options.coefficients, *reduced) : options.coefficients;

  ExpectedOutput& irradiance = AddOutput(rc, output_slot, kXyz, count, meta.tolerance.value_or(kDefaultTolerance));
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec4 n = writer.SetInput(normal_reg, i, glm::dvec4(normals[i], 1.0));
    irradiance.values[i] = glm::dvec4(IrradianceEq6(sh, glm::dvec3(n)), 0.0);
  }
  rc.named_inputs.push_back({normal_reg, "normal"});
  rc.description = fmt::format("sh9 packing={}{}", kSh9PackingNames.Name(packing), RegisterList(meta, setup->base));

  if (meta.transform) {
    const int transform = *meta.transform;
    if (transform < 0 || transform + 4 > options.constant_count) {
      return Unfit(fmt::format("transform=c{} needs c{}..c{}, beyond the {} constant registers", transform,
                               transform, transform + 3, options.constant_count));
    }
    CaseWriter absolute(rc, 0);
    Random random(options.seed ^ 0x5E11F00Dull);
    const std::array<glm::dvec4, 4> wvp = absolute.RandomMatrix4(transform, random);
    ExpectedOutput& position = AddOutput(rc, kPositionSlot, kXyzw, count, meta.tolerance.value_or(kDefaultTolerance));
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec4 p = writer.SetInput(
          *meta.position, i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), 1.0});
      position.values[i] = Rows4(wvp, p);
    }
    rc.named_inputs.push_back({*meta.position, "position"});
    rc.description += fmt::format(" transform=c{}", transform);
  }
  return std::move(rc);
}

// ---- directional_light --------------------------------------------------------------------------------

Result<ReferenceCase> BuildDirectionalLight(const ProgramMetadata& meta, const ReferenceOptions& options) {
  const int position_reg = meta.position.value_or(0), normal_reg = meta.normal.value_or(1);
  return BuildLitCase(meta, options, "directional_light", 13,
                      {{position_reg, "position"}, {normal_reg, "normal"}}, kDiffuseSlot, [&](LitCase& frame) {
    auto& [rc, w, count, tolerance, random] = frame;
    const std::array<glm::dvec4, 4> wvp = w.RandomMatrix4(0, random);
    const std::array<glm::dvec4, 3> world = w.RandomWorld(4, random);
    const glm::dvec3 light = glm::dvec3(w.SetConstant(7, glm::dvec4(random.UnitVector(), 0.0)));
    const glm::dvec3 eye = glm::dvec3(w.SetConstant(8, glm::dvec4(random.UnitVector() * 6.0, 1.0)));
    const glm::dvec4 diffuse = w.SetConstant(9, random.Colour());
    const glm::dvec4 specular = w.SetConstant(10, random.Colour());
    const glm::dvec4 ambient = w.SetConstant(11, random.Colour() * 0.2);
    const double power = w.SetConstant(12, {0.0, 0.0, 0.0, std::round(random.Uniform(4, 32))}).w;

    ExpectedOutput& position = AddOutput(rc, kPositionSlot, kXyzw, count, tolerance);
    ExpectedOutput& od0 = AddOutput(rc, kDiffuseSlot, kXyzw, count, tolerance);
    ExpectedOutput& od1 = AddOutput(rc, kSpecularSlot, kXyzw, count, tolerance);
    for (std::size_t i = 0; i < count; ++i) {
      for (int attempt = 0;; ++attempt) {
        const glm::dvec4 p = w.SetInput(position_reg, i, {random.Uniform(-1, 1), random.Uniform(-1, 1),
                                                          random.Uniform(-1, 1), 1.0});
        const glm::dvec4 n_in = w.SetInput(normal_reg, i, glm::dvec4(random.UnitVector(), 1.0));
        const glm::dvec3 world_p(Rows4(world, p));
        const glm::dvec3 n = glm::normalize(glm::dvec3(Rows3(world, glm::dvec3(n_in))));
        const glm::dvec3 h = glm::normalize(glm::normalize(eye - world_p) + light);
        const double n_dot_l = glm::dot(n, light), n_dot_h = glm::dot(n, h);
        if (attempt < kMaxRedraws &&
            (std::abs(n_dot_l) < kDiscontinuityMargin || std::abs(n_dot_h) < kDiscontinuityMargin)) {
          continue;
        }
        const glm::dvec4 lit = Lit(n_dot_l, n_dot_h, power);
        position.values[i] = Rows4(wvp, p);
        od0.values[i] = ambient + diffuse * lit.y;
        od1.values[i] = specular * lit.z;
        break;
      }
    }
  });
}

// ---- point_light ------------------------------------------------------------------------------------

Result<ReferenceCase> BuildPointLight(const ProgramMetadata& meta, const ReferenceOptions& options) {
  const int position_reg = meta.position.value_or(0), normal_reg = meta.normal.value_or(1);
  return BuildLitCase(meta, options, "point_light", 11,
                      {{position_reg, "position"}, {normal_reg, "normal"}}, kDiffuseSlot, [&](LitCase& frame) {
    auto& [rc, w, count, tolerance, random] = frame;
    const std::array<glm::dvec4, 4> wvp = w.RandomMatrix4(0, random);
    const std::array<glm::dvec4, 3> world = w.RandomWorld(4, random);
    // The light 4 to 8 units from the origin, so it stays outside the objects (|P| <= about 3.5).
    const glm::dvec3 light_pos =
        glm::dvec3(w.SetConstant(7, glm::dvec4(random.UnitVector() * random.Uniform(4, 8), 1.0)));
    const glm::dvec4 atten =
        w.SetConstant(8, {random.Uniform(0.5, 1), random.Uniform(0.05, 0.2), random.Uniform(0.01, 0.05), 0.0});
    const glm::dvec4 diffuse = w.SetConstant(9, random.Colour() * 8.0);
    const glm::dvec4 ambient = w.SetConstant(10, random.Colour() * 0.2);

    ExpectedOutput& position = AddOutput(rc, kPositionSlot, kXyzw, count, tolerance);
    ExpectedOutput& od0 = AddOutput(rc, kDiffuseSlot, kXyzw, count, tolerance);
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec4 p =
          w.SetInput(position_reg, i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), 1.0});
      const glm::dvec4 n_in = w.SetInput(normal_reg, i, glm::dvec4(random.UnitVector(), 1.0));
      const glm::dvec3 to_light = light_pos - glm::dvec3(Rows4(world, p));
      const double d = glm::length(to_light);
      const glm::dvec3 n = glm::normalize(glm::dvec3(Rows3(world, glm::dvec3(n_in))));
      const double attenuation = 1.0 / (atten.x + atten.y * d + atten.z * d * d);
      position.values[i] = Rows4(wvp, p);
      od0.values[i] = ambient + diffuse * (std::max(glm::dot(n, to_light / d), 0.0) * attenuation);
    }
  });
}

// ---- fog --------------------------------------------------------------------------------------------

Result<ReferenceCase> BuildFog(const ProgramMetadata& meta, const ReferenceOptions& options) {
  const int position_reg = meta.position.value_or(0);
  return BuildLitCase(meta, options, "fog", 8, {{position_reg, "position"}}, kFogSlot, [&](LitCase& frame) {
    auto& [rc, w, count, tolerance, random] = frame;
    const std::array<glm::dvec4, 4> wvp = w.RandomMatrix4(0, random);
    std::array<glm::dvec4, 3> world_view = w.RandomWorld(4, random);
    // Push the scene 2 to 10 units in front of the eye (view-space z), as a camera would see it.
    world_view[2] = w.SetConstant(6, world_view[2] + glm::dvec4(0, 0, 0, random.Uniform(2, 10)));
    const double density1 = random.Uniform(0.02, 0.2), density2 = random.Uniform(0.02, 0.2);
    const glm::dvec4 fog = w.SetConstant(
        7, {0.0, -density1 * std::numbers::log2e, -density2 * density2 * std::numbers::log2e, 0.0});

    ExpectedOutput& position = AddOutput(rc, kPositionSlot, kXyzw, count, tolerance);
    ExpectedOutput& o_fog = AddOutput(rc, kFogSlot, kX, count, tolerance);
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec4 p =
          w.SetInput(position_reg, i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), 1.0});
      const double d = glm::length(glm::dvec3(Rows4(world_view, p)));
      position.values[i] = Rows4(wvp, p);
      o_fog.values[i] = glm::dvec4(std::exp2(fog.y * d + fog.z * d * d), 0.0, 0.0, 0.0);
    }
  });
}

// ---- skinning ---------------------------------------------------------------------------------------

constexpr int kSkinningBones = 8;
constexpr int kSkinningPaletteOffset = 6;  // palette at c[base + 6], 3 registers per bone

Result<ReferenceCase> BuildSkinning(const ProgramMetadata& meta, const ReferenceOptions& options) {
  const int position_reg = meta.position.value_or(0), weights_reg = meta.weights.value_or(1),
            indices_reg = meta.indices.value_or(2), normal_reg = meta.normal.value_or(3);
  return BuildLitCase(meta, options, "skinning", kSkinningPaletteOffset + 3 * kSkinningBones,
                      {{position_reg, "position"}, {weights_reg, "weights"}, {indices_reg, "indices"},
                       {normal_reg, "normal"}},
                      kDiffuseSlot, [&](LitCase& frame) {
    auto& [rc, w, count, tolerance, random] = frame;
    const std::array<glm::dvec4, 4> view_proj = w.RandomMatrix4(0, random);
    const glm::dvec3 light = glm::dvec3(w.SetConstant(4, glm::dvec4(random.UnitVector(), 0.0)));
    const glm::dvec4 diffuse = w.SetConstant(5, random.Colour());
    std::array<std::array<glm::dvec4, 3>, kSkinningBones> bones;
    for (int b = 0; b < kSkinningBones; ++b) bones[b] = w.RandomWorld(kSkinningPaletteOffset + 3 * b, random);

    ExpectedOutput& position = AddOutput(rc, kPositionSlot, kXyzw, count, tolerance);
    ExpectedOutput& od0 = AddOutput(rc, kDiffuseSlot, kXyzw, count, tolerance);
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec4 p =
          w.SetInput(position_reg, i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), 1.0});
      const double w0 = random.Uniform(0, 1);
      const glm::dvec4 weights = w.SetInput(weights_reg, i, {w0, 1.0 - w0, 0.0, 1.0});
      const int b0 = static_cast<int>(random.Next() % kSkinningBones);
      const int b1 = static_cast<int>(random.Next() % kSkinningBones);
      w.SetInput(indices_reg, i, {3.0 * b0, 3.0 * b1, 0.0, 1.0});
      const glm::dvec4 n_in = w.SetInput(normal_reg, i, glm::dvec4(random.UnitVector(), 1.0));
      const glm::dvec3 skinned =
          glm::dvec3(Rows4(bones[b0], p)) * weights.x + glm::dvec3(Rows4(bones[b1], p)) * weights.y;
      const glm::dvec3 normal = glm::dvec3(Rows3(bones[b0], glm::dvec3(n_in))) * weights.x +
                                glm::dvec3(Rows3(bones[b1], glm::dvec3(n_in))) * weights.y;
      position.values[i] = Rows4(view_proj, glm::dvec4(skinned, p.w));
      od0.values[i] = diffuse * std::max(glm::dot(glm::normalize(normal), light), 0.0);
    }
  });
}

// ---- all_instructions -------------------------------------------------------------------------------

// The program's `def c20, 0.5, 2, -1, 0`.
constexpr double kHalf = 0.5;

// logp (§3.3, vs_1_1 split form) of a nonzero float, exactly: (exponent, mantissa in [1, 2),
// log2 |v|, 1).
glm::dvec4 Logp(double v) {
  v = std::abs(v);
  int exponent = 0;
  const double mantissa = 2.0 * std::frexp(v, &exponent);  // frexp gives [0.5, 1)
  return {static_cast<double>(exponent - 1), mantissa, std::log2(v), 1.0};
}

Result<ReferenceCase> BuildAllInstructions(const ProgramMetadata& meta, const ReferenceOptions& options) {
  const int position_reg = meta.position.value_or(0), normal_reg = meta.normal.value_or(1),
            texcoord_reg = meta.texcoord.value_or(2);
  return BuildLitCase(meta, options, "all_instructions", 19,
                      {{position_reg, "position"}, {normal_reg, "normal"}, {texcoord_reg, "texcoord"}}, kDiffuseSlot,
                      [&](LitCase& frame) {
    auto& [rc, w, count, tolerance, random] = frame;
    const std::array<glm::dvec4, 4> wvp = w.RandomMatrix4(0, random);
    const std::array<glm::dvec4, 3> world = w.RandomWorld(4, random);
    const glm::dvec3 light_pos =
        glm::dvec3(w.SetConstant(7, glm::dvec4(random.UnitVector() * random.Uniform(4, 8), 1.0)));
    std::array<glm::dvec4, 4> m3x4;
    for (int i = 0; i < 4; ++i) m3x4[i] = w.SetConstant(8 + i, glm::dvec4(random.UnitVector() * 2.0, 0.0));
    std::array<glm::dvec4, 2> tex;
    for (int i = 0; i < 2; ++i) {
      tex[i] = w.SetConstant(12 + i, {random.Uniform(-2, 2), random.Uniform(-2, 2), random.Uniform(-2, 2), 0.0});
    }
    const glm::dvec4 diffuse = w.SetConstant(14, random.Colour());
    const glm::dvec4 specular = w.SetConstant(15, random.Colour());
    const double power = w.SetConstant(16, {0.0, 0.0, 0.0, std::round(random.Uniform(4, 32))}).w;
    const glm::dvec3 half = glm::dvec3(w.SetConstant(17, glm::dvec4(random.UnitVector(), 0.0)));
    const glm::dvec4 fog_plane = w.SetConstant(18, glm::dvec4(random.UnitVector() * 0.3, 0.5));

    const double partial_tolerance = meta.tolerance.value_or(kPartialPrecisionTolerance);
    ExpectedOutput& o_pos = AddOutput(rc, kPositionSlot, kXyzw, count, tolerance);
    ExpectedOutput& od0 = AddOutput(rc, kDiffuseSlot, kXyzw, count, tolerance);
    ExpectedOutput& od1 = AddOutput(rc, kSpecularSlot, kXyzw, count, tolerance);
    ExpectedOutput& ot0 = AddOutput(rc, kTexCoord0Slot + 0, kXy, count, tolerance);
    ExpectedOutput& ot1 = AddOutput(rc, kTexCoord0Slot + 1, kXy, count, tolerance);
    ExpectedOutput& ot2 = AddOutput(rc, kTexCoord0Slot + 2, kXyzw, count, partial_tolerance);
    ExpectedOutput& ot3 = AddOutput(rc, kTexCoord0Slot + 3, kXyzw, count, partial_tolerance);
    ExpectedOutput& ot4 = AddOutput(rc, kTexCoord0Slot + 4, kXyzw, count, tolerance);
    ExpectedOutput& ot5 = AddOutput(rc, kTexCoord0Slot + 5, kXyzw, count, tolerance);
    ExpectedOutput& o_fog = AddOutput(rc, kFogSlot, kX, count, tolerance);
    for (std::size_t i = 0; i < count; ++i) {
      for (int attempt = 0;; ++attempt) {
        const glm::dvec4 p =
            w.SetInput(position_reg, i, {random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), 1.0});
        const glm::dvec4 n_in = w.SetInput(normal_reg, i, glm::dvec4(random.UnitVector(), 1.0));
        const glm::dvec4 t = w.SetInput(texcoord_reg, i, {random.Uniform(-2, 3), random.Uniform(0.1, 4),
                                                          random.Uniform(-1, 1), random.Uniform(-1, 1)});
        const glm::dvec3 n = glm::normalize(glm::dvec3(Rows3(world, glm::dvec3(n_in))));
        const glm::dvec3 to_light = light_pos - glm::dvec3(Rows4(world, p));
        const double d = glm::length(to_light);
        const double n_dot_l = glm::dot(n, to_light / d), n_dot_h = glm::dot(n, half);
        const glm::dvec4 transformed = Rows3(tex, glm::dvec3(t));
        if (attempt < kMaxRedraws &&
            (std::abs(n_dot_l) < kDiscontinuityMargin || std::abs(n_dot_h) < kDiscontinuityMargin ||
             NearInteger(transformed.x, kDiscontinuityMargin) || NearInteger(transformed.y, kDiscontinuityMargin))) {
          continue;
        }
        const glm::dvec4 lit = Lit(n_dot_l, n_dot_h, power);
        o_pos.values[i] = Rows4(wvp, p);
        od0.values[i] = diffuse * lit.y + specular * lit.z;
        for (int c = 0; c < 4; ++c) od1.values[i][c] = std::min(2.0 * std::abs(n_in[c]), kHalf);
        ot0.values[i] = {Fraction(transformed.x), Fraction(transformed.y), 0.0, 0.0};
        ot1.values[i] = {std::exp2(t.x), std::log2(std::abs(t.y)), 0.0, 0.0};
        ot2.values[i] = {std::exp2(std::floor(t.x)), t.x - std::floor(t.x), std::exp2(t.x), 1.0};
        ot3.values[i] = Logp(t.y);
        ot4.values[i] = Rows3(m3x4, n);
        ot5.values[i] = {1.0, d, d * d, 1.0 / d};
        o_fog.values[i] = {glm::dot(p, fog_plane), 0.0, 0.0, 0.0};
        break;
      }
    }
  });
}

constexpr std::array<ReferenceInfo, 6> kReferences = {{
    {"sh9",
     "SH irradiance E(n) by eq. (6) (packings table1, unit_sphere10, matrix, basis, order0, order1, zh3); oPos "
     "with transform=",
     BuildSh9},
    {"directional_light", "ambient + diffuse in oD0, Blinn-Phong specular via lit in oD1, oPos", BuildDirectionalLight},
    {"point_light", "point light with dst/rcp attenuation into oD0, oPos", BuildPointLight},
    {"fog", "exp / exp2 fog from the eye distance (dst, exp) into oFog, oPos", BuildFog},
    {"skinning", "two-bone matrix-palette skinning (a0.x) into oPos, diffuse into oD0", BuildSkinning},
    {"all_instructions", "every vs_1_1 instruction, outputs oPos oD0 oD1 oT0..oT5 oFog", BuildAllInstructions},
}};

}  // namespace

std::array<glm::vec4, 12> PackMatrix(const Sh9Rgb& sh) {
  // Ramamoorthi & Hanrahan's k1..k5 from the paper's c0..c4 (sh9.h), in double.
  const double k1 = kShC4, k2 = 0.5 * kShC1, k3 = 3.0 * kShC3, k4 = kShC0, k5 = kShC3;
  std::array<glm::vec4, 12> m;
  for (int ch = kRed; ch <= kBlue; ++ch) {
    auto l = [&](int band, int order) { return sh.at(band, order)[ch]; };
    const glm::dmat4 rows(k1 * l(2, 2), k1 * l(2, -2), k1 * l(2, 1), k2 * l(1, 1),         //
                          k1 * l(2, -2), -k1 * l(2, 2), k1 * l(2, -1), k2 * l(1, -1),      //
                          k1 * l(2, 1), k1 * l(2, -1), k3 * l(2, 0), k2 * l(1, 0),         //
                          k2 * l(1, 1), k2 * l(1, -1), k2 * l(1, 0), k4 * l(0, 0) - k5 * l(2, 0));
    for (int row = 0; row < 4; ++row) m[4 * ch + row] = glm::vec4(rows[row]);  // symmetric
  }
  return m;
}

std::array<glm::vec4, 9> PackBasis(const Sh9Rgb& sh) {
  std::array<glm::vec4, 9> k;
  k[0] = glm::vec4(glm::dvec4(kShN0, kShN1, kShN2, kShN3));
  k[1] = glm::vec4(glm::dvec4(kShN4, 3.0, -1.0, 0.0));
  for (int ch = kRed; ch <= kBlue; ++ch) {
    auto l = [&](int band, int order) { return sh.at(band, order)[ch]; };
    k[2 + ch] = glm::vec4(glm::dvec4(kShA0 * l(0, 0), kShA1 * l(1, -1), kShA1 * l(1, 0), kShA1 * l(1, 1)));
    k[5 + ch] = glm::vec4(glm::dvec4(kShA2 * l(2, -2), kShA2 * l(2, -1), kShA2 * l(2, 0), kShA2 * l(2, 1)));
  }
  k[8] = glm::vec4(glm::dvec4(kShA2 * sh.at(2, 2), 0.0));
  return k;
}

Sh9Rgb RandomCoefficients(std::uint64_t seed) {
  Random random(seed);
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    const double lo = i == 0 ? 0.5 : -0.5, hi = i == 0 ? 2.5 : 0.5;
    sh.coefficients[i] = {random.Uniform(lo, hi), random.Uniform(lo, hi), random.Uniform(lo, hi)};
  }
  return sh;
}

Result<Sh9Rgb> ParseCoefficientsJson(std::string_view text) {
  const auto wrong = [](std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); };
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    return wrong(fmt::format("not valid JSON: {}", e.what()));
  }
  if (!json.is_object() || !json.contains("coefficients")) {
    return wrong("expected an object with a \"coefficients\" member");
  }
  const nlohmann::json& rows = json["coefficients"];
  if (!rows.is_array() || rows.size() != kSh9Coefficients) {
    return wrong(fmt::format("\"coefficients\" must be an array of 9 [r, g, b] rows (L00, L1-1, L10, L11, L2-2, "
                             "L2-1, L20, L21, L22), got {}",
                             rows.is_array() ? fmt::format("{} rows", rows.size()) : std::string(rows.type_name())));
  }
  Sh9Rgb sh;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    const nlohmann::json& row = rows[static_cast<std::size_t>(i)];
    if (!row.is_array() || row.size() != 3) {
      return wrong(fmt::format("coefficient row {} must be an array of 3 numbers [r, g, b]", i));
    }
    for (int c = 0; c < 3; ++c) {
      const nlohmann::json& value = row[static_cast<std::size_t>(c)];
      if (!value.is_number() || !std::isfinite(value.get<double>())) {
        return wrong(
            fmt::format("coefficient row {}, channel {}: expected a finite number, got {}", i, c, value.dump()));
      }
      sh.coefficients[i][c] = value.get<double>();
    }
  }
  return sh;
}

Result<Sh9Rgb> LoadCoefficientsJson(const std::filesystem::path& path) {
  std::optional<std::string> text = ReadWholeFile(path);
  if (!text) {
    return Failure(DiagnosticCode::kCannotReadFile, fmt::format("{}: cannot read the coefficient file", path.string()));
  }
  Result<Sh9Rgb> sh = ParseCoefficientsJson(*text);
  if (!sh) return Failure(sh.error().code, fmt::format("{}: {}", path.string(), sh.message()));
  return sh;
}

std::span<const ReferenceInfo> References() { return kReferences; }

const ReferenceInfo* FindReference(std::string_view name) {
  for (const ReferenceInfo& info : kReferences) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

std::string ReferenceNames() {
  std::string names;
  for (const ReferenceInfo& info : kReferences) names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

std::vector<glm::dvec3> AxisAndDiagonalNormals() {
  std::vector<glm::dvec3> normals = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (double x : {1.0, -1.0}) {
    for (double y : {1.0, -1.0}) {
      for (double z : {1.0, -1.0}) normals.push_back(glm::normalize(glm::dvec3(x, y, z)));
    }
  }
  return normals;
}

}  // namespace vs11
