// The metadata lines of a verified program: a program says which reference (program_references.h)
// checks it through METADATA lines in its comment header, one per line, read from the raw text
// (before preprocessing) by ParseProgramMetadata:
//
//   ; vs11: reference=sh9            which reference (see References())
//   ; vs11: packing=table1           sh9: table1 | unit_sphere10 | matrix | basis | order0 | order1 | zh3
//   ; vs11: normal=v0                input register of the normal (sh9: (x, y, z, 1))
//   ; vs11: position=v0              input register of the position (x, y, z, 1)
//   ; vs11: weights=v1               skinning: blend weights (x, y)
//   ; vs11: indices=v2               skinning: 3 x bone index (x, y), as floats
//   ; vs11: texcoord=v2              all_instructions: texture coordinates (u, v, s, t)
//   ; vs11: output=oD0               the output register compared first (the "primary" output)
//   ; vs11: constants=c0             first constant register of the reference's layout
//   ; vs11: transform=c7             sh9: first of the 4 rows of WORLDVIEWPROJ; oPos is then checked
//   ; vs11: fragment=yes             the program computes a value only and writes no oPos; it is
//                                    validated with every rule except "oPos must be written"
//   ; vs11: tolerance=1e-5           default pass/fail tolerance (relative to the output's scale)
//
// programs/README.md documents the convention.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "vm/asm/program_file.h"
#include "vm/core/diagnostic.h"
#include "vm/core/program.h"

namespace vs11 {

// What a program's METADATA lines (or the command line) say. Unset fields take the reference's
// defaults (listed with each reference in References()).
struct ProgramMetadata {
  std::string reference;
  std::string packing;
  std::optional<int> normal;     // input register number
  std::optional<int> position;   // input register number
  std::optional<int> weights;    // input register number
  std::optional<int> indices;    // input register number
  std::optional<int> texcoord;   // input register number
  std::optional<int> output;     // OutputSlot value
  std::optional<int> constants;  // constant register number
  std::optional<int> transform;  // constant register number
  bool fragment = false;
  std::optional<double> tolerance;
};

// ---- metadata lines -------------------------------------------------------------------------------

struct MetadataResult {
  ProgramMetadata metadata;
  Diagnostics diagnostics;  // unknown keys, bad values (errors); repeated keys (warnings)
};

// Reads every `; vs11: key=value` (or `// vs11: key=value`) line of a program's raw text; see above
// for the keys. Other comment lines are ignored.
MetadataResult ParseProgramMetadata(std::string_view text, const std::string& file_name);

// ---- loading --------------------------------------------------------------------------------------

struct ProgramForVerify {
  std::optional<Program> program;  // set when loading (and validation, if asked) found no errors
  ProgramMetadata metadata;        // empty for bytecode files
  Diagnostics diagnostics;
};

// Loads a .vsh or bytecode file (vm/asm/program_file.h) and its metadata. With
// options.assemble.validate, a program whose metadata says fragment=yes is validated with every rule
// except "oPos must be written" (ValidatorOptions::require_position); any other program exactly as
// LoadProgram does. `fragment`, when set (a command line's --fragment or --no-fragment), wins over
// the metadata and over options.assemble.require_position.
ProgramForVerify LoadProgramForVerify(const std::filesystem::path& path, const LoadProgramOptions& options = {},
                                      std::optional<bool> fragment = std::nullopt);

// Validates a program that is only part of a vertex shader (it computes a value and writes no
// oPos): every vs_1_1 rule of the validator applies except the one demanding an oPos write.
Diagnostics ValidateFragment(const Program& program, int constant_count, bool dx9_rules);

}  // namespace vs11
