// Reading a file named on a command line, once: a regular file, a pipe given by path (`cat x | vs11
// validate /dev/stdin`, process substitution `<(...)`) or "-" for standard input. Every read has a
// limit, so an endless stream fails with a message instead of filling memory, and devices such as
// /dev/zero, folders and sockets are refused before anything is read. And the check that an output
// is not one of the inputs, so that no command overwrites what it reads.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "vm/core/result.h"

namespace vs11 {

// The name that reads standard input wherever a tool reads a file.
inline constexpr std::string_view kStandardInputName = "-";

// Limits per kind of file, each far above any real one; what is larger is refused, not read.
// A .vsh (with its #includes) or .vso: a vs_1_1 program has at most 128 instruction slots and 2048
// constant registers; the programs in programs/ are under 10 KB, so 16 MiB is generous and still
// small enough to preprocess in well under a second.
inline constexpr std::size_t kMaxProgramFileBytes = std::size_t{16} << 20;
// A constants file (`def c#, x, y, z, w` lines): at most 2048 registers, a line each, and comments.
inline constexpr std::size_t kMaxConstantsFileBytes = std::size_t{16} << 20;
// A vertex CSV: about 16 million vertices of four full-precision floats. Larger vertex data belongs
// in --npy or --buffer, which are not parsed as text.
inline constexpr std::size_t kMaxVertexCsvBytes = std::size_t{1} << 30;
// Anything else read whole (.npy arrays, raw buffers, JSON): what a 64-bit run can hold comfortably.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{4} << 30;

// "<stdin>" for "-", else the path as given: the name messages use.
std::string InputDisplayName(const std::filesystem::path& path);

// Why `path` cannot be an input file (kCannotReadFile), or success when it can: "no such file", "is a
// folder", "is a device, not a file" (a character or block device), "is a socket". Pipes are
// accepted only with `pipes_allowed`, for readers that need to seek (images) they are "not a regular
// file".
Status InputFileProblem(const std::filesystem::path& path, bool pipes_allowed);

// Reads all of `path` ("-": standard input) with one open, at most `max_bytes` of it: the whole
// file, read once, or why not (kCannotReadFile, the message without the name). A larger file or a
// longer stream is an error that names the limit. Devices, folders and sockets are refused.
Result<std::string> ReadInputFile(const std::filesystem::path& path, std::size_t max_bytes);

// The first of `inputs` that is the same file as `output` (same device and inode: through links,
// "./" and any other spelling), as "OUTPUT is the input INPUT: refusing to overwrite it"
// (kOutputOverwritesInput); success when none is. An output that does not exist yet is no input,
// and "-" is no file.
Status OutputOverwritesInput(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs);

}  // namespace vs11
