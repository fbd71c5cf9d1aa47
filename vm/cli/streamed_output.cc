#include "vm/cli/streamed_output.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "vm/cli/cli_support.h"
#include "vm/core/atomic_file.h"

namespace vs11::cli {
namespace {

namespace fs = std::filesystem;

// Vertices formatted per piece handed to a sink: 4096 x at most 23 columns x 16 bytes <= 1.5 MB.
constexpr std::size_t kVerticesPerPiece = 4096;

// Streams one file into a fresh temporary beside its target. On failure removes the temporary and
// returns the message; an exception from `produce` removes it and passes on.
Status WriteTemporary(const StreamedFile& file, fs::path& temporary) {
  temporary = TemporaryPathBeside(file.path);
  std::FILE* stream = std::fopen(temporary.c_str(), "wb");
  if (stream == nullptr) {
    const fs::path folder = file.path.parent_path().empty() ? fs::path(".") : file.path.parent_path();
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{}: cannot create a file in {}", file.path.string(), folder.string()));
  }
  bool written = true;
  try {
    file.produce([&](std::string_view bytes) {
      written = written && std::fwrite(bytes.data(), 1, bytes.size(), stream) == bytes.size();
    });
  } catch (...) {
    std::fclose(stream);
    RemoveQuietly(temporary);
    throw;
  }
  written = std::fclose(stream) == 0 && written;
  if (!written) {
    RemoveQuietly(temporary);
    return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: write failed", file.path.string()));
  }
  return {};
}

}  // namespace

Status WriteStreamedFilesAtomically(std::span<const StreamedFile> files) {
  std::vector<PendingRename> renames;
  auto remove_written = [&] {
    for (const PendingRename& rename : renames) RemoveQuietly(rename.temporary);
  };
  for (const StreamedFile& file : files) {
    fs::path temporary;
    Status written;
    try {
      written = WriteTemporary(file, temporary);
    } catch (...) {
      remove_written();
      throw;
    }
    if (!written) {
      remove_written();
      return written;
    }
    renames.push_back({temporary, file.path});
  }
  return CommitRenames(renames);
}

Status WriteStreamedAtomically(const fs::path& path, const std::function<void(const ByteSink&)>& produce) {
  const StreamedFile file[] = {{path, produce}};
  return WriteStreamedFilesAtomically(file);
}

ByteSink StdoutSink() {
  return [](std::string_view bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size()) Fail("cannot write to standard output");
  };
}

void StreamInterleaved(const VertexArrays& outputs, const std::vector<InterleavedColumn>& columns, const ByteSink& sink) {
  std::size_t stride = 0;
  for (const InterleavedColumn& column : columns) stride += sizeof(float) * static_cast<std::size_t>(column.components);
  std::string piece;
  for (std::size_t first = 0; first < outputs.count(); first += kVerticesPerPiece) {
    const std::size_t count = std::min(kVerticesPerPiece, outputs.count() - first);
    piece.resize(count * stride);
    char* out = piece.data();
    for (std::size_t v = first; v < first + count; ++v) {
      for (const InterleavedColumn& column : columns) {
        for (int lane = 0; lane < column.components; ++lane) {
          std::memcpy(out, outputs.lane(column.slot, lane) + v, sizeof(float));
          out += sizeof(float);
        }
      }
    }
    sink(piece);
  }
}

}  // namespace vs11::cli
