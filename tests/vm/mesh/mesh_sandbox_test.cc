// The sandboxed mesh loader (vm/mesh/mesh_sandbox.h): files that crashed or hung Assimp 5.2 under
// tests/fuzz/fuzz_mesh give a clear error (and exit code 1 from the tools), a child that dies by a
// signal is named with it, and the parent checks what the child sends (vm/mesh/mesh_wire.h).
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/common_interface_defs.h>
#endif
#endif

#include "tests/run_tool.h"
#include "tests/vm/mesh/mesh_test_support.h"
#include "vm/mesh/mesh_io.h"
#include "vm/mesh/mesh_sandbox.h"
#include "vm/mesh/mesh_wire.h"

namespace vs11::mesh {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using internal::LoadStage;

// Inputs that crashed Assimp are fuzz seeds too; those that hang it are not (each would cost the
// fuzz target its whole time limit at every start).
const fs::path kFound = fs::path(VS11_SOURCE_DIR) / "tests/fuzz/seeds/fuzz_mesh";
const fs::path kHangs = fs::path(VS11_SOURCE_DIR) / "tests/data/mesh";
const std::string kProgram = std::string(VS11_SOURCE_DIR) + "/programs/directional_light.vsh";
const std::string kWuson = std::string(vs11::testing::kAssimpModels) + "/PLY/Wuson.ply";

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Found by fuzz_mesh (in fork mode, before the sandbox): Assimp's 3DS and text DirectX readers take
// sizes from the file and allocate tens of gigabytes. Each must end in an error naming the file:
// the child's memory limit makes the allocation fail, which Assimp reports; under AddressSanitizer
// (no such limit) ASan's allocator refuses it and ends the child, which is named as a crash, as is
// ThreadSanitizer's out-of-memory abort at the limit (.ci/tsan sets abort_on_error).
TEST(MeshSandbox, FilesThatMadeAssimpAllocateTensOfGigabytesGiveAnError) {
  for (const char* name : {"3ds_allocates_45gb.3ds", "3ds_allocates_46gb.3ds", "x_text_allocates_26gb.x"}) {
    const fs::path file = kFound / name;
    Result<Mesh> result = LoadMesh(file);
    ASSERT_FALSE(result.ok()) << name;
    EXPECT_NE(result.error().code, DiagnosticCode::kMeshConverterCrashed) << result.message();
    const bool out_of_memory = result.message() == file.string() + ": Assimp ran out of memory reading it "
                                               "(std::bad_alloc): the file is corrupt, or needs more than the "
                                               "loader's memory limit";
    const bool crashed = result.message().starts_with("Assimp crashed reading " + file.string() + " (SIG");
    EXPECT_TRUE(out_of_memory || crashed) << result.message();
  }
}

// Found by fuzz_mesh: a mutated Collada file on which Assimp's XML reader loops (until the child's
// memory limit, minutes later); by mutating test_cube_compressed.x: a compressed DirectX file on
// which Assimp's reader loops.
TEST(MeshSandbox, FilesThatHangAssimpStopAtTheTimeLimit) {
  for (const char* name : {"collada_endless_loop.dae", "x_compressed_endless_loop.x"}) {
    const fs::path file = kHangs / name;
    MeshLoadOptions options;
    options.timeout_seconds = 1.5;
    const auto start = Clock::now();
    Result<Mesh> result = LoadMesh(file, options);
    EXPECT_FALSE(result.ok());
    EXPECT_NE(result.message().find("reading " + file.string() + " did not finish within 1.5 s (in Assimp's reader"),
              std::string::npos) << result.message();
    EXPECT_LT(SecondsSince(start), 30.0);
  }
}

TEST(MeshSandbox, ToolsExitWithCode1AndTheTimeoutError) {
  const fs::path file = kHangs / "collada_endless_loop.dae";
  auto run = vs11::testing::RunVs11("run " + kProgram + " --mesh " + file.string() + " --mesh-timeout 1");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("did not finish within 1 s"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--mesh-timeout"), std::string::npos) << run.output;
  for (const char* name : {"3ds_allocates_46gb.3ds", "x_text_allocates_26gb.x"}) {
    run = vs11::testing::RunVs11("run " + kProgram + " --mesh " + (kFound / name).string());
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find((kFound / name).string()), std::string::npos) << run.output;
    EXPECT_TRUE(run.output.find("out of memory") != std::string::npos ||
                run.output.find("Assimp crashed reading") != std::string::npos) << run.output;
  }
}

TEST(MeshSandbox, IrrmapExitsWithCode1AndTheTimeoutError) {
  const fs::path out = fs::path(::testing::TempDir()) / "vs11_mesh_sandbox_irrmap";
  fs::remove_all(out);
  auto run = vs11::testing::RunIrrmap("sky --face-size 16 --out " + out.string() + " --mesh " +
                                      (kHangs / "collada_endless_loop.dae").string() + " --mesh-timeout 1");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("did not finish within 1 s"), std::string::npos) << run.output;
  fs::remove_all(out);
}

