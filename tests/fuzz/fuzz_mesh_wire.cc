// libFuzzer target: arbitrary bytes as the sandboxed mesh loader's reply (mesh_wire.h's
// DecodeChildReply): the parent's parser of what its child sends, untrusted because a corrupt file
// may have damaged the child. A decoded mesh must keep the promises DecodeMesh checks.
#include <cstddef>
#include <cstdint>

#include "vm/mesh/mesh_wire.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vs11::mesh::ChildReply reply = vs11::mesh::DecodeChildReply({data, size});
  if (!reply.complete) return 0;
  if (!reply.result.ok()) {
    if (reply.result.message().empty()) __builtin_trap();
    return 0;
  }
  const vs11::mesh::Mesh& mesh = *reply.result;
  if (mesh.positions.size() != mesh.vertex_count) __builtin_trap();
  for (std::uint32_t index : mesh.indices) {
    if (index >= mesh.vertex_count) __builtin_trap();
  }
  for (const vs11::mesh::MeshPart& part : mesh.parts) {
    if (part.first_vertex + part.vertex_count > mesh.vertex_count) __builtin_trap();
  }
  // Encoding the decoded mesh gives the same record back.
  const std::string record = vs11::mesh::EncodeReplyRecord(reply.result);
  if (!vs11::mesh::DecodeMesh({reinterpret_cast<const std::uint8_t*>(record.data()) + 9, record.size() - 9}).ok()) {
    __builtin_trap();
  }
  return 0;
}
