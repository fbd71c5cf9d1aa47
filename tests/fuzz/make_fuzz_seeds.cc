// Writes the fuzzers' seed corpora: make_fuzz_seeds SOURCE_DIR CORPUS_DIR.
//   CORPUS_DIR/fuzz_assembler    programs/*.vsh and tests/data/disasm/*.vsh
//   CORPUS_DIR/fuzz_translate    the same sources
//   CORPUS_DIR/fuzz_bytecode     the same programs assembled (without validation) to bytecode
//   CORPUS_DIR/fuzz_environment  tiny images, one per layout and format (.hdr .exr .png .tif)
//   CORPUS_DIR/fuzz_mesh         assimp-testmodels files under 16 KB
//   CORPUS_DIR/fuzz_mesh_wire    the sandboxed mesh loader's replies for those that load
//   CORPUS_DIR/fuzz_npy          .npy files of 1 to 4 columns
//   CORPUS_DIR/fuzz_buffer_element  "STRIDE v#=OFFSET:COUNT..." lines, each with a buffer of floats
//   CORPUS_DIR/fuzz_capi         a D3D9 and a D3D8 shader with declarations, FVF and declaration outputs
//   CORPUS_DIR/fuzz_batch_merge  only its committed seeds: shard outputs (records, a duplicate, a cut-off line)
// plus, for each target, the committed files in tests/fuzz/seeds/<target>/.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/mesh_wire.h"
#include "vm/mesh/npy.h"
#include "tests/fuzz/fuzz_capi_input.h"

namespace {

namespace fs = std::filesystem;
namespace irr = vs11::irradiance;

bool WriteOrComplain(const fs::path& path, std::span<const std::uint8_t> bytes) {
  if (const vs11::Status written = vs11::WriteFileAtomically(path, bytes); !written) {
    std::fprintf(stderr, "make_fuzz_seeds: %s\n", written.message().c_str());
    return false;
  }
  return true;
}

bool WriteProgramSeeds(const fs::path& source_dir, const fs::path& corpus_dir) {
  bool ok = true;
  for (const fs::path& folder : {source_dir / "programs", source_dir / "tests" / "data" / "disasm"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      if (entry.path().extension() != ".vsh") continue;
      std::string name = folder.filename().string() + "_" + entry.path().stem().string();
      for (const char* target : {"fuzz_assembler", "fuzz_translate"}) {
        fs::copy_file(entry.path(), corpus_dir / target / (name + ".vsh"), fs::copy_options::overwrite_existing);
      }
      vs11::AssembleOptions options;
      options.validate = false;
      vs11::AssembleResult assembled = vs11::AssembleFile(entry.path(), options);
      if (!assembled.program) continue;  // a program that needs -I or -D: its text is seed enough
      std::vector<std::uint8_t> bytes = vs11::BytesFromWords(vs11::Encode(*assembled.program));
      ok &= WriteOrComplain(corpus_dir / "fuzz_bytecode" / (name + ".vso"), bytes);
    }
  }
  return ok;
}

// A small image with a gradient, so that no two channels or pixels are alike.
irr::Image Gradient(int width, int height) {
  irr::Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.at(x, y) = glm::vec3(0.1f * x, 0.2f * y + 0.05f, 0.5f);
  }
  return image;
}

bool WriteImageSeeds(const fs::path& dir) {
  struct Seed {
    const char* name;
    int width, height;
  };
  const Seed seeds[] = {
      {"latlong.hdr", 8, 4}, {"hcross.exr", 8, 6}, {"vcross.png", 3, 4}, {"hstrip.tif", 6, 1},
      {"vstrip.exr", 2, 12}, {"angular.png", 4, 4}, {"odd.hdr", 5, 3},
  };
  bool ok = true;
  for (const Seed& seed : seeds) {
    if (const vs11::Status written = irr::WriteImage(Gradient(seed.width, seed.height), dir / seed.name); !written) {
      std::fprintf(stderr, "make_fuzz_seeds: %s\n", written.message().c_str());
      ok = false;
    }
  }
  return ok;
}

}  // namespace

