// Small mesh files written by the mesh tests: a glTF triangle placed by a node transform.
#pragma once

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace vs11::testing {

inline constexpr const char* kAssimpModels = "/usr/share/assimp/models";

inline void WriteBytes(const std::filesystem::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline void WriteText(const std::filesystem::path& path, const std::string& text) {
  WriteBytes(path, text.data(), text.size());
}

// One triangle (0,0,0) (1,0,0) (0,1,0) with normals `normal` at each corner, under a node with the
// given glTF "scale" and "translation" (JSON arrays). Returns the .gltf path.
inline std::filesystem::path WriteGltfTriangle(const std::filesystem::path& dir, const float normal[3],
                                               const std::string& scale, const std::string& translation) {
  std::filesystem::create_directories(dir);
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::vector<float> normals;
  for (int i = 0; i < 3; ++i) normals.insert(normals.end(), normal, normal + 3);
  std::vector<char> bin(72);
  std::memcpy(bin.data(), positions.data(), 36);
  std::memcpy(bin.data() + 36, normals.data(), 36);
  WriteBytes(dir / "tri.bin", bin.data(), bin.size());
  const std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "scale": )" + scale + R"(, "translation": )" + translation + R"(}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
  "buffers": [{"uri": "tri.bin", "byteLength": 72}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}]})";
  WriteText(dir / "tri.gltf", gltf);
  return dir / "tri.gltf";
}

}  // namespace vs11::testing
