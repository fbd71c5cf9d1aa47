#include "vm/mesh/mesh_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <map>
#include <mutex>
#include <system_error>
#include <utility>

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "vm/core/input_file.h"
#include "vm/mesh/mesh_sandbox.h"
#include "vm/mesh/smooth_normals.h"

namespace vs11::mesh {
namespace {

Matrix4d FromAssimp(const aiMatrix4x4& m) {
  return {{{m.a1, m.a2, m.a3, m.a4}, {m.b1, m.b2, m.b3, m.b4}, {m.c1, m.c2, m.c3, m.c4}, {m.d1, m.d2, m.d3, m.d4}}};
}

Matrix4d Multiply(const Matrix4d& a, const Matrix4d& b) {
  Matrix4d result{};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += a[r][k] * b[k][c];
      result[r][c] = sum;
    }
  }
  return result;
}

Matrix4d GlobalTransform(const aiNode* node) {
  Matrix4d global = IdentityMatrix();
  for (; node != nullptr; node = node->mParent) global = Multiply(FromAssimp(node->mTransformation), global);
  return global;
}

// How a part's directions move: positions by M, tangents by M3, normals by the cofactor matrix of
// M3 (the inverse transpose times det M3, sign-corrected so that mirroring keeps normals outward).
struct PartTransform {
  Matrix4d m;
  std::array<std::array<double, 3>, 3> normal;

  explicit PartTransform(const Matrix4d& matrix) : m(matrix) {
    auto a = [&](int r, int c) { return m[r][c]; };
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        normal[r][c] = a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1);
      }
    }
    const double det = a(0, 0) * normal[0][0] + a(0, 1) * normal[0][1] + a(0, 2) * normal[0][2];
    if (det < 0) {
      for (auto& row : normal) {
        for (double& v : row) v = -v;
      }
    }
  }
  Vec4f Point(const aiVector3D& p) const {
    Vec4f out{};
    for (int r = 0; r < 3; ++r) out[r] = static_cast<float>(m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3]);
    out[3] = 1.0f;
    return out;
  }
  static Vec4f Normalized(const std::array<double, 3>& v) {
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double scale = length > 0.0 ? 1.0 / length : 1.0;  // a zero vector stays zero
    return {static_cast<float>(v[0] * scale), static_cast<float>(v[1] * scale), static_cast<float>(v[2] * scale), 1.0f};
  }
  Vec4f Direction(const aiVector3D& d) const {
    std::array<double, 3> out{};
    for (int r = 0; r < 3; ++r) out[r] = m[r][0] * d.x + m[r][1] * d.y + m[r][2] * d.z;
    return Normalized(out);
  }
  Vec4f Normal(const aiVector3D& n) const { return Normal(Vec3d{n.x, n.y, n.z}); }
  Vec4f Normal(const Vec3d& n) const {
    std::array<double, 3> out{};
    for (int r = 0; r < 3; ++r) out[r] = normal[r][0] * n[0] + normal[r][1] * n[1] + normal[r][2] * n[2];
    return Normalized(out);
  }
};

Vec4f Untransformed(const aiVector3D& v) { return {v.x, v.y, v.z, 1.0f}; }
Vec4f Untransformed(const Vec3d& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), 1.0f};
}
Vec3f ToVec3f(const aiVector3D& v) { return {v.x, v.y, v.z}; }

bool HasTriangles(const aiMesh& m) {
  for (unsigned f = 0; m.mFaces != nullptr && f < m.mNumFaces; ++f) {
    if (m.mFaces[f].mNumIndices == 3 && m.mFaces[f].mIndices != nullptr) return true;
  }
  return false;
}

struct PlacedMesh {
  const aiMesh* mesh;
  const aiNode* node;
};

