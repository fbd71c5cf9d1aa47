// Runs a mesh load in a child process, so that a crash or a hang in Assimp's readers (which corrupt
// files cause: a SEGV in the compressed DirectX .x and in the Collada reader, an endless loop in
// the Collada reader, found by tests/fuzz/fuzz_mesh) becomes a clear error instead of taking the
// tool down. The child (fork, no exec: it inherits the file name or the bytes) parses with Assimp,
// converts the scene to a Mesh, sends it over a pipe in mesh_wire.h's form and _exits; the parent
// reads the pipe while the child writes, stops the child at the time limit, checks the bytes
// (DecodeMesh) and names a fatal signal: "Assimp crashed reading FILE (SIGSEGV); ...".
//
// The child reports which code it is running (Assimp's or vs11's own checks and conversion), so that
// a death in vs11's code is told apart and reported as vs11's bug (DiagnosticCode::kMeshConverterCrashed).
//
// The child of a threaded process holds only the forking thread: it calls nothing but the loader
// (Assimp makes no threads of its own in 5.2, and glibc's malloc and ASan's allocator stay usable
// after fork), resets every signal handler (the tool's, and libFuzzer's in the fuzz target) and,
// under a sanitizer, the death callback (libFuzzer's saves the fuzzed input as a crash-* file), sends
// its stdout to /dev/null (the tools' JSON output stays clean; Assimp's logger writes nowhere) and
// keeps stderr (a sanitizer report in the child reaches the user), closes every other descriptor,
// and dumps no core. It runs under an address-space limit (MeshLoadOptions::memory_limit_bytes),
// except under AddressSanitizer, whose shadow memory alone exceeds any such limit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>

#include "vm/mesh/mesh_io.h"

namespace vs11::mesh::internal {

// The bytes the child writes before each stage of the load, then one reply record (mesh_wire.h).
enum class LoadStage : char { kAssimp = 'A', kVs11 = 'V' };
using StageReporter = std::function<void(LoadStage)>;

// Runs `load` in a child process as described above. `name` names the input in errors;
// `input_bytes` (the file's size) scales the default time and memory limits.
Result<Mesh> RunSandboxed(const std::string& name, std::uintmax_t input_bytes, const MeshLoadOptions& options,
                          const std::function<Result<Mesh>(const StageReporter&)>& load);

// The loads themselves, in this process: the sandbox's child runs them, reporting each stage; the
// fuzz target reruns one that crashed in vs11's code to get its stack under ASan.
Result<Mesh> LoadMeshInProcess(const std::filesystem::path& path, const MeshLoadOptions& options,
                               const StageReporter& report);
Result<Mesh> LoadMeshFromMemoryInProcess(std::span<const std::uint8_t> bytes, const std::string& format_hint,
                                         const MeshLoadOptions& options, const StageReporter& report);

// The limits RunSandboxed applies for these options and this input size.
double TimeLimitSeconds(const MeshLoadOptions& options, std::uintmax_t input_bytes);
std::uintmax_t MemoryLimitBytes(const MeshLoadOptions& options, std::uintmax_t input_bytes);

}  // namespace vs11::mesh::internal
