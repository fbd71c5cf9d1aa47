// The metadata lines of verified programs, and loading a program with them. See program_metadata.h.
#include "vm/reference/program_metadata.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "vm/asm/validator.h"
#include "vm/core/input_file.h"
#include "vm/core/register_names.h"
#include "vm/reference/program_references.h"

namespace vs11 {
namespace {


constexpr std::string_view kMetadataTag = "vs11:";

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<bool> ParseBool(std::string_view value) {
  const std::string v = Lower(value);
  if (v == "yes" || v == "true" || v == "1") return true;
  if (v == "no" || v == "false" || v == "0") return false;
  return std::nullopt;
}

// Applies one key=value to the metadata; returns an error message or "".
// What is wrong with one metadata line.
struct MetadataError {
  DiagnosticCode code;
  std::string message;
};

// Sets field `key` of `m` from `value`; what is wrong, if anything.
std::optional<MetadataError> ApplyMetadata(ProgramMetadata& m, const std::string& key, std::string_view value) {
  auto bad_value = [](std::string message) { return MetadataError{DiagnosticCode::kMetadataValue, std::move(message)}; };
  auto input = [&](std::optional<int>& field) -> std::optional<MetadataError> {
    field = ParseInputRegister(value);
    if (field) return std::nullopt;
    return bad_value(fmt::format("{}= expects an input register v0..v15, got '{}'", key, value));
  };
  auto constant = [&](std::optional<int>& field) -> std::optional<MetadataError> {
    field = ParseConstantRegister(value);
    if (field) return std::nullopt;
    return bad_value(fmt::format("{}= expects a constant register such as c0, got '{}'", key, value));
  };
  if (key == "reference") {
    m.reference = std::string(value);
    if (FindReference(value)) return std::nullopt;
    return bad_value(fmt::format("unknown reference '{}' (known: {})", value, ReferenceNames()));
  }
  if (key == "packing") {
    m.packing = std::string(value);
    if (kSh9PackingNames.Find(value)) return std::nullopt;
    return bad_value(fmt::format("unknown packing '{}' (use {})", value, kSh9PackingNames.List()));
  }
  if (key == "normal") return input(m.normal);
  if (key == "position") return input(m.position);
  if (key == "weights") return input(m.weights);
  if (key == "indices") return input(m.indices);
  if (key == "texcoord") return input(m.texcoord);
  if (key == "constants") return constant(m.constants);
  if (key == "transform") return constant(m.transform);
  if (key == "output") {
    m.output = OutputSlotFromName(value);
    if (m.output) return std::nullopt;
    return bad_value(
        fmt::format("output= expects an output register (oPos, oFog, oPts, oD0, oD1, oT0..oT7), got '{}'", value));
  }
  if (key == "fragment") {
    std::optional<bool> flag = ParseBool(value);
    if (flag) m.fragment = *flag;
    if (flag) return std::nullopt;
    return bad_value(fmt::format("fragment= expects yes or no, got '{}'", value));
  }
  if (key == "tolerance") {
    double t = 0;
    const std::string v(value);
    auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), t);
    if (ec != std::errc() || end != v.data() + v.size() || !(t >= 0) || !std::isfinite(t)) {
      return bad_value(fmt::format("tolerance= expects a non-negative number, got '{}'", value));
    }
    m.tolerance = t;
    return std::nullopt;
  }
  return MetadataError{DiagnosticCode::kMetadataUnknownKey,
                       fmt::format("unknown metadata key '{}' (reference, packing, normal, position, weights, indices, "
                                   "texcoord, output, constants, transform, fragment, tolerance)",
                                   key)};
}

}  // namespace

// ---- metadata -------------------------------------------------------------------------------------

MetadataResult ParseProgramMetadata(std::string_view text, const std::string& file_name) {
  MetadataResult result;
  std::vector<std::string> seen;
  int line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const std::size_t newline = text.find('\n');
    std::string_view line = Trim(text.substr(0, newline));
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
    if (line.starts_with("//")) {
      line.remove_prefix(2);
    } else if (line.starts_with(";")) {
      while (line.starts_with(";")) line.remove_prefix(1);
    } else {
      continue;
    }
    line = Trim(line);
    if (!line.starts_with(kMetadataTag)) continue;
    line = Trim(line.substr(kMetadataTag.size()));
    const SourceLoc loc{file_name, line_number, 0};
    const std::size_t equals = line.find('=');
    if (equals == std::string_view::npos) {
      result.diagnostics.Error(loc, DiagnosticCode::kMetadataSyntax,
                               fmt::format("metadata line needs key=value, got '{}'", line));
      continue;
    }
    const std::string key = Lower(Trim(line.substr(0, equals)));
    const std::string_view value = Trim(line.substr(equals + 1));
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
      result.diagnostics.Warning(loc, DiagnosticCode::kMetadataDuplicateKey,
                                 fmt::format("metadata key '{}' given again; the last value wins", key));
    }
    seen.push_back(key);
    if (std::optional<MetadataError> error = ApplyMetadata(result.metadata, key, value)) {
      result.diagnostics.Error(loc, error->code, std::move(error->message));
    }
  }
  return result;
}

// ---- loading --------------------------------------------------------------------------------------

Diagnostics ValidateFragment(const Program& program, int constant_count, bool dx9_rules) {
  ValidatorOptions options;
  options.require_position = false;
  options.constant_count = constant_count;
  options.dialect = dx9_rules ? ValidatorOptions::Dialect::kDx9 : ValidatorOptions::Dialect::kDx8;
  return Validate(program, options);
}

ProgramForVerify LoadProgramForVerify(const std::filesystem::path& path, const LoadProgramOptions& options,
                                      std::optional<bool> fragment) {
  ProgramForVerify result;
  // Read once: a pipe (/dev/stdin, "-") cannot be read a second time.
  const std::string name = InputDisplayName(path);
  Result<std::string> text = ReadInputFile(path, kMaxProgramFileBytes);
  if (!text) {
    result.diagnostics.Error({name}, text.error().code, text.message());
    return result;
  }
  MetadataResult metadata = ParseProgramMetadata(*text, name);
  LoadProgramOptions load_options = options;
  if (fragment) {
    load_options.assemble.require_position = !*fragment;
  } else if (metadata.metadata.fragment) {
    load_options.assemble.require_position = false;
  }
  LoadedProgram loaded = LoadProgramBytes(*text, name, load_options);
  if (!loaded.from_bytecode) {
    result.diagnostics.Append(metadata.diagnostics);
    result.metadata = std::move(metadata.metadata);
  }
  result.diagnostics.Append(loaded.diagnostics);
  if (!loaded.program || result.diagnostics.HasErrors()) return result;
  result.program = std::move(loaded.program);
  return result;
}

}  // namespace vs11