// Depth first, children in order; an explicit stack so that deep hostile hierarchies cannot
// exhaust the call stack.
std::vector<PlacedMesh> PlaceMeshes(const aiScene& scene) {
  std::vector<PlacedMesh> placed;
  std::vector<bool> referenced(scene.mNumMeshes, false);
  std::vector<const aiNode*> stack;
  if (scene.mMeshes == nullptr) return placed;
  if (scene.mRootNode != nullptr) stack.push_back(scene.mRootNode);
  while (!stack.empty()) {
    const aiNode* node = stack.back();
    stack.pop_back();
    for (unsigned i = 0; node->mMeshes != nullptr && i < node->mNumMeshes; ++i) {
      const unsigned index = node->mMeshes[i];
      if (index >= scene.mNumMeshes || scene.mMeshes[index] == nullptr || scene.mMeshes[index]->mVertices == nullptr) {
        continue;
      }
      placed.push_back({scene.mMeshes[index], node});
      referenced[index] = true;
    }
    for (unsigned i = node->mChildren != nullptr ? node->mNumChildren : 0; i-- > 0;) {
      if (node->mChildren[i] != nullptr) stack.push_back(node->mChildren[i]);
    }
  }
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    if (!referenced[i] && scene.mMeshes[i] != nullptr && scene.mMeshes[i]->mVertices != nullptr) placed.push_back({scene.mMeshes[i], nullptr});
  }
  return placed;
}

// What is wrong with a file vs11 or Assimp cannot read as a mesh.
Diagnostic Unreadable(std::string message) { return Failure(DiagnosticCode::kCannotReadFile, std::move(message)); }

// `error` with the input's name in front.
Diagnostic Named(const std::string& name, const Diagnostic& error) {
  return Failure(error.code, fmt::format("{}: {}", name, error.message));
}