Result<Mesh> RaiseIn(LoadStage stage, int signal) {
  return internal::RunSandboxed("test.obj", 100, {}, [&](const internal::StageReporter& report) -> Result<Mesh> {
    report(stage);
    raise(signal);
    return Failure(DiagnosticCode::kCannotReadFile, "not reached");
  });
}

TEST(MeshSandbox, SignalDeathNamesTheFileAndTheSignal) {
  Result<Mesh> result = RaiseIn(LoadStage::kAssimp, SIGSEGV);
  EXPECT_EQ(result.message(), "Assimp crashed reading test.obj (SIGSEGV); the file is corrupt or unsupported");
  EXPECT_EQ(result.error().code, DiagnosticCode::kCannotReadFile);
  result = RaiseIn(LoadStage::kAssimp, SIGBUS);
  EXPECT_NE(result.message().find("(SIGBUS)"), std::string::npos) << result.message();
  // A death in vs11's own code is vs11's bug, and says so.
  result = RaiseIn(LoadStage::kVs11, SIGSEGV);
  EXPECT_EQ(result.error().code, DiagnosticCode::kMeshConverterCrashed);
  EXPECT_NE(result.message().find("vs11 crashed converting test.obj"), std::string::npos) << result.message();
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
// libFuzzer sets a sanitizer death callback that saves the input being fuzzed as a crash-* file
// (tests/fuzz). A sanitizer report in the child (here ASan refusing an allocation larger than it
// supports, as Assimp's corrupt-size reads provoke) ends the child without running it: the parent
// reports the file as unreadable, and fuzz_mesh leaves no crash file that is not vs11's.
fs::path DeathCallbackMarker() { return fs::path(::testing::TempDir()) / "mesh_sandbox_death_callback_ran"; }

TEST(MeshSandbox, ChildDiesWithoutTheParentsSanitizerDeathCallback) {
  fs::remove(DeathCallbackMarker());
  __sanitizer_set_death_callback([] { std::ofstream(DeathCallbackMarker()) << "the child ran it\n"; });
  const Result<Mesh> result =
      internal::RunSandboxed("test.obj", 100, {}, [](const internal::StageReporter& report) -> Result<Mesh> {
    report(LoadStage::kAssimp);
    volatile std::size_t beyond_asan = std::size_t{1} << 50;
    void* volatile memory = std::malloc(beyond_asan);
    std::free(memory);
    return Failure(DiagnosticCode::kCannotReadFile, "not reached: ASan refuses the allocation");
  });
  __sanitizer_set_death_callback(nullptr);
  EXPECT_NE(result.message().find("Assimp crashed reading test.obj"), std::string::npos) << result.message();
  EXPECT_FALSE(fs::exists(DeathCallbackMarker()));
}
#endif
#endif

TEST(MeshSandbox, ChildErrorsAndExceptionsComeBackNamingTheFile) {
  Result<Mesh> result = internal::RunSandboxed("a.obj", 10, {}, [](const internal::StageReporter&) -> Result<Mesh> {
    return Failure(DiagnosticCode::kCannotReadFile, "no vertices");
  });
  EXPECT_EQ(result.message(), "a.obj: no vertices");
  EXPECT_EQ(result.error().code, DiagnosticCode::kCannotReadFile);
  result = internal::RunSandboxed("a.obj", 10, {}, [](const internal::StageReporter&) -> Result<Mesh> {
    throw std::bad_alloc();
  });
  EXPECT_NE(result.message().find("a.obj: out of memory"), std::string::npos) << result.message();
  // The code crosses the pipe with the message.
  EXPECT_EQ(result.error().code, DiagnosticCode::kOutOfMemory);
}

// 1 Mi vertices with normals (~36 MB through the pipe, far more than its buffer): the parent reads
// while the child writes, and gets every value back.
TEST(MeshSandbox, LargeMeshCrossesThePipeIntact) {
  constexpr std::size_t kVertices = std::size_t{1} << 20;
  Result<Mesh> result = internal::RunSandboxed("big", 10, {}, [](const internal::StageReporter& report) {
    report(LoadStage::kVs11);
    Mesh mesh;
    mesh.vertex_count = kVertices;
    for (std::size_t i = 0; i < kVertices; ++i) {
      const float x = static_cast<float>(i);
      mesh.positions.push_back({x, -x, 0.5f * x, 1.0f});
      mesh.normals.push_back({0.0f, 0.0f, 1.0f, 1.0f});
    }
    for (std::uint32_t i = 0; i + 2 < kVertices; i += 3) mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + 2});
    mesh.parts.push_back({"m", "n", IdentityMatrix(), true, false, 0, kVertices, 0, mesh.indices.size()});
    return mesh;
  });
  ASSERT_TRUE(result.ok()) << result.message();
  ASSERT_EQ(result->vertex_count, kVertices);
  ASSERT_EQ(result->positions.size(), kVertices);
  EXPECT_EQ(result->positions[kVertices - 1][1], -static_cast<float>(kVertices - 1));
  EXPECT_EQ(result->indices.back(), kVertices - 2);
  EXPECT_TRUE(result->tangents.empty());
}

