#include "vm/mesh/mesh_wire.h"

#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

#include <fmt/format.h>

namespace vs11::mesh {
namespace {

// Layout (version 1), every count a u64:
//   "vs11mesh" u32 version, vertex_count, u32 attribute mask, u8 texcoord_components[8],
//   the positions and then each attribute of the mask in mask-bit order (vertex_count x 4 floats),
//   nonfinite_vertex_count, index count + u32 indices, bone count + bones (name, 16 doubles),
//   part count + parts (mesh_name, node_name, 16 doubles, u8 transformed, u8 skinned,
//   first_vertex, vertex_count, first_index, index_count), warning count + strings.
// A string is its byte count and its bytes.
constexpr std::string_view kMagic = "vs11mesh";
constexpr std::uint32_t kVersion = 1;

// How many DiagnosticCodes there are: an error record's code must be one of them.
#define VS11_COUNT_DIAGNOSTIC_CODE(code, name) +1
constexpr std::uint32_t kDiagnosticCodeCount = 0 VS11_DIAGNOSTIC_CODES(VS11_COUNT_DIAGNOSTIC_CODE);
#undef VS11_COUNT_DIAGNOSTIC_CODE

// The optional per-vertex arrays in mask-bit order.
template <typename MeshType>
auto OptionalArrays(MeshType& mesh) {
  std::vector<decltype(&mesh.normals)> arrays = {&mesh.normals, &mesh.tangents, &mesh.binormals};
  for (auto& set : mesh.texcoords) arrays.push_back(&set);
  for (auto& set : mesh.colors) arrays.push_back(&set);
  arrays.push_back(&mesh.blend_weights);
  arrays.push_back(&mesh.blend_indices);
  return arrays;
}

class Writer {
 public:
  template <typename T>
  void Value(const T& value) {
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void Count(std::size_t count) { Value(static_cast<std::uint64_t>(count)); }
  void String(const std::string& text) {
    const std::size_t length = std::min(text.size(), kMaxWireStringBytes);
    Count(length);
    out_.append(text, 0, length);
  }
  void Matrix(const Matrix4d& m) {
    for (const auto& row : m) out_.append(reinterpret_cast<const char*>(row.data()), sizeof row);
  }
  void Rows(const std::vector<Vec4f>& rows) {
    out_.append(reinterpret_cast<const char*>(rows.data()), rows.size() * sizeof(Vec4f));
  }
  std::string Take() { return std::move(out_); }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

// Reads from untrusted bytes: every read checks what is left, and a count is refused before
// anything is allocated for it when it exceeds its limit or the bytes that could hold it.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  bool Take(void* out, std::size_t size) {
    if (failed() || size > bytes_.size() - at_) return Fail("the data ends early");
    if (size == 0) return true;  // out may be a null data() of an empty vector
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
    return true;
  }
  template <typename T>
  T Value() {
    T value{};
    Take(&value, sizeof value);
    return value;
  }
  // A count of items each at least `min_item_bytes` long, at most `limit`.
  std::size_t Count(const char* what, std::uint64_t limit, std::size_t min_item_bytes) {
    const auto count = Value<std::uint64_t>();
    if (failed()) return 0;
    if (count > limit) {
      Fail(fmt::format("{} {}, over the limit of {}", count, what, limit));
    } else if (min_item_bytes > 0 && count > (bytes_.size() - at_) / min_item_bytes) {
      Fail(fmt::format("{} {} do not fit in the bytes left", count, what));
    }
    return failed() ? 0 : static_cast<std::size_t>(count);
  }
  std::string String() {
    const std::size_t length = Count("string bytes", kMaxWireStringBytes, 1);
    std::string text(length, '\0');
    Take(text.data(), length);
    return text;
  }
  Matrix4d Matrix() {
    Matrix4d m{};
    for (auto& row : m) Take(row.data(), sizeof row);
    return m;
  }
  void Rows(std::vector<Vec4f>& rows, std::size_t count) {
    if (failed() || count > (bytes_.size() - at_) / sizeof(Vec4f)) {
      Fail("the data ends early");
      return;
    }
    rows.resize(count);
    Take(rows.data(), count * sizeof(Vec4f));
  }
  bool Fail(std::string message) {
    if (error_.empty()) error_ = std::move(message);
    return false;
  }
  bool failed() const { return !error_.empty(); }
  bool at_end() const { return at_ == bytes_.size(); }
  const std::string& error() const { return error_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  std::string error_;
};

constexpr std::size_t kBoneBytes = sizeof(std::uint64_t) + sizeof(Matrix4d);
constexpr std::size_t kPartBytes = 2 * sizeof(std::uint64_t) + sizeof(Matrix4d) + 2 + 4 * sizeof(std::uint64_t);

// What a loaded Mesh promises its users beyond the sizes the reader already checked (kMeshWire).
Status CheckInvariants(const Mesh& mesh) {
  const auto broken = [](std::string what) { return Failure(DiagnosticCode::kMeshWire, std::move(what)); };
  if (mesh.vertex_count == 0) return broken("a mesh without vertices");
  if (mesh.nonfinite_vertex_count > mesh.vertex_count) return broken("more non-finite vertices than vertices");
  if (mesh.tangents.empty() != mesh.binormals.empty()) return broken("tangents without binormals or the reverse");
  if (mesh.blend_weights.empty() != mesh.blend_indices.empty()) {
    return broken("blend weights without indices or the reverse");
  }
  for (int component : mesh.texcoord_components) {
    if (component < 0 || component > 3) return broken(fmt::format("a UV set of {} components", component));
  }
  if (mesh.indices.size() % 3 != 0) return broken("an index count that is not a multiple of 3");
  for (std::uint32_t index : mesh.indices) {
    if (index >= mesh.vertex_count) {
      return broken(fmt::format("index {} past the {} vertices", index, mesh.vertex_count));
    }
  }
  for (const Vec4f& row : mesh.blend_indices) {
    for (float index : row) {
      const bool names_bone = index >= 0.0f && index == std::floor(index) &&
                              (static_cast<double>(index) < static_cast<double>(mesh.bones.size()) || index == 0.0f);
      if (!names_bone) {
        return broken(fmt::format("blend index {} names none of the {} bones", index, mesh.bones.size()));
      }
    }
  }
  for (const MeshPart& part : mesh.parts) {
    if (part.first_vertex > mesh.vertex_count || part.vertex_count > mesh.vertex_count - part.first_vertex ||
        part.first_index > mesh.indices.size() || part.index_count > mesh.indices.size() - part.first_index ||
        part.index_count % 3 != 0) {
      return broken(fmt::format("part '{}' lies outside the mesh's arrays", part.mesh_name));
    }
  }
  return {};
}

}  // namespace

std::string EncodeMesh(const Mesh& mesh) {
  Writer out;
  out.bytes().reserve(64 + mesh.vertex_count * sizeof(Vec4f) * 4 + mesh.indices.size() * 4);
  out.bytes().append(kMagic);
  out.Value(kVersion);
  out.Count(mesh.vertex_count);
  std::uint32_t mask = 0;
  const auto arrays = OptionalArrays(mesh);
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    if (!arrays[i]->empty()) mask |= std::uint32_t{1} << i;
  }
  out.Value(mask);
  for (int components : mesh.texcoord_components) out.Value(static_cast<std::uint8_t>(components));
  out.Rows(mesh.positions);
  for (const std::vector<Vec4f>* array : arrays) out.Rows(*array);
  out.Count(mesh.nonfinite_vertex_count);
  out.Count(mesh.indices.size());
  out.bytes().append(reinterpret_cast<const char*>(mesh.indices.data()), mesh.indices.size() * sizeof(std::uint32_t));
  out.Count(mesh.bones.size());
  for (const Bone& bone : mesh.bones) {
    out.String(bone.name);
    out.Matrix(bone.skin);
  }
  out.Count(mesh.parts.size());
  for (const MeshPart& part : mesh.parts) {
    out.String(part.mesh_name);
    out.String(part.node_name);
    out.Matrix(part.transform);
    out.Value(static_cast<std::uint8_t>(part.transformed));
    out.Value(static_cast<std::uint8_t>(part.skinned));
    for (std::size_t n : {part.first_vertex, part.vertex_count, part.first_index, part.index_count}) out.Count(n);
  }
  out.Count(mesh.warnings.size());
  for (const std::string& warning : mesh.warnings) out.String(warning);
  return out.Take();
}

Result<Mesh> DecodeMesh(std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  char magic[kMagic.size()] = {};
  in.Take(magic, sizeof magic);
  if (!in.failed() && std::string_view(magic, sizeof magic) != kMagic) in.Fail("not a vs11 mesh");
  if (const auto version = in.Value<std::uint32_t>(); !in.failed() && version != kVersion) {
    in.Fail(fmt::format("version {}, not {}", version, kVersion));
  }
  Mesh mesh;
  mesh.vertex_count = in.Count("vertices", kMaxMeshVertices, sizeof(Vec4f));
  const auto mask = in.Value<std::uint32_t>();
  for (int& components : mesh.texcoord_components) components = in.Value<std::uint8_t>();
  in.Rows(mesh.positions, mesh.vertex_count);
  const auto arrays = OptionalArrays(mesh);
  if (!in.failed() && (mask >> arrays.size()) != 0) in.Fail("unknown attributes");
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    if ((mask >> i) & 1) in.Rows(*arrays[i], mesh.vertex_count);
  }
  mesh.nonfinite_vertex_count = in.Count("non-finite vertices", kMaxMeshVertices, 0);
  mesh.indices.resize(in.Count("indices", 3 * kMaxMeshTriangles, sizeof(std::uint32_t)));
  in.Take(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  mesh.bones.resize(in.Count("bones", kMaxMeshVertices, kBoneBytes));
  for (Bone& bone : mesh.bones) {
    bone.name = in.String();
    bone.skin = in.Matrix();
  }
  mesh.parts.resize(in.Count("parts", kMaxMeshVertices, kPartBytes));
  for (MeshPart& part : mesh.parts) {
    part.mesh_name = in.String();
    part.node_name = in.String();
    part.transform = in.Matrix();
    part.transformed = in.Value<std::uint8_t>() != 0;
    part.skinned = in.Value<std::uint8_t>() != 0;
    for (std::size_t* n : {&part.first_vertex, &part.vertex_count, &part.first_index, &part.index_count}) {
      *n = in.Count("part elements", 3 * kMaxMeshTriangles, 0);
    }
  }
  mesh.warnings.resize(in.Count("warnings", kMaxMeshVertices, sizeof(std::uint64_t)));
  for (std::string& warning : mesh.warnings) warning = in.String();
  if (!in.failed() && !in.at_end()) in.Fail("bytes after the mesh");
  if (in.failed()) return Failure(DiagnosticCode::kMeshWire, in.error());
  if (Status invariants = CheckInvariants(mesh); !invariants.ok()) return invariants.error();
  return mesh;
}

std::string EncodeReplyRecord(const Result<Mesh>& result) {
  std::string body;
  if (result.ok()) {
    body = EncodeMesh(*result);
  } else {
    Writer error;
    error.Value(static_cast<std::uint32_t>(result.error().code));
    body = error.Take() + result.error().message.substr(0, kMaxWireStringBytes);
  }
  Writer out;
  out.Value(result.ok() ? 'M' : 'E');
  out.Count(body.size());
  out.bytes() += body;
  return out.Take();
}

ChildReply DecodeChildReply(std::span<const std::uint8_t> bytes) {
  ChildReply reply;
  std::size_t at = 0;
  for (; at < bytes.size() && (bytes[at] == 'A' || bytes[at] == 'V'); ++at) reply.last_stage = static_cast<char>(bytes[at]);
  constexpr std::size_t kHeader = 1 + sizeof(std::uint64_t);
  if (bytes.size() - at < kHeader) return reply;
  const char tag = static_cast<char>(bytes[at]);
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + at + 1, sizeof length);
  const std::span<const std::uint8_t> body = bytes.subspan(at + kHeader);
  auto malformed = [&](std::string message) {
    reply.complete = true;
    reply.malformed = true;
    reply.result = Failure(DiagnosticCode::kMeshWire, std::move(message));
    return reply;
  };
  if (tag != 'M' && tag != 'E') return malformed(fmt::format("an unknown record {:#04x}", static_cast<unsigned>(bytes[at])));
  if (length > kMaxReplyBytes) return malformed(fmt::format("a reply of {} bytes, over the limit of {}", length, kMaxReplyBytes));
  if (body.size() < length) return reply;
  if (body.size() > length) return malformed("bytes after the reply");
  reply.complete = true;
  if (tag == 'E') {
    std::uint32_t code = 0;
    if (length < sizeof code) return malformed("an error without its code");
    if (length > sizeof code + kMaxWireStringBytes) return malformed("an error message over the length limit");
    std::memcpy(&code, body.data(), sizeof code);
    if (code >= kDiagnosticCodeCount) return malformed(fmt::format("an unknown error code {}", code));
    std::string message(reinterpret_cast<const char*>(body.data()) + sizeof code, body.size() - sizeof code);
    if (message.empty()) return malformed("an empty error message");
    reply.result = Failure(static_cast<DiagnosticCode>(code), std::move(message));
    return reply;
  }
  Result<Mesh> mesh = DecodeMesh(body);
  if (!mesh) return malformed("an unreadable mesh: " + mesh.message());
  reply.result = std::move(mesh);
  return reply;
}

}  // namespace vs11::mesh