bool IsFinite(const Vec4f& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

class MeshBuilder {
 public:
  MeshBuilder(const aiScene& scene, const MeshLoadOptions& options) : scene_(scene), options_(options) {}

  Result<Mesh> Build() {
    const std::vector<PlacedMesh> placed = PlaceMeshes(scene_);
    std::size_t vertices = 0, triangles = 0;
    for (const PlacedMesh& p : placed) {
      vertices += p.mesh->mNumVertices;
      triangles += p.mesh->mNumFaces;  // an upper bound: points and lines add none
      if (vertices > kMaxMeshVertices || triangles > kMaxMeshTriangles) {
        return Unreadable(fmt::format("more than {} vertices or {} triangles (the limit)", kMaxMeshVertices,
                                 kMaxMeshTriangles));
      }
    }
    if (vertices == 0) return Unreadable("the scene holds no mesh with vertices");
    mesh_.vertex_count = vertices;
    Allocate(placed);
    for (const PlacedMesh& p : placed) {
      if (Status added = AddPart(p); !added) return added.error();
    }
    CountNonFinite();
    return std::move(mesh_);
  }

 private:
  void Allocate(const std::vector<PlacedMesh>& placed) {
    const std::size_t n = mesh_.vertex_count;
    auto any = [&](auto has) { return std::any_of(placed.begin(), placed.end(), [&](const PlacedMesh& p) { return has(*p.mesh); }); };
    mesh_.positions.assign(n, kDefaultInput);
    const bool computes = options_.compute_normals || options_.repair_normals;
    if (any([&](const aiMesh& m) { return m.HasNormals() || (computes && HasTriangles(m)); })) {
      mesh_.normals.assign(n, kDefaultInput);
    }
    if (any([](const aiMesh& m) { return m.HasTangentsAndBitangents(); })) {
      mesh_.tangents.assign(n, kDefaultInput);
      mesh_.binormals.assign(n, kDefaultInput);
    }
    for (int set = 0; set < kMaxTexCoordSets; ++set) {
      if (any([&](const aiMesh& m) { return m.HasTextureCoords(set); })) mesh_.texcoords[set].assign(n, kDefaultInput);
    }
    for (int set = 0; set < kMaxColorSets; ++set) {
      if (any([&](const aiMesh& m) { return m.HasVertexColors(set); })) mesh_.colors[set].assign(n, kDefaultInput);
    }
    if (any([](const aiMesh& m) { return m.HasBones(); })) {
      mesh_.blend_weights.assign(n, Vec4f{});
      mesh_.blend_indices.assign(n, Vec4f{});
    }
  }

  Status AddPart(const PlacedMesh& placed) {
    const aiMesh& m = *placed.mesh;
    MeshPart part;
    part.mesh_name = m.mName.C_Str();
    part.node_name = placed.node != nullptr ? placed.node->mName.C_Str() : "";
    part.transform = placed.node != nullptr ? GlobalTransform(placed.node) : IdentityMatrix();
    part.skinned = m.HasBones();
    part.transformed = options_.transform_to_world && !part.skinned;
    part.first_vertex = next_vertex_;
    part.vertex_count = m.mNumVertices;
    part.first_index = mesh_.indices.size();
    std::vector<std::uint32_t> triangles;
    if (Status read = PartTriangles(m, part.mesh_name, triangles); !read) return read;
    const PartTransform transform(part.transformed ? part.transform : IdentityMatrix());
    const std::size_t base = next_vertex_;
    std::vector<Vec4f> normals = PartNormals(m, triangles, transform, part.transformed);
    if (!normals.empty()) std::copy(normals.begin(), normals.end(), mesh_.normals.begin() + static_cast<std::ptrdiff_t>(base));
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      Vec4f& position = mesh_.positions[base + v];
      position = part.transformed ? transform.Point(m.mVertices[v]) : Untransformed(m.mVertices[v]);
      if (m.HasTangentsAndBitangents()) {
        mesh_.tangents[base + v] = part.transformed ? transform.Direction(m.mTangents[v]) : Untransformed(m.mTangents[v]);
        mesh_.binormals[base + v] =
            part.transformed ? transform.Direction(m.mBitangents[v]) : Untransformed(m.mBitangents[v]);
      }
      for (int set = 0; set < kMaxTexCoordSets; ++set) {
        if (!m.HasTextureCoords(set)) continue;
        const aiVector3D& t = m.mTextureCoords[set][v];
        const unsigned components = m.mNumUVComponents[set];
        mesh_.texcoords[set][base + v] = {t.x, components >= 2 ? t.y : 0.0f, components >= 3 ? t.z : 0.0f, 1.0f};
      }
      for (int set = 0; set < kMaxColorSets; ++set) {
        if (!m.HasVertexColors(set)) continue;
        const aiColor4D& c = m.mColors[set][v];
        mesh_.colors[set][base + v] = {c.r, c.g, c.b, c.a};
      }
    }
    for (int set = 0; set < kMaxTexCoordSets; ++set) {
      if (m.HasTextureCoords(set)) {
        mesh_.texcoord_components[set] = std::max(mesh_.texcoord_components[set], static_cast<int>(m.mNumUVComponents[set]));
      }
    }
    for (const std::uint32_t index : triangles) mesh_.indices.push_back(static_cast<std::uint32_t>(base + index));
    part.index_count = mesh_.indices.size() - part.first_index;
    if (part.skinned) {
      if (Status added = AddBones(m, base); !added) return added;
    }
    next_vertex_ += m.mNumVertices;
    mesh_.parts.push_back(std::move(part));
    return {};
  }

  // The part's triangles, three vertex indices of its own each; points and lines add none
  // (triangulation leaves nothing larger).
  static Status PartTriangles(const aiMesh& m, const std::string& name, std::vector<std::uint32_t>& triangles) {
    for (unsigned f = 0; m.mFaces != nullptr && f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m.mNumVertices) {
          return Unreadable(
              fmt::format("mesh '{}': face {} refers to vertex {} of {}", name, f, face.mIndices[k], m.mNumVertices));
        }
        triangles.push_back(face.mIndices[k]);
      }
    }
    return {};
  }

  // The normals the part's vertices get (empty: the part has none): the file's, or computed ones
  // (smooth_normals.h) for every vertex with compute_normals and for the file's missing, zero and
  // non-finite ones with repair_normals. A vertex in no triangle with area keeps the file's normal
  // (kDefaultInput where the file has none) and is counted.
  std::vector<Vec4f> PartNormals(const aiMesh& m, std::span<const std::uint32_t> triangles,
                                 const PartTransform& transform, bool transformed) {
    std::vector<bool> compute(m.mNumVertices, false);
    std::size_t to_compute = 0;
    if (!triangles.empty() && (options_.compute_normals || options_.repair_normals)) {
      for (unsigned v = 0; v < m.mNumVertices; ++v) {
        compute[v] = options_.compute_normals || !m.HasNormals() || !IsUsableNormal(ToVec3f(m.mNormals[v]));
        to_compute += compute[v] ? 1 : 0;
      }
    }
    if (!m.HasNormals() && to_compute == 0) return {};
    std::vector<Vec3d> computed;
    if (to_compute > 0) {
      std::vector<Vec3f> positions(m.mNumVertices);
      for (unsigned v = 0; v < m.mNumVertices; ++v) positions[v] = ToVec3f(m.mVertices[v]);
      computed = AreaWeightedNormals(positions, triangles);
      if (!options_.compute_normals) repaired_normals_ += to_compute;
    }
    std::vector<Vec4f> normals(m.mNumVertices, kDefaultInput);
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      if (compute[v] && computed[v] != Vec3d{}) {
        normals[v] = transformed ? transform.Normal(computed[v]) : Untransformed(computed[v]);
        continue;
      }
      if (compute[v]) ++uncomputed_normals_;
      if (!m.HasNormals()) continue;
      if (!compute[v]) {
        const double length = m.mNormals[v].Length();
        if (length == 0.0) ++zero_normals_;
        if (std::abs(length - 1.0) > kUnitTolerance) ++nonunit_normals_;
      }
      normals[v] = transformed ? transform.Normal(m.mNormals[v]) : Untransformed(m.mNormals[v]);
    }
    return normals;
  }

  // Bones shared by several parts (same name, same offset matrix) get one palette entry.
  int PaletteIndex(const aiBone& bone) {
    const Matrix4d offset = FromAssimp(bone.mOffsetMatrix);
    auto key = std::make_pair(std::string(bone.mName.C_Str()), offset);
    auto [it, inserted] = palette_.try_emplace(key, static_cast<int>(mesh_.bones.size()));
    if (inserted) {
      const aiNode* node = scene_.mRootNode != nullptr ? scene_.mRootNode->FindNode(bone.mName) : nullptr;
      if (node == nullptr) ++bones_without_node_;
      mesh_.bones.push_back({key.first, Multiply(node != nullptr ? GlobalTransform(node) : IdentityMatrix(), offset)});
    }
    return it->second;
  }

  Status AddBones(const aiMesh& m, std::size_t base) {
    std::vector<std::vector<std::pair<float, int>>> influences(m.mNumVertices);
    for (unsigned b = 0; b < m.mNumBones; ++b) {
      const aiBone* bone = m.mBones[b];
      if (bone == nullptr || (bone->mNumWeights > 0 && bone->mWeights == nullptr)) continue;
      const int index = PaletteIndex(*bone);
      for (unsigned w = 0; w < bone->mNumWeights; ++w) {
        const aiVertexWeight& weight = bone->mWeights[w];
        if (weight.mVertexId >= m.mNumVertices) {
          return Unreadable(fmt::format("mesh '{}': bone '{}' weights vertex {} of {}", m.mName.C_Str(),
                                   bone->mName.C_Str(), weight.mVertexId, m.mNumVertices));
        }
        if (weight.mWeight != 0.0f) influences[weight.mVertexId].emplace_back(weight.mWeight, index);
      }
    }
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      auto& list = influences[v];
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
      });
      if (list.empty()) ++unweighted_vertices_;
      double kept = 0.0;
      for (std::size_t i = 0; i < list.size() && i < kMaxBonesPerVertex; ++i) kept += list[i].first;
      const bool renormalise = list.size() > kMaxBonesPerVertex && kept > 0.0;
      if (list.size() > kMaxBonesPerVertex) ++trimmed_vertices_;
      for (std::size_t i = 0; i < list.size() && i < kMaxBonesPerVertex; ++i) {
        mesh_.blend_weights[base + v][i] = renormalise ? static_cast<float>(list[i].first / kept) : list[i].first;
        mesh_.blend_indices[base + v][i] = static_cast<float>(list[i].second);
      }
    }
    return {};
  }

  void CountNonFinite() {
    std::vector<const std::vector<Vec4f>*> arrays = {&mesh_.positions, &mesh_.normals, &mesh_.tangents,
                                                     &mesh_.binormals, &mesh_.blend_weights};
    for (const auto& set : mesh_.texcoords) arrays.push_back(&set);
    for (const auto& set : mesh_.colors) arrays.push_back(&set);
    for (std::size_t v = 0; v < mesh_.vertex_count; ++v) {
      bool finite = true;
      for (const std::vector<Vec4f>* array : arrays) {
        if (!array->empty() && !IsFinite((*array)[v])) finite = false;
      }
      if (!finite) ++mesh_.nonfinite_vertex_count;
    }
    if (mesh_.nonfinite_vertex_count > 0) {
      mesh_.warnings.push_back(fmt::format("{} of {} vertices have a NaN or infinite attribute",
                                           mesh_.nonfinite_vertex_count, mesh_.vertex_count));
    }
    if (trimmed_vertices_ > 0) {
      mesh_.warnings.push_back(fmt::format(
          "{} vertices have more than {} bone influences: the {} largest are kept, renormalised to sum 1",
          trimmed_vertices_, kMaxBonesPerVertex, kMaxBonesPerVertex));
    }
    if (unweighted_vertices_ > 0) {
      mesh_.warnings.push_back(fmt::format("{} vertices of skinned meshes have no bone weight (they read weight 0)",
                                           unweighted_vertices_));
    }
    if (nonunit_normals_ > 0) {
      mesh_.warnings.push_back(fmt::format(
          "{} normals are not of unit length ({} of them zero){}{}", nonunit_normals_, zero_normals_,
          options_.transform_to_world ? "; nonzero ones are normalised where the node transform is applied" : "",
          zero_normals_ > 0 ? "; --compute-normals replaces them" : ""));
    }
    if (repaired_normals_ > 0) {
      std::string unlit;
      if (uncomputed_normals_ > 0) {
        unlit = fmt::format("; {} of them are in no triangle with area and still have none", uncomputed_normals_);
      }
      mesh_.warnings.push_back(fmt::format(
          "{} of {} vertices have no usable normal (none, zero or not finite) in the file: computed smooth normals "
          "for them (the area-weighted mean of the faces at each position){}",
          repaired_normals_, mesh_.vertex_count, unlit));
    } else if (uncomputed_normals_ > 0) {
      mesh_.warnings.push_back(fmt::format(
          "{} vertices are in no triangle with area: they have no computed normal and keep the file's",
          uncomputed_normals_));
    }
    if (bones_without_node_ > 0) {
      mesh_.warnings.push_back(fmt::format("{} bones name no node of the scene: their skin matrix is the offset alone",
                                           bones_without_node_));
    }
  }

  const aiScene& scene_;
  const MeshLoadOptions& options_;
  Mesh mesh_;
  std::size_t next_vertex_ = 0;
  std::map<std::pair<std::string, Matrix4d>, int> palette_;
  static constexpr double kUnitTolerance = 1e-3;
  std::size_t zero_normals_ = 0, nonunit_normals_ = 0;  // among the file's normals that are kept
  std::size_t repaired_normals_ = 0, uncomputed_normals_ = 0;
  std::size_t trimmed_vertices_ = 0, unweighted_vertices_ = 0, bones_without_node_ = 0;
};

