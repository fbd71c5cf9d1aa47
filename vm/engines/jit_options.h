// The jit engine's own options (EngineOptions::settings): the instruction set it compiles to.
#pragma once

#include "vm/core/machine.h"
#include "vm/core/name_table.h"

namespace vs11 {

// The instruction set the jit engine compiles to: the best the CPU has, or one forced (for tests and
// benchmarks). A forced set the CPU lacks leaves the program on the batch kernels.
enum class JitIsa { kBest, kAvx2, kAvx512 };
inline constexpr NameTable kJitIsaNames("jit instruction set", {
    Choice(JitIsa::kBest, "best"), Choice(JitIsa::kAvx2, "avx2"), Choice(JitIsa::kAvx512, "avx512")});

struct JitOptions {
  JitIsa isa = JitIsa::kBest;
};

// `options` with the jit's instruction set forced to `isa`.
inline EngineOptions WithJitIsa(EngineOptions options, JitIsa isa) {
  options.settings.Set(JitOptions{isa});
  return options;
}

}  // namespace vs11