// Debian's assimp-testmodels files under 16 KB that hold everything in one file.
bool WriteMeshSeeds(const fs::path& dir) {
  const fs::path models = "/usr/share/assimp/models";
  if (!fs::is_directory(models)) {
    std::fprintf(stderr, "make_fuzz_seeds: %s missing (install assimp-testmodels)\n", models.c_str());
    return false;
  }
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    if (!entry.is_regular_file() || entry.file_size() == 0 || entry.file_size() > 16384) continue;
    std::string extension = entry.path().extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".obj" && extension != ".ply" && extension != ".off" && extension != ".stl" &&
        extension != ".gltf" && extension != ".glb" && extension != ".dae" && extension != ".3ds" &&
        extension != ".x" && extension != ".ac" && extension != ".smd" && extension != ".fbx") {
      continue;
    }
    fs::copy_file(entry.path(), dir / ("seed" + std::to_string(count++) + extension), fs::copy_options::overwrite_existing);
  }
  return count > 0;
}

// The sandboxed loader's replies (stage bytes and a record, mesh_wire.h) for the mesh seeds that
// load, and one error reply.
std::span<const std::uint8_t> AsBytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

bool WriteMeshReplySeeds(const fs::path& mesh_seeds, const fs::path& dir) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(mesh_seeds)) {
    if (count == 24) break;
    vs11::Result<vs11::mesh::Mesh> loaded = vs11::mesh::LoadMesh(entry.path());
    if (!loaded.ok()) continue;
    const std::string reply = "AVAV" + vs11::mesh::EncodeReplyRecord(loaded);
    if (!WriteOrComplain(dir / ("reply" + std::to_string(count++) + ".bin"), AsBytes(reply))) return false;
  }
  const std::string error = "AV" + vs11::mesh::EncodeReplyRecord(
      vs11::Failure(vs11::DiagnosticCode::kCannotReadFile, "the scene holds no mesh with vertices"));
  return count > 0 && WriteOrComplain(dir / "error.bin", AsBytes(error));
}

bool WriteNpySeeds(const fs::path& dir) {
  bool ok = true;
  for (int columns = 1; columns <= 4; ++columns) {
    vs11::mesh::NpyArray array;
    array.rows = 3;
    array.columns = columns;
    for (int i = 0; i < 3 * columns; ++i) array.values.push_back(0.5f * static_cast<float>(i) - 1.0f);
    ok &= WriteOrComplain(dir / ("rows" + std::to_string(columns) + ".npy"), vs11::mesh::FormatNpy(array));
  }
  return ok;
}

// Layouts as `vs11 run --buffer` takes them (tests/fuzz/fuzz_buffer_element.cc), among them one whose
// end wrapped around, each followed by three vertices of floats.
bool WriteBufferElementSeeds(const fs::path& dir) {
  const struct {
    const char* name;
    const char* layout;
    int stride;
  } seeds[] = {{"one", "16 v0=0:4", 16},
               {"three", "32 v0=0:3 v3=12:3 v7=24:2", 32},
               {"odd_stride", "13 v1=1:3 v2=9:1", 13},
               {"wrapped", "16 v0=18446744073709551600:4", 16}};
  bool ok = true;
  for (const auto& seed : seeds) {
    std::string text = std::string(seed.layout) + "\n";
    for (int i = 0; i < 3 * seed.stride; ++i) text.push_back(static_cast<char>(i));
    ok &= WriteOrComplain(dir / seed.name, AsBytes(text));
  }
  return ok;
}

