// irrmap's options checked before any work: the values alone (a usage error), then what they name
// on disk (the environment, the output folder, outputs that would overwrite an input). Used by the
// irrmap job (irrmap_job.cc); the public checks are declared in irrmap_job.h.
#pragma once

#include <optional>
#include <string>

#include "irradiance/jobs/engine_exports.h"
#include "irradiance/jobs/irrmap_job.h"

namespace vs11::irradiance {

// What the options say once checked.
struct CheckedOptions {
  std::string engine = "batch";
  std::optional<ShOrder> order;  // nullopt: chosen by max_error
  bool builtin = false;
  int threads = 1;
  CheckedExports exports;  // --map-format, --sh-export
};

// "face size N has levels 0 (NxN) to K (1x1)".
std::string LevelRange(int face_size);

// "--level 9" or "level=9", as the caller named the option.
std::string LevelWithValue(const IrrmapOptions& options);

// The options' own values (kOptionValue, or kFaceSize); the environment and the output folder are
// CheckOptions'.
Status CheckOptionValues(const IrrmapOptions& options, CheckedOptions& checked);

// CheckOptionValues, then the environment and the output folder; fills `checked`.
Status CheckOptions(const IrrmapOptions& options, CheckedOptions& checked);

}  // namespace vs11::irradiance
