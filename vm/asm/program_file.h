// Programs from files: .vsh source (preprocessed, assembled, validated) or .vso bytecode (decoded,
// validated).
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

// Reads a whole file as bytes; nullopt when it cannot be opened.
std::optional<std::string> ReadWholeFile(const std::filesystem::path& path);

}  // namespace vs11
