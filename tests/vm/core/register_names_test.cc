// Register names outside a program's text are read with the assembler's spelling table.
#include "vm/core/register_names.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/io/vertex_io.h"
#include "vm/mesh/vertex_binding.h"
#include "vm/mesh/vertex_buffer.h"
#include "vm/reference/program_metadata.h"

namespace vs11 {
namespace {

TEST(RegisterNames, ParseANumberedRegisterOfTheAskedFileInAnyCase) {
  EXPECT_EQ(ParseNumberedRegister("v0", RegisterFile::kInput), 0);
  EXPECT_EQ(ParseNumberedRegister("V15", RegisterFile::kInput), 15);
  EXPECT_EQ(ParseNumberedRegister("c95", RegisterFile::kConst), 95);
  EXPECT_EQ(ParseNumberedRegister("oT3", RegisterFile::kTexCoordOut), 3);
  EXPECT_EQ(ParseNumberedRegister("OD1", RegisterFile::kAttributeOut), 1);
}

TEST(RegisterNames, RejectAnotherFileASignSpacesAndTrailingText) {
  EXPECT_EQ(ParseNumberedRegister("c1", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("v", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("v-1", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("v+1", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("v 1", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("v1x", RegisterFile::kInput), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("c99999999999", RegisterFile::kConst), std::nullopt);
  EXPECT_EQ(ParseNumberedRegister("oPos", RegisterFile::kRasterOut), std::nullopt);  // fixed, not numbered
}

TEST(RegisterNames, PrefixIsTheSpellingsLength) {
  EXPECT_EQ(NumberedRegisterPrefix("c[7]", RegisterFile::kConst), 1u);
  EXPECT_EQ(NumberedRegisterPrefix("Ot2", RegisterFile::kTexCoordOut), 2u);
  EXPECT_EQ(NumberedRegisterPrefix("x1", RegisterFile::kConst), 0u);
}

TEST(RegisterNames, InputAndConstantNamesOutsideAProgram) {
  EXPECT_EQ(ParseInputRegister("v0"), 0);
  EXPECT_EQ(ParseInputRegister("V15"), 15);
  EXPECT_EQ(ParseInputRegister("v16"), std::nullopt);
  EXPECT_EQ(ParseInputRegister("c1"), std::nullopt);
  EXPECT_EQ(ParseInputRegister("v"), std::nullopt);
  EXPECT_EQ(ParseConstantRegister("c7"), 7);
  EXPECT_EQ(ParseConstantRegister("c[ 95 ]"), 95);
  EXPECT_EQ(ParseConstantRegister("c-1"), std::nullopt);
  EXPECT_EQ(ParseConstantRegister("c[3"), std::nullopt);
}

// Spellings of input and constant registers, with what each means (nullopt: rejected).
struct Spelling {
  std::string text;
  std::optional<int> index;
};
const std::vector<Spelling> kInputSpellings = {
    {"v0", 0},         {"V15", 15},      {" v3 ", 3},      {"v16", std::nullopt}, {"v", std::nullopt},
    {"c1", std::nullopt}, {"v-1", std::nullopt}, {"v+1", std::nullopt}, {"v 1", std::nullopt},
    {"v1x", std::nullopt}, {"v[1]", std::nullopt}, {"r0", std::nullopt},
};
const std::vector<Spelling> kConstantSpellings = {
    {"c0", 0},           {"C12", 12},         {" c7 ", 7},         {"c[7]", 7},          {"c[ 95 ]", 95},
    {"c2047", 2047},     {"c2048", std::nullopt}, {"c", std::nullopt}, {"c-1", std::nullopt},
    {"c[3", std::nullopt}, {"c[]", std::nullopt}, {"c 1", std::nullopt}, {"v1", std::nullopt},
    {"c99999999999", std::nullopt},
};

std::optional<int> FromMetadata(const std::string& key, const std::string& name) {
  const MetadataResult parsed = ParseProgramMetadata("; vs11: " + key + "=" + name + "\n", "test.vsh");
  if (parsed.diagnostics.HasErrors()) return std::nullopt;
  return key == "normal" ? parsed.metadata.normal : parsed.metadata.constants;
}

// Every place a register is named outside a program's text (vs11 run --input, --bind, --element,
// metadata lines) reads it through ParseInputRegister or ParseConstantRegister, so they agree.
TEST(RegisterNames, EveryEntryPointAcceptsTheSameInputSpellings) {
  for (const Spelling& spelling : kInputSpellings) {
    SCOPED_TRACE(spelling.text);
    EXPECT_EQ(ParseInputRegister(spelling.text), spelling.index);
    const Result<InputSpec> spec = ParseInputSpec(spelling.text + "=inputs.csv");
    EXPECT_EQ(spec ? std::optional<int>(spec->reg) : std::nullopt, spelling.index) << spec.message();
    std::vector<mesh::RegisterBinding> bindings;
    const Status bound = mesh::ParseBindings(spelling.text + "=normal", bindings);
    EXPECT_EQ(bound ? std::optional<int>(bindings.at(0).reg) : std::nullopt, spelling.index);
    mesh::BufferElement element;
    const Status parsed = mesh::ParseBufferElement(spelling.text + "=0:3", element);
    EXPECT_EQ(parsed ? std::optional<int>(element.reg) : std::nullopt, spelling.index);
    EXPECT_EQ(FromMetadata("normal", spelling.text), spelling.index);
  }
}

TEST(RegisterNames, EveryEntryPointAcceptsTheSameConstantSpellings) {
  for (const Spelling& spelling : kConstantSpellings) {
    SCOPED_TRACE(spelling.text);
    EXPECT_EQ(ParseConstantRegister(spelling.text), spelling.index);
    EXPECT_EQ(FromMetadata("constants", spelling.text), spelling.index);
  }
}

}  // namespace
}  // namespace vs11
