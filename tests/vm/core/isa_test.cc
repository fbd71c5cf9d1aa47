// The opcode table's lookups: every row found by its token and mnemonic, nothing else found.
#include "vm/core/isa.h"

#include <string>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

TEST(Isa, EveryRowIsFoundByItsTokenAndByItsMnemonicInAnyCase) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    EXPECT_EQ(OpcodeFromToken(info.token), info.opcode) << info.mnemonic;
    EXPECT_EQ(OpcodeFromMnemonic(info.mnemonic), info.opcode);
    std::string upper(info.mnemonic);
    for (char& c : upper) c = static_cast<char>(c - ('a' <= c && c <= 'z' ? 'a' - 'A' : 0));
    EXPECT_EQ(OpcodeFromMnemonic(upper), info.opcode) << upper;
  }
}

TEST(Isa, TokensAndMnemonicsOutsideTheTableAreNotFound) {
  EXPECT_EQ(OpcodeFromToken(0x31), std::nullopt);  // between defi (0x30) and the pixel shaders' texcoord (0x40)
  EXPECT_EQ(OpcodeFromToken(0xFFFF), std::nullopt);  // the end token's low half
  EXPECT_EQ(OpcodeFromMnemonic("texld"), std::nullopt);
  EXPECT_EQ(OpcodeFromMnemonic("mo"), std::nullopt);
  EXPECT_EQ(OpcodeFromMnemonic(""), std::nullopt);
}

TEST(Isa, MatrixMacrosReadOneRegisterPerRowFromTheirSecondSourceOnly) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    for (int source = 0; source < info.source_count(); ++source) {
      const bool matrix = info.kind == ResultKind::kMatrix && source == OpcodeInfo::kMatrixSource;
      EXPECT_EQ(info.registers_read(source), matrix ? info.matrix_rows : 1) << info.mnemonic << " source " << source;
    }
    EXPECT_EQ(info.result_lanes(), info.kind == ResultKind::kMatrix ? info.matrix_rows : 4) << info.mnemonic;
  }
  EXPECT_EQ(Info(Opcode::kM4x3).registers_read(1), 3);
  EXPECT_EQ(Info(Opcode::kM3x2).result_lanes(), 2);
}

TEST(Isa, OnlyMovWritesTheAddressRegister) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    EXPECT_EQ(info.can_write_address(), info.opcode == Opcode::kMov) << info.mnemonic;
  }
}

TEST(Isa, DeclarationUsagesAreFoundByNameInAnyCase) {
  for (std::size_t i = 0; i < kDeclUsageNames.size(); ++i) {
    EXPECT_EQ(DeclUsageFromName(kDeclUsageNames[i]), static_cast<int>(i));
  }
  EXPECT_EQ(DeclUsageFromName("NORMAL"), kDeclUsageNormal);
  EXPECT_EQ(DeclUsageFromName("normals"), std::nullopt);
}

}  // namespace
}  // namespace vs11
