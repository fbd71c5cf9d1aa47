#include "vm/cli/texture_flags.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "vm/cli/cli_support.h"
#include "vm/mesh/npy.h"

namespace vs11::cli {
namespace {

constexpr std::array<std::pair<std::string_view, TextureAddress>, 3> kAddressNames = {
    {{"wrap", TextureAddress::kWrap}, {"clamp", TextureAddress::kClamp}, {"border", TextureAddress::kBorder}}};

// "s2=VALUE" -> {2, "VALUE"}, or a usage error naming `option`.
std::pair<int, std::string> SplitSamplerAssignment(std::string_view option, const std::string& flag, std::string_view value) {
  const std::size_t equals = flag.find('=');
  const std::string name = flag.substr(0, equals);
  if (equals == std::string::npos) FailUsage(fmt::format("{} '{}': expected s#={}", option, flag, value));
  const bool numbered = name.size() == 2 && (name[0] == 's' || name[0] == 'S') && name[1] >= '0' &&
                        name[1] < static_cast<char>('0' + kVertexSamplerCount);
  if (!numbered) FailUsage(fmt::format("{} '{}': '{}' is not a vertex sampler s0-s{}", option, flag, name, kVertexSamplerCount - 1));
  return {name[1] - '0', flag.substr(equals + 1)};
}

TextureAddress AddressFromName(const std::string& flag, std::string_view name) {
  for (const auto& [spelling, mode] : kAddressNames) {
    if (spelling == name) return mode;
  }
  FailUsage(fmt::format("--texture-address '{}': '{}' is not wrap, clamp or border", flag, name));
}

// The samplers the program declares (dcl_2d s#).
std::vector<int> DeclaredSamplers(const Program& program) {
  std::vector<int> samplers;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode == Opcode::kDcl && instruction.dest.reg.file == RegisterFile::kSampler) {
      samplers.push_back(instruction.dest.reg.index);
    }
  }
  return samplers;
}

// (H, W): R32F; (H, W, 4): A32B32G32R32F; anything else an error naming the file.
std::shared_ptr<const VertexTexture> ReadTexture(const std::string& file) {
  Result<mesh::NpyGrid> grid = mesh::ReadNpyGrid(file);
  if (!grid) Fail(grid.message());
  const std::vector<std::size_t>& shape = grid->shape;
  const bool r32f = shape.size() == 2;
  if (!r32f && !(shape.size() == 3 && shape[2] == 4)) {
    Fail(fmt::format("{}: shape ({}) is no vertex texture: give (H, W) for R32F or (H, W, 4) for A32B32G32R32F", file,
                     fmt::join(shape, ", ")));
  }
  const auto size = [&](std::size_t n) { return static_cast<int>(std::min<std::size_t>(n, kMaxTextureTexels + 1)); };
  Result<VertexTexture> texture = VertexTexture::Make(r32f ? TextureFormat::kR32F : TextureFormat::kA32B32G32R32F,
                                                      size(shape[1]), size(shape[0]), std::move(grid->values));
  if (!texture) Fail(fmt::format("{}: {}", file, texture.message()));
  return std::make_shared<const VertexTexture>(std::move(texture).value());
}

}  // namespace

void TextureFlags::AddTo(CLI::App& command) {
  command.add_option("--texture", textures,
                     "Vertex texture for texldl from a float32 .npy array: (H, W) is R32F, (H, W, 4) A32B32G32R32F, "
                     "e.g. s0=heights.npy");
  command.add_option("--texture-address", addresses,
                     "A sampler's address modes for u and v: wrap (the default), clamp or border (reads 0), e.g. "
                     "s0=clamp or s0=wrap,clamp");
}

std::vector<std::string> TextureFlags::Files() const {
  std::vector<std::string> files;
  for (const std::string& flag : textures) files.push_back(flag.substr(flag.find('=') + 1));
  return files;
}

void BindTextures(const TextureFlags& flags, const Program& program, const std::string& program_name, ConstantBank& bank) {
  const std::vector<int> declared = DeclaredSamplers(program);
  const auto check_declared = [&](std::string_view option, int sampler, const std::string& what) {
    if (std::ranges::find(declared, sampler) != declared.end()) return;
    FailUsage(fmt::format("{} {}: {} declares no sampler s{} (dcl_2d s{})", option, what, program_name, sampler, sampler));
  };
  std::vector<int> textured, addressed;
  for (const std::string& flag : flags.textures) {
    const auto [sampler, file] = SplitSamplerAssignment("--texture", flag, "FILE.npy");
    NoteRegisterOnce("--texture", 's', sampler, textured);
    check_declared("--texture", sampler, file);
  }
  for (const std::string& flag : flags.addresses) {
    const auto [sampler, modes] = SplitSamplerAssignment("--texture-address", flag, "MODE[,MODE]");
    NoteRegisterOnce("--texture-address", 's', sampler, addressed);
    check_declared("--texture-address", sampler, flag);
    const std::size_t comma = modes.find(',');
    SamplerState& state = bank.sampler(sampler).state;
    state.address_u = AddressFromName(flag, modes.substr(0, comma));
    state.address_v = comma == std::string::npos ? state.address_u : AddressFromName(flag, modes.substr(comma + 1));
  }
  for (const std::string& flag : flags.textures) {
    const auto [sampler, file] = SplitSamplerAssignment("--texture", flag, "FILE.npy");
    bank.sampler(sampler).texture = ReadTexture(file);
  }
  for (int sampler : declared) {
    if (sampler < 0 || sampler >= kVertexSamplerCount || bank.sampler(sampler).texture) continue;
    std::fprintf(stderr, "%s: warning: s%d is declared but no --texture binds it: texldl reads (0, 0, 0, 1) there\n",
                 program_name.c_str(), sampler);
  }
}

}  // namespace vs11::cli
