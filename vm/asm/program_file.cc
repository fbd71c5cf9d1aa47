#include "vm/asm/program_file.h"

#include <cstdio>

#include <fmt/format.h>

#include "vm/asm/bytecode.h"
#include "vm/asm/validator.h"
#include "vm/core/input_file.h"

namespace vs11 {
namespace {

bool LooksLikeBytecode(const std::filesystem::path& path, std::string_view bytes) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".vso" || extension == ".cso" || extension == ".bin") return true;
  // 0xFFFE01xx to 0xFFFE03xx little-endian: xx 01 FE FF (vs_1_x) ... xx 03 FE FF (vs_3_0).
  const auto major = static_cast<unsigned char>(bytes.size() >= 4 ? bytes[1] : 0);
  return bytes.size() >= 4 && major >= 0x01 && major <= 0x03 &&
         static_cast<unsigned char>(bytes[2]) == 0xFE && static_cast<unsigned char>(bytes[3]) == 0xFF;
}

LoadedProgram LoadBytecode(const std::filesystem::path& path, std::string_view bytes, const LoadProgramOptions& options) {
  LoadedProgram loaded;
  loaded.from_bytecode = true;
  std::span<const std::uint8_t> raw(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  std::optional<std::vector<std::uint32_t>> words = WordsFromBytes(raw);
  if (!words) {
    loaded.diagnostics.Error({path.string()}, DiagnosticCode::kBytecodeTruncated,
                             fmt::format("{} bytes is not a whole number of 32-bit tokens", bytes.size()));
    return loaded;
  }
  DecodeResult decoded = Decode(*words);
  for (Diagnostic d : decoded.diagnostics.all()) {
    d.loc.file = path.string();
    loaded.diagnostics.Add(std::move(d));
  }
  if (!decoded.program) return loaded;
  if (options.assemble.validate) {
    ValidatorOptions validator;
    validator.constant_count = options.assemble.constant_count;
    validator.require_position = options.assemble.require_position;
    validator.strict = options.assemble.strict;
    Diagnostics validation = Validate(*decoded.program, validator);
    for (Diagnostic d : validation.all()) {
      if (d.loc.file.empty()) d.loc.file = path.string();
      loaded.diagnostics.Add(std::move(d));
    }
    if (loaded.diagnostics.HasErrors()) return loaded;
  }
  loaded.program = std::move(decoded.program);
  return loaded;
}

}  // namespace

std::optional<std::string> ReadWholeFile(const std::filesystem::path& path) {
  Result<std::string> bytes = ReadInputFile(path, kMaxInputFileBytes);
  if (!bytes) return std::nullopt;
  return std::move(*bytes);
}

LoadedProgram LoadProgramBytes(std::string_view bytes, const std::string& name, const LoadProgramOptions& options) {
  if (LooksLikeBytecode(name, bytes)) return LoadBytecode(name, bytes, options);
  AssembleResult assembled = AssembleSource(bytes, name, options.assemble);
  LoadedProgram loaded;
  loaded.diagnostics = std::move(assembled.diagnostics);
  if (!loaded.diagnostics.HasErrors()) loaded.program = std::move(assembled.program);
  return loaded;
}

LoadedProgram LoadProgram(const std::filesystem::path& path, const LoadProgramOptions& options) {
  Result<std::string> bytes = ReadInputFile(path, kMaxProgramFileBytes);
  if (!bytes) {
    LoadedProgram loaded;
    loaded.diagnostics.Error({InputDisplayName(path)}, bytes.error().code, bytes.message());
    return loaded;
  }
  return LoadProgramBytes(*bytes, InputDisplayName(path), options);
}

}  // namespace vs11
