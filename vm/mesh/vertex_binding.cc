#include "vm/mesh/vertex_binding.h"

#include <charconv>

#include <fmt/format.h>

#include "vm/core/register_names.h"

namespace vs11::mesh {
namespace {

struct AttributeSpelling {
  std::string_view name;
  Attribute attribute;
  bool has_sets;
};
constexpr AttributeSpelling kSpellings[] = {
    {"position", Attribute::kPosition, false},  {"normal", Attribute::kNormal, false},
    {"tangent", Attribute::kTangent, false},    {"binormal", Attribute::kBinormal, false},
    {"texcoord", Attribute::kTexCoord, true},   {"color", Attribute::kColor, true},
    {"blendweight", Attribute::kBlendWeight, false}, {"blendindices", Attribute::kBlendIndices, false},
};

std::string Lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return out;
}

std::string_view Trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// The attribute a D3DDECLUSAGE stands for, if a mesh has one.
std::optional<Attribute> AttributeOfUsage(std::string_view usage) {
  for (const AttributeSpelling& spelling : kSpellings) {
    if (spelling.name == usage) return spelling.attribute;
  }
  return std::nullopt;
}

std::string Hint(const AttributeRef& attribute) {
  switch (attribute.attribute) {
    case Attribute::kNormal: return "--compute-normals generates smooth normals";
    case Attribute::kTangent:
    case Attribute::kBinormal: return "--compute-tangents generates them from texcoord0 (the mesh needs UVs)";
    case Attribute::kBlendWeight:
    case Attribute::kBlendIndices: return "only skinned meshes (with bones) have them";
    default: return "bind the register to an attribute the mesh has with --bind v#=ATTRIBUTE";
  }
}

std::string ListAttributes(const Mesh& mesh) {
  std::string list;
  auto add = [&](const AttributeRef& a) {
    if (mesh.Find(a.attribute, a.set) != nullptr) list += (list.empty() ? "" : ", ") + AttributeName(a);
  };
  for (Attribute a : {Attribute::kPosition, Attribute::kNormal, Attribute::kTangent, Attribute::kBinormal,
                      Attribute::kBlendWeight, Attribute::kBlendIndices}) {
    add({a, 0});
  }
  for (int set = 0; set < kMaxTexCoordSets; ++set) add({Attribute::kTexCoord, set});
  for (int set = 0; set < kMaxColorSets; ++set) add({Attribute::kColor, set});
  return list;
}

}  // namespace

std::optional<AttributeRef> AttributeFromName(std::string_view name) {
  const std::string lower = Lower(Trim(name));
  for (const AttributeSpelling& spelling : kSpellings) {
    if (lower.rfind(spelling.name, 0) != 0) continue;
    std::string_view rest = std::string_view(lower).substr(spelling.name.size());
    if (rest.empty()) return AttributeRef{spelling.attribute, 0};
    if (!spelling.has_sets || rest.size() != 1 || rest[0] < '0' || rest[0] > '7') continue;
    return AttributeRef{spelling.attribute, rest[0] - '0'};
  }
  return std::nullopt;
}

std::string AttributeName(const AttributeRef& attribute) {
  for (const AttributeSpelling& spelling : kSpellings) {
    if (spelling.attribute == attribute.attribute) {
      return spelling.has_sets ? fmt::format("{}{}", spelling.name, attribute.set) : std::string(spelling.name);
    }
  }
  return "?";
}

Status ParseBindings(std::string_view text, std::vector<RegisterBinding>& bindings) {
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view item = Trim(text.substr(0, comma));
    const std::size_t equals = item.find('=');
    if (equals == std::string_view::npos) {
      return Failure(DiagnosticCode::kBinding, fmt::format("'{}': expected v#=ATTRIBUTE, e.g. v3=normal", item));
    }
    std::optional<int> reg = ParseInputRegister(item.substr(0, equals));
    if (!reg) {
      return Failure(DiagnosticCode::kBinding,
                     fmt::format("'{}' is not an input register v0-v15", Trim(item.substr(0, equals))));
    }
    std::optional<AttributeRef> attribute = AttributeFromName(item.substr(equals + 1));
    if (!attribute) {
      return Failure(DiagnosticCode::kBinding,
                     fmt::format("'{}' is not a mesh attribute (position, normal, tangent, binormal, texcoord0-7, "
                                 "color0-7, blendweight, blendindices)",
                                 Trim(item.substr(equals + 1))));
    }
    bindings.push_back({*reg, *attribute, fmt::format("--bind {}", item)});
    if (comma == std::string_view::npos) return {};
    text.remove_prefix(comma + 1);
  }
}