// The C library's inputs (tests/fuzz/fuzz_capi_input.h): shaders that validate, so that the fuzzer
// starts from runs that reach the engines and the output writers.
bool WriteCApiSeeds(const fs::path& dir) {
  auto tokens = [](const char* source) {
    vs11::AssembleResult assembled = vs11::AssembleSource(source, "seed.vsh", {});
    return assembled.program ? vs11::Encode(*assembled.program) : std::vector<std::uint32_t>{};
  };
  vs11::fuzz::CApiInput d3d9;
  d3d9.vertex_count = 3;
  d3d9.tokens = tokens("vs_1_1\ndcl_position v0\ndcl_color v1\ndcl_texcoord v2\nm4x4 oPos, v0, c0\nmov oD0, v1\nmov oT0, v2\n");
  // FLOAT3 POSITION and D3DCOLOR COLOR in stream 0, SHORT2N TEXCOORD0 in stream 1.
  d3d9.input = {{0, 0, 2, 0, 0, 0}, {0, 12, 4, 0, 10, 0}, {1, 0, 9, 0, 5, 0}};
  d3d9.fvf = 0x004 | 0x040 | 0x100;  // XYZRHW, DIFFUSE, TEX1
  d3d9.output_stride = 28;
  d3d9.strides[0] = 16;
  d3d9.strides[1] = 4;
  for (int i = 0; i < 64; ++i) d3d9.vertex_bytes.push_back(static_cast<std::uint8_t>(i * 37));
  vs11::fuzz::CApiInput declared = d3d9;
  declared.fvf = 0;
  declared.output = {{0, 0, 3, 0, 9, 0}, {0, 16, 4, 0, 10, 0}, {0, 20, 1, 0, 5, 0}};
  vs11::fuzz::CApiInput d3d8 = d3d9;
  d3d8.d3d8 = true;
  d3d8.input.clear();
  d3d8.tokens = tokens("vs.1.1\nm4x4 oPos, v0, c0\nmov oD0, v5\nmov oT0, v7\n");
  // STREAM(0), REG(0, FLOAT3), REG(5, D3DCOLOR), STREAM(1), REG(7, SHORT2), CONST(0, 1) + 4 floats, END.
  d3d8.declaration = {0x20000000, 0x40020000, 0x40040005, 0x20000001, 0x40060007, 0x82000000,
                      0x3F800000, 0, 0, 0, 0xFFFFFFFF};
  bool ok = true;
  ok &= WriteOrComplain(dir / "d3d9_fvf", vs11::fuzz::SerializeCApiInput(d3d9));
  ok &= WriteOrComplain(dir / "d3d9_declaration", vs11::fuzz::SerializeCApiInput(declared));
  ok &= WriteOrComplain(dir / "d3d8", vs11::fuzz::SerializeCApiInput(d3d8));
  return ok;
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_fuzz_seeds SOURCE_DIR CORPUS_DIR\n");
    return 2;
  }
  fs::path source_dir = argv[1], corpus_dir = argv[2];
  bool ok = true;
  for (const char* target : {"fuzz_assembler", "fuzz_bytecode", "fuzz_environment", "fuzz_mesh", "fuzz_mesh_wire", "fuzz_npy",
                             "fuzz_buffer_element", "fuzz_translate", "fuzz_batch_merge", "fuzz_capi"}) {
    fs::create_directories(corpus_dir / target);
    fs::path committed = source_dir / "tests" / "fuzz" / "seeds" / target;
    if (fs::is_directory(committed)) {
      fs::copy(committed, corpus_dir / target, fs::copy_options::overwrite_existing);
    }
  }
  ok &= WriteProgramSeeds(source_dir, corpus_dir);
  ok &= WriteImageSeeds(corpus_dir / "fuzz_environment");
  ok &= WriteMeshSeeds(corpus_dir / "fuzz_mesh");
  ok &= WriteMeshReplySeeds(corpus_dir / "fuzz_mesh", corpus_dir / "fuzz_mesh_wire");
  ok &= WriteNpySeeds(corpus_dir / "fuzz_npy");
  ok &= WriteBufferElementSeeds(corpus_dir / "fuzz_buffer_element");
  ok &= WriteCApiSeeds(corpus_dir / "fuzz_capi");
  return ok ? 0 : 1;
}