Mesh LoadWuson() {
  Result<Mesh> result = LoadMesh(kWuson);
  EXPECT_TRUE(result.ok()) << result.message();
  return result.ok() ? *result : Mesh{};
}

std::span<const std::uint8_t> Bytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

TEST(MeshWire, RoundTripIsExact) {
  const Mesh mesh = LoadWuson();
  const std::string bytes = EncodeMesh(mesh);
  Result<Mesh> back = DecodeMesh(Bytes(bytes));
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back->positions, mesh.positions);
  EXPECT_EQ(back->normals, mesh.normals);
  EXPECT_EQ(back->texcoords, mesh.texcoords);
  EXPECT_EQ(back->texcoord_components, mesh.texcoord_components);
  EXPECT_EQ(back->indices, mesh.indices);
  EXPECT_EQ(back->warnings, mesh.warnings);
  ASSERT_EQ(back->parts.size(), mesh.parts.size());
  EXPECT_EQ(back->parts[0].transform, mesh.parts[0].transform);
  EXPECT_EQ(EncodeMesh(*back), bytes);
}

TEST(MeshWire, DamagedBytesAreRefused) {
  Mesh mesh = LoadWuson();
  const std::string bytes = EncodeMesh(mesh);
  EXPECT_EQ(DecodeMesh(Bytes(bytes.substr(0, bytes.size() - 1))).message(), "the data ends early");
  EXPECT_EQ(DecodeMesh(Bytes(bytes + "x")).error().code, DiagnosticCode::kMeshWire);
  EXPECT_EQ(DecodeMesh(Bytes(bytes + "x")).message(), "bytes after the mesh");
  std::string error;
  // A vertex count over the limit is refused from the count, before anything is allocated.
  std::string huge = bytes;
  const std::uint64_t too_many = kMaxMeshVertices + 1;
  std::memcpy(huge.data() + 12, &too_many, sizeof too_many);
  error = DecodeMesh(Bytes(huge)).message();
  EXPECT_NE(error.find("over the limit"), std::string::npos) << error;
  // An index past the vertices.
  mesh.indices[5] = static_cast<std::uint32_t>(mesh.vertex_count);
  error = DecodeMesh(Bytes(EncodeMesh(mesh))).message();
  EXPECT_NE(error.find("past the"), std::string::npos) << error;
}

TEST(MeshWire, ChildReplyNeedsAWholeRecord) {
  const std::string record = EncodeReplyRecord(LoadWuson());
  ChildReply reply = DecodeChildReply(Bytes("AVA" + record.substr(0, 20)));
  EXPECT_FALSE(reply.complete);
  EXPECT_EQ(reply.last_stage, 'A');
  reply = DecodeChildReply(Bytes("AV" + record));
  EXPECT_TRUE(reply.complete && reply.result.ok()) << reply.result.message();
  reply = DecodeChildReply(Bytes("AVQ" + record));
  EXPECT_TRUE(reply.malformed);
  EXPECT_EQ(reply.result.error().code, DiagnosticCode::kMeshWire);
}

TEST(MeshWire, AnErrorRecordKeepsItsCodeAndMessage) {
  const std::string record = EncodeReplyRecord(Failure(DiagnosticCode::kOutOfMemory, "out of memory"));
  ChildReply reply = DecodeChildReply(Bytes("A" + record));
  ASSERT_TRUE(reply.complete && !reply.malformed) << reply.result.message();
  EXPECT_EQ(reply.result.error().code, DiagnosticCode::kOutOfMemory);
  EXPECT_EQ(reply.result.message(), "out of memory");
  // A code no DiagnosticCode has is refused.
  std::string unknown = record;
  const std::uint32_t code = 100000;
  std::memcpy(unknown.data() + 9, &code, sizeof code);
  reply = DecodeChildReply(Bytes(unknown));
  EXPECT_TRUE(reply.malformed);
  EXPECT_NE(reply.result.message().find("an unknown error code 100000"), std::string::npos) << reply.result.message();
}

}  // namespace
}  // namespace vs11::mesh
