#include "vm/core/isa.h"

#include <algorithm>
#include <cctype>

namespace vs11 {
namespace {

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::optional<Opcode> OpcodeFromToken(std::uint16_t token) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (info.token == token) return info.opcode;
  }
  return std::nullopt;
}

std::optional<Opcode> OpcodeFromMnemonic(std::string_view mnemonic) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (EqualsIgnoringCase(info.mnemonic, mnemonic)) return info.opcode;
  }
  return std::nullopt;
}

std::optional<int> DeclUsageFromName(std::string_view name) {
  for (int i = 0; i < static_cast<int>(kDeclUsageNames.size()); ++i) {
    if (EqualsIgnoringCase(kDeclUsageNames[i], name)) return i;
  }
  return std::nullopt;
}

std::optional<int> ComparisonFromName(std::string_view name) {
  for (int i = 1; i < static_cast<int>(kComparisonNames.size()); ++i) {
    if (EqualsIgnoringCase(kComparisonNames[i], name)) return i;
  }
  return std::nullopt;
}

std::optional<int> SamplerTypeFromName(std::string_view name) {
  for (int i = 0; i < static_cast<int>(kSamplerTypeNames.size()); ++i) {
    if (!kSamplerTypeNames[i].empty() && EqualsIgnoringCase(kSamplerTypeNames[i], name)) return i;
  }
  return std::nullopt;
}

}  // namespace vs11