// Assimp reports what it repaired or dropped (a triangle with an index out of range, say) only
// through its global logger. While a load runs, a logger collects the warnings and errors; the
// mutex keeps two loads from sharing it.
std::mutex assimp_logger_mutex;

class AssimpMessages : public Assimp::LogStream {
 public:
  AssimpMessages() {
    Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(this, kSeverities);
  }
  ~AssimpMessages() override {
    Assimp::DefaultLogger::get()->detachStream(this, kSeverities);
    Assimp::DefaultLogger::kill();
  }
  void write(const char* message) override {
    std::string text = message;
    // "Warn,  T0: text\n" -> "text"
    if (std::size_t colon = text.find(": "); colon != std::string::npos && colon < 16) text.erase(0, colon + 2);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    if (!text.empty() && messages.size() < kMaxMessages) messages.push_back("Assimp: " + text);
  }
  std::vector<std::string> messages;

 private:
  static constexpr unsigned kSeverities = Assimp::Logger::Warn | Assimp::Logger::Err;
  static constexpr std::size_t kMaxMessages = 20;
};

// Assimp's OFF and PLY readers allocate from the vertex and face counts in the header before they
// read the data (a 309-byte OFF file declaring 35 billion vertices runs for minutes). A count
// larger than the file's size cannot be honest, whatever the encoding: refuse it first.
constexpr std::size_t kHeaderBytes = 65536;

