// The byte form in which the sandboxed mesh loader's child process (mesh_sandbox.cc) hands a
// vs11::mesh::Mesh to its parent. Both ends are the same binary on the same machine, so numbers
// are in native byte order; the parent still treats the bytes as untrusted (a child whose memory a
// corrupt file has damaged may send anything), so DecodeMesh checks every count against the
// loader's limits and against the bytes left before it allocates, and every invariant a loaded Mesh
// promises (indices name vertices, parts lie inside the arrays, blend indices name bones, ...).
// tests/fuzz/fuzz_mesh_wire feeds it arbitrary bytes.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "vm/core/result.h"
#include "vm/mesh/mesh_io.h"

namespace vs11::mesh {

// Strings (names, warnings) longer than this are cut by EncodeMesh and refused by DecodeMesh.
inline constexpr std::size_t kMaxWireStringBytes = 4096;

std::string EncodeMesh(const Mesh& mesh);

// The mesh, or an error (kMeshWire) saying what is wrong with the bytes.
Result<Mesh> DecodeMesh(std::span<const std::uint8_t> bytes);

// The sandboxed child's whole output: stage bytes (mesh_sandbox.h's LoadStage), then one record,
// 'M' u64 length + EncodeMesh's bytes or 'E' u64 length + the error's u32 DiagnosticCode and message.
std::string EncodeReplyRecord(const Result<Mesh>& result);

// The largest reply the parent reads: the encoded size of a mesh at the loader's limits, with every
// attribute, plus 1 GiB for names and warnings. A longer reply is refused as it arrives.
inline constexpr std::uint64_t kMaxReplyBytes =
    std::uint64_t{kMaxMeshVertices} * 23 * sizeof(Vec4f) + std::uint64_t{kMaxMeshTriangles} * 12 + (std::uint64_t{1} << 30);

struct ChildReply {
  char last_stage = 0;    // the last stage byte (0: none arrived)
  bool complete = false;  // a whole record arrived; then `result` holds it
  // The mesh, the child's error, or (when `malformed`, code kMeshWire) what is wrong with the bytes.
  Result<Mesh> result = Failure(DiagnosticCode::kMeshWire, "no whole record arrived");
  bool malformed = false;
};
ChildReply DecodeChildReply(std::span<const std::uint8_t> bytes);

}  // namespace vs11::mesh
