// vs11 run's outputs written as they are formatted, a piece at a time, so that memory does not grow
// with the file (30M vertices of CSV are 1.5 GB of text), and still atomically: into a temporary
// beside the target (vm/core/atomic_file.h), renamed over it only once every byte is written.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11::cli {

// Receives the next piece of a file.
using ByteSink = std::function<void(std::string_view)>;

// One file of a set written together: `produce` hands its bytes, in pieces, to the sink it is given.
struct StreamedFile {
  std::filesystem::path path;
  std::function<void(const ByteSink&)> produce;
};

// Writes several files, all or none: each is streamed into its temporary, and only when every one is
// written are they renamed into place (CommitRenames in vm/core/atomic_file.h). On a failed write no
// target is touched and no temporary is left: returns the error (kCannotWriteFile). An exception
// from a `produce` removes the temporaries and passes on.
Status WriteStreamedFilesAtomically(std::span<const StreamedFile> files);

// Runs `produce` with a sink into a temporary beside `path`, then renames it over `path`. On a
// failed write nothing is left and `path` is untouched: returns the error. An exception from
// `produce` (std::bad_alloc) removes the temporary and passes on.
Status WriteStreamedAtomically(const std::filesystem::path& path, const std::function<void(const ByteSink&)>& produce);

// A sink that writes to stdout; a failed write ends the command (error, exit 1).
ByteSink StdoutSink();

// An output register as raw float32 columns: its first `components` lanes.
struct InterleavedColumn {
  int slot;
  int components;
};

// Vertex after vertex, each column's `components` floats (stride: 4 x their sum), handed to `sink`
// a few hundred KB at a time.
void StreamInterleaved(const VertexArrays& outputs, const std::vector<InterleavedColumn>& columns, const ByteSink& sink);

}  // namespace vs11::cli
