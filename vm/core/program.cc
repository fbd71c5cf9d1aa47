#include "vm/core/program.h"

#include <set>

namespace vs11 {

ProgramStats ComputeStats(const Program& program) {
  ProgramStats stats;
  std::set<int> constants, temporaries, inputs;
  for (const Instruction& instruction : program.instructions) {
    const OpcodeInfo& info = instruction.info();
    if (!info.is_executable()) continue;
    ++stats.instructions;
    stats.slots += info.slots;
    if (info.has_dest() && instruction.dest.reg.file == RegisterFile::kTemp) {
      temporaries.insert(instruction.dest.reg.index);
    }
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      const int rows = info.registers_read(s);
      for (int row = 0; row < rows; ++row) {
        switch (reg.file) {
          case RegisterFile::kConst:
            constants.insert(reg.index + row + (reg.relative ? 1 << 16 : 0));
            stats.uses_relative_addressing |= reg.relative;
            break;
          case RegisterFile::kTemp: temporaries.insert(reg.index + row); break;
          case RegisterFile::kInput: inputs.insert(reg.index + row); break;
          default: break;
        }
      }
    }
  }
  stats.constants = static_cast<int>(constants.size());
  stats.temporaries = static_cast<int>(temporaries.size());
  stats.inputs = static_cast<int>(inputs.size());
  return stats;
}

}  // namespace vs11
