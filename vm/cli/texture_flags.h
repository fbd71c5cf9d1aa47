// `vs11 run`'s vertex textures (vs_3_0's texldl): --texture s#=FILE.npy binds a float32 array to a
// sampler, --texture-address s#=MODE[,MODE] sets its address modes.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/core/machine.h"

namespace vs11::cli {

struct TextureFlags {
  std::vector<std::string> textures;   // s#=FILE.npy
  std::vector<std::string> addresses;  // s#=wrap|clamp|border[,wrap|clamp|border]

  void AddTo(CLI::App& command);
  std::vector<std::string> Files() const;  // the .npy files, for CheckInputsAndOutputs
};

// Binds each --texture to its sampler in `bank`, with its --texture-address modes. Usage errors (exit
// 2): a malformed flag, a sampler named twice, a texture or address mode for a sampler the program does
// not declare (dcl_2d s#). Input errors (exit 1): a file that is no (H, W) or (H, W, 4) float32 array,
// each naming the file. A sampler the program declares with no texture: a warning on stderr naming it
// (it reads (0, 0, 0, 1)).
void BindTextures(const TextureFlags& flags, const Program& program, const std::string& program_name, ConstantBank& bank);

}  // namespace vs11::cli
