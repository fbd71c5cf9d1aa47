#include "irradiance/sh/constants_output.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh9.h"
#include "vm/asm/assembler.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/io/vertex_io.h"
#include "vm/reference/program_references.h"

namespace vs11::irradiance {
namespace {

using testing::HasSubstr;

// The program's float arithmetic (11 instructions on inputs rounded to float, ~10 roundings of
// 2^-24 each, relative to the largest term) against eq. (6) in double: the brief's limit.
constexpr double kProgramRelativeTolerance = 1e-5;

SevenConstants SampleConstants(std::uint64_t seed) { return PackTable1(RandomCoefficients(seed)); }

void ExpectSameBits(const Vec4f& actual, const glm::vec4& expected, const std::string& where) {
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(actual[c]), std::bit_cast<std::uint32_t>(expected[c]))
        << where << " lane " << c << ": " << actual[c] << " vs " << expected[c];
  }
}

TEST(ConstantsOutput, DefTextParsesBackBitForBit) {
  for (std::uint64_t seed : {1u, 2u, 3u, 99u}) {
    for (int base : {0, 10, 89}) {
      const SevenConstants constants = SampleConstants(seed);
      const std::string text = ConstantsDefText(constants, base, "a comment\n\nsecond line");
      ConstantBank bank;
      Diagnostics diagnostics;
      ParseConstantsText(text, "constants.vsh", bank, diagnostics);
      ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString() << text;
      for (int i = 0; i < 7; ++i) ExpectSameBits(bank[base + i], constants.registers[i], SevenConstants::kNames[i]);
      if (base > 0) ExpectSameBits(bank[base - 1], glm::vec4(0.0f), "register before the seven");
    }
  }
}

TEST(ConstantsOutput, DefTextNamesEachRegisterAndItsTable1Contents) {
  const std::string text = ConstantsDefText(SampleConstants(5), 0);
  EXPECT_THAT(text, HasSubstr("def c0, "));
  EXPECT_THAT(text, HasSubstr("; cAr = (c1 R11, c1 R1-1, c1 R10, c0 R00 - c3 R20)"));
  EXPECT_THAT(text, HasSubstr("; cBg = (c2 G2-2, c2 G2-1, 3 c3 G20, c2 G21)"));
  EXPECT_THAT(text, HasSubstr("def c6, "));
  EXPECT_THAT(text, HasSubstr("; cC = (c4 R22, c4 G22, c4 B22, unused)"));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 7);
}

TEST(ConstantsOutput, DefTextAssemblesInsideAProgramWithTheSameBits) {
  const SevenConstants constants = SampleConstants(7);
  const std::string source = "vs.1.1\n" + ConstantsDefText(constants, 0, "header") + "mov oPos, c0\n";
  AssembleResult assembled = AssembleSource(source, "defs.vsh", AssembleOptions{});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  const ConstantBank bank = ApplyDefinitions(*assembled.program, ConstantBank());
  for (int i = 0; i < 7; ++i) ExpectSameBits(bank[i], constants.registers[i], SevenConstants::kNames[i]);
}

TEST(ConstantsOutput, PaperProgramWithParsedConstantsReproducesEq6) {
  Result<PaperProgram> program = PaperProgram::Load();
  ASSERT_TRUE(program) << program.message();
  const std::vector<glm::dvec3> normals = SphereNormals(500);
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const Sh9Rgb sh = RandomCoefficients(seed);
    ConstantBank bank;
    Diagnostics diagnostics;
    ParseConstantsText(ConstantsDefText(PackTable1(sh), program->constant_base()), "c", bank, diagnostics);
    ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
    for (std::string kind : {"ref", "batch"}) {
      const std::array<int, 1> registers = {program->normal_register()};
      VertexArrays inputs = MakeInputArrays(normals.size(), registers);
      for (int c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < normals.size(); ++i) {
          inputs.lane(program->normal_register(), c)[i] = static_cast<float>(normals[i][c]);
        }
      }
      VertexArrays outputs = MakeOutputArrays(normals.size(), program->program());
      ASSERT_EQ(MakeEngine(kind, program->program(), bank).value()->Run(inputs, outputs).message(), "");
      double scale = 0.0;
      for (const glm::dvec3& n : normals) {
        const glm::dvec3 e = IrradianceEq6(sh, n);
        scale = std::max({scale, std::abs(e.x), std::abs(e.y), std::abs(e.z)});
      }
      double worst = 0.0;
      for (std::size_t i = 0; i < normals.size(); ++i) {
        const glm::dvec3 expected = IrradianceEq6(sh, normals[i]);
        for (int c = 0; c < 3; ++c) {
          worst = std::max(worst, std::abs(outputs.lane(program->output_slot(), c)[i] - expected[c]) / scale);
        }
      }
      EXPECT_LT(worst, kProgramRelativeTolerance) << "seed " << seed << " engine " << kind;
    }
  }
}