// Assimp 5.2's PLY reader loops without end on some malformed headers (fuzz_mesh: an element with
// no property and no end_header). The header is checked first: every element with a property and
// a count the file can hold, end_header within `head`.
Status CheckPlyHeader(std::string_view head, std::uintmax_t file_size) {
  std::size_t line_start = 0;
  bool element_open = false, element_has_property = true;
  while (line_start < head.size()) {
    std::size_t line_end = head.find('\n', line_start);
    if (line_end == std::string_view::npos) break;
    std::string_view line = head.substr(line_start, line_end - line_start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    line_start = line_end + 1;
    const std::string_view keyword = line.substr(0, line.find(' '));
    if (keyword == "end_header") {
      if (element_open && !element_has_property) return Unreadable("a PLY element has no property");
      return {};
    }
    if (keyword == "element") {
      if (element_open && !element_has_property) return Unreadable("a PLY element has no property");
      element_open = true;
      element_has_property = false;
      const std::size_t count_at = line.rfind(' ');
      const auto no_count = [&] { return Unreadable(fmt::format("PLY header line '{}' has no element count", line)); };
      if (count_at == std::string_view::npos) return no_count();  // before pointing past it
      std::uintmax_t count = 0;
      auto [ptr, ec] = std::from_chars(line.data() + count_at + 1, line.data() + line.size(), count);
      if (ec != std::errc() || ptr != line.data() + line.size()) return no_count();
      if (count > file_size) {
        return Unreadable(
            fmt::format("the header declares {} elements, more than a {}-byte file can hold", count, file_size));
      }
    } else if (keyword == "property") {
      if (!element_open) return Unreadable("a PLY property comes before any element");
      element_has_property = true;
    }  // other lines (comments without the keyword, as some exporters write) are skipped, as Assimp does
  }
  return Unreadable("no PLY end_header in the first 64 KB");
}

Status CheckHeaderCounts(std::string_view head, std::uintmax_t file_size) {
  auto too_many = [&](std::uintmax_t count, const char* what) -> Status {
    if (count <= file_size) return {};
    return Unreadable(
        fmt::format("the header declares {} {}, more than a {}-byte file can hold", count, what, file_size));
  };
  auto number_at = [&](std::size_t& at) -> std::optional<std::uintmax_t> {
    while (at < head.size() && (head[at] == ' ' || head[at] == '\t' || head[at] == '\r' || head[at] == '\n')) ++at;
    std::uintmax_t value = 0;
    auto [ptr, ec] = std::from_chars(head.data() + at, head.data() + head.size(), value);
    if (ec != std::errc()) return std::nullopt;
    at = static_cast<std::size_t>(ptr - head.data());
    return value;
  };
  if (head.starts_with("OFF") || head.starts_with("NOFF") || head.starts_with("COFF") || head.starts_with("STOFF")) {
    std::size_t at = head.find_first_of(" \t\r\n");
    if (at == std::string_view::npos) return {};
    std::optional<std::uintmax_t> vertices = number_at(at), faces = number_at(at);
    if (vertices) {
      if (Status counted = too_many(*vertices, "vertices"); !counted) return counted;
    }
    if (faces) return too_many(*faces, "faces");
    return {};
  }
  if (head.starts_with("ply")) return CheckPlyHeader(head, file_size);
  return {};
}

// Normals are vs11's (smooth_normals.h), computed after post-processing from its final triangles.
// Assimp's GenSmoothNormals runs only where CalcTangentSpace needs normals for a part without any;
// never with aiProcess_ForceGenNormals, which in Assimp 5.2 frees a point or line mesh's normals and
// leaves the freed pointer in the mesh.
unsigned PostProcessFlags(const MeshLoadOptions& options) {
  unsigned flags = aiProcess_Triangulate;
  if (options.compute_tangents) flags |= aiProcess_CalcTangentSpace;
  if (options.compute_tangents && options.compute_normals) flags |= aiProcess_GenSmoothNormals;
  return flags;
}

// What Assimp's post-processing steps and MeshBuilder index without checking. Assimp's own
// aiProcess_ValidateDataStructure checks this too, but it also refuses sound files for things vs11
// does not read (a light without a node, a point cloud without faces), so the scene is read with
// no post-processing, checked here, and post-processed after (a face index past the vertices
// crashes aiProcess_Triangulate).
// Also rewrites each mesh's mPrimitiveTypes from its faces: aiProcess_Triangulate trusts the
// POLYGON bit and aborts (an ai_assert in Debian's build) when no face is a polygon after all.
Status CheckSceneIndices(aiScene& scene) {
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr) return Unreadable("the scene lists meshes it does not hold");
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    aiMesh* m = scene.mMeshes[i];
    if (m == nullptr) return Unreadable(fmt::format("mesh {} is missing", i));
    const char* name = m->mName.C_Str();
    if (m->mNumVertices > 0 && m->mVertices == nullptr) {
      return Unreadable(fmt::format("mesh '{}' has no vertex positions", name));
    }
    if (m->mNumFaces > 0 && m->mFaces == nullptr) return Unreadable(fmt::format("mesh '{}' lists faces it does not hold", name));
    unsigned primitive_types = 0;
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr) {
        return Unreadable(fmt::format("mesh '{}': face {} has no indices", name, f));
      }
      primitive_types |= face.mNumIndices == 1   ? aiPrimitiveType_POINT
                         : face.mNumIndices == 2 ? aiPrimitiveType_LINE
                         : face.mNumIndices == 3 ? aiPrimitiveType_TRIANGLE
                                                 : aiPrimitiveType_POLYGON;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= m->mNumVertices) {
          return Unreadable(fmt::format("mesh '{}': face {} refers to vertex {} of {}", name, f, face.mIndices[k],
                             m->mNumVertices));
        }
      }
    }
    m->mPrimitiveTypes = primitive_types;
    if (m->mNumBones > 0 && m->mBones == nullptr) return Unreadable(fmt::format("mesh '{}' lists bones it does not hold", name));
    for (unsigned b = 0; b < m->mNumBones; ++b) {
      const aiBone* bone = m->mBones[b];
      if (bone == nullptr || (bone->mNumWeights > 0 && bone->mWeights == nullptr)) {
        return Unreadable(fmt::format("mesh '{}': bone {} is missing its weights", name, b));
      }
      for (unsigned w = 0; w < bone->mNumWeights; ++w) {
        if (bone->mWeights[w].mVertexId >= m->mNumVertices) {
          return Unreadable(fmt::format("mesh '{}': bone '{}' weights vertex {} of {}", name, bone->mName.C_Str(),
                             bone->mWeights[w].mVertexId, m->mNumVertices));
        }
      }
    }
  }
  return {};
}

