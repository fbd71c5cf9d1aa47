// libFuzzer target: arbitrary bytes as a mesh file through mesh::LoadMeshFromMemory, end to end:
// the header checks here, Assimp's ReadFileFromMemory (no format hint, so every importer whose
// signature check accepts the bytes gets them) and vs11's conversion in the sandbox's child process,
// and the decoding of its reply here. Normals and tangents are generated on some inputs so that
// those post-processing steps run too.
// Assimp crashing or hanging in the child is an error result, as for users (Assimp is a system
// library built without sanitizers; its crashes on corrupt files are not ours to fix). A child that
// dies in vs11's own code is a bug: the input is loaded again in this process, where ASan shows the
// stack, and the target traps if that does not crash.
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "vm/mesh/mesh_io.h"
#include "vm/mesh/mesh_sandbox.h"

// Assimp asks for tens of gigabytes on some corrupt files. libFuzzer's -malloc_limit_mb hook
// (.ci/sanitize: 4096) is inherited by the sandbox's forked child, and there it wrote the child's
// input as an oom-* file, as if vs11 had failed (15 in a 10-minute run). Below that limit ASan's own
// allocator refuses the request first: in the child that is a death like any other Assimp crash
// (its death callback is cleared, vm/mesh/mesh_sandbox.cc), so the load is an error result and no
// file is written; in this process it is still an ASan report that fails the run. ASAN_OPTIONS
// given at run time override this default.
extern "C" const char* __asan_default_options() { return "max_allocation_size_mb=4000"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vs11::mesh::MeshLoadOptions options;
  options.compute_normals = (size & 1) != 0;
  options.compute_tangents = (size & 2) != 0;
  options.repair_normals = (size & 4) != 0;  // irrmap --mesh sets it
  // Well inside .ci/sanitize's -timeout=60, so that a hang in Assimp ends as an error result.
  options.timeout_seconds = 10;
  vs11::Result<vs11::mesh::Mesh> result = vs11::mesh::LoadMeshFromMemory({data, size}, "", options);
  if (!result.ok() && result.error().code == vs11::DiagnosticCode::kMeshConverterCrashed) {
    std::fprintf(stderr, "fuzz_mesh: %s\nfuzz_mesh: loading it again in this process\n", result.message().c_str());
    // Only for the crash's stack under ASan: the result, should it come back, is not wanted.
    static_cast<void>(vs11::mesh::internal::LoadMeshFromMemoryInProcess({data, size}, "", options,
                                                                        [](vs11::mesh::internal::LoadStage) {}));
    __builtin_trap();
  }
  if (result.ok()) {
    // Every index must name a vertex of the joined arrays.
    for (std::uint32_t index : result->indices) {
      if (index >= result->vertex_count) __builtin_trap();
    }
  } else if (result.message().empty()) {
    __builtin_trap();
  }
  return 0;
}
