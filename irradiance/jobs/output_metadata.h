// What every vs11 output that holds coefficients says about itself: coeffs.json, each `irrmap batch`
// record, and the Python module's Projection.metadata. Under "schema_version" (the layout of the
// output: kOutputSchemaVersion), "convention" and "provenance":
//
//   "convention": {"quantity": "radiance", "basis", "coefficient_order": ["L00", "L1-1", ..., "L22"],
//                  "channels": ["r", "g", "b"], "frame": "direct3d_cube", "frame_description",
//                  "source_kind": "cube" or "latlong" (ShSourceKind: which column of --sh-export's
//                  frames applies, irradiance/sh/engine_sh.h), "units", "scale": 1, "window", "constants"}
//   "provenance": {"vs11_version", "input": the environment as given, "input_kind": the layout read
//                  ("latlong", "angular", "hcross", "vcross", "hstrip", "vstrip", "faces", "dds",
//                  "builtin", or what an array was taken as), "files": [{"path" (absolute),
//                  "size_bytes", "sha256"}] (every file read: one, six for a "{face}" pattern, none for
//                  a built-in or an array), "options": {"layout", "face_size", "level", "max_error",
//                  "error_metric", "order", "window", "window_width"}: every option that changes the
//                  numbers, as asked (no "level": chosen by max_error), named as the Python arguments}
//
// Schema versions: 1, outputs without "schema_version" (vs11 before 0.1.0's provenance); 2, these.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "irradiance/sh/engine_sh.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

struct IrrmapOptions;
struct IrrmapReport;

inline constexpr int kOutputSchemaVersion = 2;

struct InputFileDigest {
  std::string path;  // absolute
  std::uintmax_t size_bytes = 0;
  std::string sha256;  // 64 lowercase hex digits
};

// The size and SHA-256 of a file (OpenSSL's EVP), or why it cannot be read (kCannotReadFile).
Status DigestInputFile(const std::filesystem::path& path, InputFileDigest& digest);

// The files an environment path reads: itself, or the six of a "{face}" pattern (each face under
// the name that exists, px or posx, as the loader looks for them).
std::vector<std::filesystem::path> EnvironmentFiles(const std::string& environment);

// "cube" or "latlong".
std::string_view ShSourceKindName(ShSourceKind kind);

// {"schema_version", "convention", "provenance"} of a finished job (report.input_files digested).
nlohmann::ordered_json OutputMetadata(const IrrmapReport& report, const IrrmapOptions& options);

// The schema version of an output or record: its "schema_version", 1 where it has none, nullopt
// where it is not a positive integer.
std::optional<int> OutputSchemaVersion(const nlohmann::json& output);

// Success when `record` is of kOutputSchemaVersion; else what it is (kBatchRecord: "schema version 1
// (an older vs11's)", "schema version 3 (a newer vs11's)", "a schema_version that is not a positive
// integer").
Status OtherSchemaVersion(const nlohmann::json& record);

}  // namespace vs11::irradiance