// `scene` as read with no post-processing.
Result<Mesh> FromScene(const aiScene* scene, Assimp::Importer& importer, const std::string& name,
                       const MeshLoadOptions& options, AssimpMessages& messages, const internal::StageReporter& report) {
  auto assimp_error = [&] {
    std::string reason = importer.GetErrorString();
    if (reason.empty()) reason = "Assimp could not read it";
    // Assimp turns every exception into its message; a corrupt size field makes some readers ask
    // for tens of gigabytes (tests/fuzz/seeds/fuzz_mesh/*_allocates_*).
    if (reason == "std::bad_alloc") {
      reason = "Assimp ran out of memory reading it (std::bad_alloc): the file is corrupt, or needs more than "
               "the loader's memory limit";
    }
    return Unreadable(fmt::format("{}: {}", name, reason));
  };
  if (scene == nullptr) return assimp_error();
  report(internal::LoadStage::kVs11);
  // The importer owns the scene and hands it out as const; the check repairs its primitive flags.
  if (Status checked = CheckSceneIndices(*const_cast<aiScene*>(scene)); !checked) return Named(name, checked.error());
  report(internal::LoadStage::kAssimp);
  scene = importer.ApplyPostProcessing(PostProcessFlags(options));
  if (scene == nullptr) return assimp_error();
  report(internal::LoadStage::kVs11);
  Result<Mesh> result = MeshBuilder(*scene, options).Build();
  if (!result) return Named(name, result.error());
  std::vector<std::string>& warnings = result->warnings;
  warnings.insert(warnings.begin(), messages.messages.begin(), messages.messages.end());
  return result;
}

