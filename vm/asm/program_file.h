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
// extension .vso/.cso/.bin; source otherwise. The file is read once (a pipe or "-" for standard
// input work too), up to kMaxProgramFileBytes (vm/core/input_file.h).
LoadedProgram LoadProgram(const std::filesystem::path& path, const LoadProgramOptions& options = {});
// The same for a file already read; `name` is its name in messages (and its extension counts).
LoadedProgram LoadProgramBytes(std::string_view bytes, const std::string& name, const LoadProgramOptions& options = {});

// Reads a whole file as bytes (ReadInputFile, up to kMaxInputFileBytes); nullopt when it cannot be
// read.
std::optional<std::string> ReadWholeFile(const std::filesystem::path& path);

}  // namespace vs11