Status ResolveBindings(const Program& program, const std::vector<RegisterBinding>& overrides,
                       std::vector<RegisterBinding>& bindings) {
  bindings.clear();
  auto overridden = [&](int reg) {
    for (const RegisterBinding& b : overrides) {
      if (b.reg == reg) return true;
    }
    return false;
  };
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode != Opcode::kDcl || instruction.dest.reg.file != RegisterFile::kInput) continue;
    const int reg = instruction.dest.reg.index;
    if (overridden(reg)) continue;
    const std::string_view usage = instruction.usage >= 0 && instruction.usage < static_cast<int>(kDeclUsageNames.size())
                                       ? kDeclUsageNames[instruction.usage]
                                       : std::string_view("?");
    const std::string origin = fmt::format("dcl_{}{} v{}", usage, instruction.usage_index == 0 ? "" : std::to_string(instruction.usage_index), reg);
    std::optional<Attribute> attribute = AttributeOfUsage(usage);
    const bool has_sets = attribute == Attribute::kTexCoord || attribute == Attribute::kColor;
    if (!attribute || (!has_sets && instruction.usage_index != 0) || instruction.usage_index >= kMaxTexCoordSets) {
      return Failure(
          DiagnosticCode::kBinding,
          fmt::format("{}: a mesh has no such attribute; bind v{} with --bind v{}=ATTRIBUTE", origin, reg, reg));
    }
    bindings.push_back({reg, {*attribute, has_sets ? instruction.usage_index : 0}, origin});
  }
  for (const RegisterBinding& b : overrides) {
    std::erase_if(bindings, [&](const RegisterBinding& old) { return old.reg == b.reg; });
    bindings.push_back(b);
  }
  return {};
}

Status BindMesh(const Mesh& mesh, const std::vector<RegisterBinding>& bindings, const BindOptions& options,
                RegisterData& registers) {
  for (const RegisterBinding& binding : bindings) {
    const std::vector<Vec4f>* array = mesh.Find(binding.attribute.attribute, binding.attribute.set);
    if (array == nullptr) {
      return Failure(
          DiagnosticCode::kMeshAttributeMissing,
          fmt::format("{} needs {}, and {} has none (it has: {}); {}", binding.origin, AttributeName(binding.attribute),
                      options.mesh_name, ListAttributes(mesh), Hint(binding.attribute)));
    }
    std::vector<Vec4f> values = *array;
    if (binding.attribute.attribute == Attribute::kBlendIndices && options.blend_index_scale != 1.0f) {
      for (Vec4f& v : values) {
        for (float& c : v) c *= options.blend_index_scale;
      }
    }
    std::erase_if(registers, [&](const auto& entry) { return entry.first == binding.reg; });
    registers.emplace_back(binding.reg, std::move(values));
  }
  return {};
}

Status WriteBonePalette(const Mesh& mesh, int base, ConstantBank& constants) {
  if (mesh.bones.empty()) return Failure(DiagnosticCode::kBonePalette, "the mesh has no bones for a palette");
  const long last = static_cast<long>(base) + 3L * static_cast<long>(mesh.bones.size()) - 1;
  if (base < 0 || last >= constants.size()) {
    return Failure(DiagnosticCode::kBonePalette,
                   fmt::format("{} bones need c{}..c{}, beyond the {} constant registers (raise --max-constants)",
                               mesh.bones.size(), base, last, constants.size()));
  }
  for (std::size_t b = 0; b < mesh.bones.size(); ++b) {
    for (int row = 0; row < 3; ++row) {
      Vec4f& c = constants[base + 3 * static_cast<int>(b) + row];
      for (int column = 0; column < 4; ++column) c[column] = static_cast<float>(mesh.bones[b].skin[row][column]);
    }
  }
  return {};
}

}  // namespace vs11::mesh
