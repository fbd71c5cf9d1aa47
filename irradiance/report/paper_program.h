// The embedded irradiance programs (programs/*.vsh compiled into the binary), assembled and ready to
// run on any engine: what irrmap, mesh lighting, the chart and the stability report evaluate.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/sh/constants_output.h"
#include "irradiance/sh/sh9.h"
#include "irradiance/sh/sh_order.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The paper's program (programs/sh9_irradiance.vsh, compiled into the binary) ready to run: its
// registers come from the program's own metadata comments (normal=v0, output=oD0, constants=c0).
class PaperProgram {
 public:
  // Assembles and validates (as a fragment: it writes no oPos) the embedded text; an error
  // (kEmbeddedProgram) if that fails (a build problem, not a user one).
  static Result<PaperProgram> Load();
  // The same for another embedded irradiance program with the same metadata lines (such as
  // programs/sh9_irradiance_unit10.vsh, which takes PackUnitSphere10 constants).
  static Result<PaperProgram> LoadEmbedded(std::string_view file_name, std::string_view text);
  // The program of an order (Info(order).program_file, embedded).
  static Result<PaperProgram> LoadOrder(ShOrder order);
  // The text of an embedded program by file name ("sh_order1.vsh"); empty when there is none.
  static std::string_view EmbeddedText(std::string_view file_name);

  const Program& program() const { return program_; }
  int normal_register() const { return normal_register_; }  // v#
  int output_slot() const { return output_slot_; }          // OutputSlot
  int constant_base() const { return constant_base_; }      // c# of cAr

  // The constant bank with the seven registers (or any list of them) from constant_base() on.
  ConstantBank Constants(const SevenConstants& constants) const;
  ConstantBank Constants(std::span<const NamedRegister> registers) const;
  // Runs the program once per normal (as (x, y, z, 1) in floats) and returns the output's rgb, or
  // why the engine could not be built or failed to run (the gl engine's driver; the CPU engines never
  // fail, and irrmap checks that the gl engine builds before any work).
  Result<std::vector<glm::dvec3>> Irradiance(const SevenConstants& constants, std::span<const glm::dvec3> normals,
                                             std::string engine, const EngineOptions& engine_options = {}) const;
  Result<std::vector<glm::dvec3>> Irradiance(const ConstantBank& bank, std::span<const glm::dvec3> normals,
                                             std::string engine, const EngineOptions& engine_options = {}) const;

 private:
  Program program_;
  int normal_register_ = 0;
  int output_slot_ = 0;
  int constant_base_ = 0;
};

}  // namespace vs11::irradiance
