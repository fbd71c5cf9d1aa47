#include "vm/core/atomic_file.h"
#include "vm/mesh/mesh_export.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include <assimp/Exporter.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/asm/program_file.h"

namespace vs11::mesh {
namespace {

aiVector3D ToVector(const Vec4f& v) { return {v[0], v[1], v[2]}; }

// The scene Assimp's exporters read: one mesh under the root node, one default material.
std::unique_ptr<aiScene> BuildScene(const Mesh& mesh, const ExportAttributes& attributes, bool clamp_colors) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("root");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh& out = *scene->mMeshes[0];
  out.mName = "vs11";
  out.mMaterialIndex = 0;
  out.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const unsigned n = static_cast<unsigned>(mesh.vertex_count);
  out.mNumVertices = n;
  out.mVertices = new aiVector3D[n];
  for (unsigned v = 0; v < n; ++v) out.mVertices[v] = ToVector(mesh.positions[v]);
  if (!mesh.normals.empty()) {
    out.mNormals = new aiVector3D[n];
    for (unsigned v = 0; v < n; ++v) out.mNormals[v] = ToVector(mesh.normals[v]);
  }
  if (attributes.color != nullptr) {
    out.mColors[0] = new aiColor4D[n];
    for (unsigned v = 0; v < n; ++v) {
      const Vec4f& c = (*attributes.color)[v];
      out.mColors[0][v] = clamp_colors ? aiColor4D(std::clamp(c[0], 0.0f, 1.0f), std::clamp(c[1], 0.0f, 1.0f),
                                                   std::clamp(c[2], 0.0f, 1.0f), std::clamp(c[3], 0.0f, 1.0f))
                                       : aiColor4D(c[0], c[1], c[2], c[3]);
    }
  }
  int next_set = 0;  // Assimp wants the UV sets packed from 0
  for (const std::vector<Vec4f>* texcoords : attributes.texcoords) {
    if (texcoords == nullptr) continue;
    out.mTextureCoords[next_set] = new aiVector3D[n];
    out.mNumUVComponents[next_set] = 2;
    for (unsigned v = 0; v < n; ++v) out.mTextureCoords[next_set][v] = aiVector3D((*texcoords)[v][0], (*texcoords)[v][1], 0.0f);
    ++next_set;
  }
  const std::size_t triangles = mesh.indices.size() / 3;
  out.mNumFaces = static_cast<unsigned>(triangles);
  out.mFaces = new aiFace[triangles];
  for (std::size_t t = 0; t < triangles; ++t) {
    out.mFaces[t].mNumIndices = 3;
    out.mFaces[t].mIndices = new unsigned[3]{mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
  }
  return scene;
}

// PLY: the note as comment lines right after the format line.
std::string AnnotatePly(std::string bytes, const std::string& note) {
  const std::size_t format_line = bytes.find("format ");
  const std::size_t line_end = bytes.find('\n', format_line);
  if (format_line == std::string::npos || line_end == std::string::npos) return bytes;
  std::string comments;
  std::size_t start = 0;
  while (start < note.size()) {
    std::size_t end = note.find('\n', start);
    if (end == std::string::npos) end = note.size();
    comments += "comment vs11: " + note.substr(start, end - start) + "\n";
    start = end + 1;
  }
  bytes.insert(line_end + 1, comments);
  return bytes;
}

std::uint32_t ReadU32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

void WriteU32(std::string& bytes, std::size_t at, std::uint32_t value) { std::memcpy(bytes.data() + at, &value, 4); }

// GLB: header (12 bytes), then the JSON chunk (length, "JSON", text padded with spaces to 4 bytes),
// then the binary chunk. The note goes into asset.extras.vs11; lengths are rewritten.
// The errors name `path`.
Status AnnotateGlb(std::string& bytes, const std::string& note, const std::filesystem::path& path) {
  const auto unexpected = [&path](std::string_view what) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{}: Assimp's GLB exporter wrote {}", path.string(), what));
  };
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || bytes.compare(16, 4, "JSON") != 0) {
    return unexpected("an unexpected layout");
  }
  const std::uint32_t json_length = ReadU32(bytes, 12);
  if (20 + static_cast<std::size_t>(json_length) > bytes.size()) return unexpected("a short JSON chunk");
  nlohmann::json json = nlohmann::json::parse(bytes.substr(20, json_length), nullptr, false);
  if (json.is_discarded()) return unexpected("JSON that does not parse");
  json["asset"]["extras"]["vs11"] = note;
  std::string text = json.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  std::string rebuilt = bytes.substr(0, 12);
  rebuilt.append(8, '\0');
  WriteU32(rebuilt, 12, static_cast<std::uint32_t>(text.size()));
  std::memcpy(rebuilt.data() + 16, "JSON", 4);
  rebuilt += text;
  rebuilt += bytes.substr(20 + json_length);
  WriteU32(rebuilt, 8, static_cast<std::uint32_t>(rebuilt.size()));
  bytes = std::move(rebuilt);
  return {};
}

}  // namespace

Status ExportMesh(const Mesh& mesh, const ExportAttributes& attributes, const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const char* format = extension == ".ply" ? "ply" : extension == ".glb" ? "glb2" : nullptr;
  if (format == nullptr) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{}: --out-mesh writes .ply or .glb files", path.string()));
  }
  auto check = [&](const std::vector<Vec4f>* values) { return values == nullptr || values->size() == mesh.vertex_count; };
  bool sizes_match = check(attributes.color);
  for (const auto* texcoords : attributes.texcoords) sizes_match = sizes_match && check(texcoords);
  if (!sizes_match) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{}: an output array does not hold one value per vertex", path.string()));
  }

  // Assimp's PLY exporter stores colours as 8-bit channels: they
  // are clamped to [0, 1] first, as D3D clamps oD0. GLB keeps float RGBA as it is.
  const bool ply = extension == ".ply";
  std::unique_ptr<aiScene> scene = BuildScene(mesh, attributes, ply);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), format);
  if (blob == nullptr) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{}: Assimp could not export: {}", path.string(), exporter.GetErrorString()));
  }
  if (blob->next != nullptr) {
    return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: Assimp wrote more than one file", path.string()));
  }
  std::string bytes(static_cast<const char*>(blob->data), blob->size);
  if (!attributes.note.empty()) {
    if (ply) {
      const std::string colour_note = attributes.color != nullptr ? "\nPLY colours: clamped to [0, 1], 8-bit" : "";
      bytes = AnnotatePly(std::move(bytes), attributes.note + colour_note);
    } else if (Status annotated = AnnotateGlb(bytes, attributes.note, path); !annotated.ok()) {
      return annotated;
    }
  }
  return WriteFileAtomically(path, bytes);
}

}  // namespace vs11::mesh
