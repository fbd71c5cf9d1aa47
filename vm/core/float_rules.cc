#include "vm/core/float_rules.h"

namespace vs11 {

std::optional<FloatRules> FloatRulesFromName(std::string_view name) {
  if (name == "d3d9") return FloatRules::kD3d9;
  if (name == "legacy") return FloatRules::kLegacy;
  return std::nullopt;
}

std::string_view FloatRulesName(FloatRules rules) {
  return rules == FloatRules::kLegacy ? "legacy" : "d3d9";
}

}  // namespace vs11