// What is checked before Assimp sees a file: its size and the header counts above.
Status CheckBeforeAssimp(std::span<const std::uint8_t> head, std::uintmax_t size) {
  if (size == 0) return Unreadable("the file is empty");
  if (size > kMaxMeshFileBytes) {
    return Unreadable(fmt::format("{} bytes, over the {}-byte limit for mesh files", size, kMaxMeshFileBytes));
  }
  return CheckHeaderCounts({reinterpret_cast<const char*>(head.data()), head.size()}, size);
}

}  // namespace

Matrix4d IdentityMatrix() { return {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}}; }

const std::vector<Vec4f>* Mesh::Find(Attribute attribute, int set) const {
  const std::vector<Vec4f>* array = nullptr;
  switch (attribute) {
    case Attribute::kPosition: array = &positions; break;
    case Attribute::kNormal: array = &normals; break;
    case Attribute::kTangent: array = &tangents; break;
    case Attribute::kBinormal: array = &binormals; break;
    case Attribute::kTexCoord: array = set >= 0 && set < kMaxTexCoordSets ? &texcoords[set] : nullptr; break;
    case Attribute::kColor: array = set >= 0 && set < kMaxColorSets ? &colors[set] : nullptr; break;
    case Attribute::kBlendWeight: array = &blend_weights; break;
    case Attribute::kBlendIndices: array = &blend_indices; break;
  }
  return array != nullptr && !array->empty() ? array : nullptr;
}

