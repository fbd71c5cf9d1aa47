// Register names outside a program's text are read with the assembler's spelling table.
#include "vm/core/register_names.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vs11
