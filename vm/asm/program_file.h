// Programs from files: .vsh source (preprocessed, assembled, validated) or .vso bytecode (decoded,
// validated), and atomic file writing shared by every tool.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "vm/asm/assembler.h"
#include "vm/core/diagnostic.h"
#include "vm/core/program.h"

namespace vs11 {

struct LoadProgramOptions {
  AssembleOptions assemble;  // validate = false skips validation for .vso too
};

struct LoadedProgram {
  std::optional<Program> program;
  Diagnostics diagnostics;  // errors and warnings, with file:line:col for sources, word offsets for bytecode
  bool from_bytecode = false;
};

// Bytecode when the file starts with a vertex-shader version token in little-endian order or has the
// extension .vso/.cso/.bin; source otherwise.
LoadedProgram LoadProgram(const std::filesystem::path& path, const LoadProgramOptions& options = {});

// Writes `bytes` to a temporary file beside `path`, then renames it over `path`, so that a failure
// never leaves a partial file. Returns an error message on failure.
std::optional<std::string> WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes);
std::optional<std::string> WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

// Reads a whole file as bytes; nullopt when it cannot be opened.
std::optional<std::string> ReadWholeFile(const std::filesystem::path& path);

}  // namespace vs11