// Reads `inline constexpr float kName[4] = {a, b, c, d};` lines back with strtof.
std::vector<std::vector<float>> ParseCppArrays(const std::string& header, std::vector<std::string>& names) {
  static const std::regex kLine(R"(inline constexpr float (\w+)\[4\] = \{([^}]*)\};)");
  std::vector<std::vector<float>> arrays;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), kLine); it != std::sregex_iterator(); ++it) {
    names.push_back((*it)[1]);
    std::vector<float> values;
    std::string list = (*it)[2];
    std::size_t start = 0;
    while (start < list.size()) {
      std::size_t end = list.find(',', start);
      if (end == std::string::npos) end = list.size();
      std::string literal = list.substr(start, end - start);
      literal.erase(0, literal.find_first_not_of(' '));
      if (literal.find("quiet_NaN") != std::string::npos) {
        values.push_back(std::numeric_limits<float>::quiet_NaN());
      } else if (literal.find("infinity") != std::string::npos) {
        values.push_back(literal[0] == '-' ? -std::numeric_limits<float>::infinity()
                                           : std::numeric_limits<float>::infinity());
      } else {
        EXPECT_EQ(literal.back(), 'f') << literal;
        EXPECT_NE(literal.find_first_of(".e"), std::string::npos) << "not a float literal: " << literal;
        values.push_back(std::strtof(literal.c_str(), nullptr));
      }
      start = end + 1;
    }
    arrays.push_back(values);
  }
  return arrays;
}

TEST(ConstantsOutput, CppHeaderLiteralsReadBackBitForBit) {
  SevenConstants constants = SampleConstants(21);
  constants.registers[6].w = 1.0f;  // an integer value still needs a float literal: 1.0f
  const std::string header = ConstantsCppHeader(constants, "lighting", "generated");
  EXPECT_THAT(header, HasSubstr("#pragma once"));
  EXPECT_THAT(header, HasSubstr("namespace lighting {"));
  EXPECT_THAT(header, HasSubstr("1.0f"));
  EXPECT_THAT(header, testing::Not(HasSubstr("<limits>")));
  std::vector<std::string> names;
  const std::vector<std::vector<float>> arrays = ParseCppArrays(header, names);
  ASSERT_EQ(arrays.size(), 7u);
  EXPECT_THAT(names, testing::ElementsAre("kCAr", "kCAg", "kCAb", "kCBr", "kCBg", "kCBb", "kCC"));
  for (int i = 0; i < 7; ++i) {
    ASSERT_EQ(arrays[i].size(), 4u);
    ExpectSameBits({arrays[i][0], arrays[i][1], arrays[i][2], arrays[i][3]}, constants.registers[i], names[i]);
  }
}

TEST(ConstantsOutput, CppHeaderSpellsNonFiniteValuesWithNumericLimits) {
  SevenConstants constants = SampleConstants(22);
  constants.registers[0].x = std::numeric_limits<float>::infinity();
  constants.registers[1].y = -std::numeric_limits<float>::infinity();
  constants.registers[2].z = std::numeric_limits<float>::quiet_NaN();
  const std::string header = ConstantsCppHeader(constants);
  EXPECT_THAT(header, HasSubstr("#include <limits>"));
  EXPECT_THAT(header, HasSubstr("-std::numeric_limits<float>::infinity()"));
  std::vector<std::string> names;
  const std::vector<std::vector<float>> arrays = ParseCppArrays(header, names);
  ASSERT_EQ(arrays.size(), 7u);
  EXPECT_TRUE(std::isinf(arrays[0][0]) && arrays[0][0] > 0);
  EXPECT_TRUE(std::isinf(arrays[1][1]) && arrays[1][1] < 0);
  EXPECT_TRUE(std::isnan(arrays[2][2]));
}

TEST(ConstantsOutput, JsonHoldsTheSevenNamedRegistersInTable1Order) {
  const SevenConstants constants = SampleConstants(31);
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(ConstantsJson(constants).dump());
  std::vector<std::string> keys;
  for (const auto& [key, value] : json.items()) keys.push_back(key);
  EXPECT_THAT(keys, testing::ElementsAre("cAr", "cAg", "cAb", "cBr", "cBg", "cBb", "cC"));
  for (int i = 0; i < 7; ++i) {
    const auto& values = json[SevenConstants::kNames[i]];
    ASSERT_EQ(values.size(), 4u);
    ExpectSameBits({values[0].get<float>(), values[1].get<float>(), values[2].get<float>(), values[3].get<float>()},
                   constants.registers[i], SevenConstants::kNames[i]);
  }
}

}  // namespace
}  // namespace vs11::irradiance