bool IsMeshFileExtension(const std::string& extension) {
  if (extension.empty()) return false;
  return Assimp::Importer().IsExtensionSupported(extension[0] == '.' ? extension : "." + extension);
}

Result<Mesh> LoadMesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string name = path.string();
  std::error_code error;
  if (const Status why = InputFileProblem(path, /*pipes_allowed=*/false); !why.ok()) return Named(name, why.error());
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return Unreadable(fmt::format("{}: cannot read its size ({})", name, error.message()));
  std::vector<std::uint8_t> head(std::min<std::uintmax_t>(size, kHeaderBytes));
  {
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  if (const Status checked = CheckBeforeAssimp(head, size); !checked) return Named(name, checked.error());
  return internal::RunSandboxed(name, size, options, [&](const internal::StageReporter& report) {
    return internal::LoadMeshInProcess(path, options, report);
  });
}

Result<Mesh> LoadMeshFromMemory(std::span<const std::uint8_t> bytes, const std::string& format_hint,
                                const MeshLoadOptions& options) {
  if (bytes.empty()) return Unreadable("<memory>: no bytes");
  const Status checked = CheckBeforeAssimp(bytes.first(std::min(bytes.size(), kHeaderBytes)), bytes.size());
  if (!checked) return Named("<memory>", checked.error());
  return internal::RunSandboxed("<memory>", bytes.size(), options, [&](const internal::StageReporter& report) {
    return internal::LoadMeshFromMemoryInProcess(bytes, format_hint, options, report);
  });
}

namespace internal {

// In the sandbox's child a single thread runs; the lock serves in-process callers (the fuzz target).
Result<Mesh> LoadMeshInProcess(const std::filesystem::path& path, const MeshLoadOptions& options,
                               const StageReporter& report) {
  std::lock_guard lock(assimp_logger_mutex);
  report(LoadStage::kAssimp);
  AssimpMessages messages;
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), 0);
  return FromScene(scene, importer, path.string(), options, messages, report);
}

Result<Mesh> LoadMeshFromMemoryInProcess(std::span<const std::uint8_t> bytes, const std::string& format_hint,
                                         const MeshLoadOptions& options, const StageReporter& report) {
  std::lock_guard lock(assimp_logger_mutex);
  report(LoadStage::kAssimp);
  AssimpMessages messages;
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, format_hint.c_str());
  return FromScene(scene, importer, "<memory>", options, messages, report);
}

}  // namespace internal
}  // namespace vs11::mesh
