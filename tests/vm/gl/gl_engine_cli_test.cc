// `--engine gl` and `--gl-device` through the tools: the same outputs as the CPU engines, the devices
// listed, and a clear error with exit status 1 (never a crash) where EGL has no driver or no such
// device. In ctest's vs11_tests.llvmpipe entry (tests/CMakeLists.txt).
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/jobs/irrmap_job.h"
#include "tests/run_tool.h"
#include "vm/gl/gl_engine.h"

namespace vs11 {
namespace {

using ::testing::HasSubstr;
using testing::RunIrrmap;
using testing::RunVs11;

const std::string kSource = VS11_SOURCE_DIR;

// Sets an environment variable for the tools a test starts, and restores it after.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnvironment() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// glvnd's libEGL loads the vendor libraries this variable names instead of the installed ones: a file
// that does not exist leaves EGL with no driver at all, as on a machine without Mesa's libegl-mesa0.
constexpr const char* kNoEglDriver = "__EGL_VENDOR_LIBRARY_FILENAMES";

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class GlEngineCliTest : public testing::ToolFolderTest {
 protected:
  // The paper's program over 64 sphere normals with its seven constants set.
  std::string Sh9Run(const std::string& engine_flags) {
    const std::string consts = Write("constants.vsh",
                                     "c0 = 0.5 0.25 0.125 1\nc1 = -0.3 0.2 0.1 0\nc2 = 0.7 -0.1 0.4 0\n"
                                     "c3 = 0.05 0.02 -0.03 0\nc4 = 0.1 0.2 0.3 0\nc5 = -0.2 0.1 0.05 0\n"
                                     "c6 = 0.3 0.3 0.3 0\n");
    return "run " + kSource + "/programs/sh9_irradiance.vsh --fragment --consts " + consts +
           " --sphere 64 --sphere-reg v0 " + engine_flags;
  }
};

TEST_F(GlEngineCliTest, RunWritesTheReferenceEnginesCsv) {
  const testing::CommandResult gl = RunVs11(Sh9Run("--engine gl --out " + (dir_ / "gl.csv").string()));
  ASSERT_EQ(gl.status, 0) << gl.output;
  const testing::CommandResult ref = RunVs11(Sh9Run("--engine ref --out " + (dir_ / "ref.csv").string()));
  ASSERT_EQ(ref.status, 0) << ref.output;
  const std::string csv = ReadFile(dir_ / "gl.csv");
  EXPECT_GT(csv.size(), 64u * 10u);
  EXPECT_EQ(csv, ReadFile(dir_ / "ref.csv"));
}

// Both paths write the reference's CSV and say which ran; ES 3.1 (llvmpipe's 3.2) picks compute, an
// ES 3.0 context (Mesa's MESA_GLES_VERSION_OVERRIDE) transform feedback, and --gl-path compute there
// is the engine's error, exit 1.
TEST_F(GlEngineCliTest, GlPathSaysWhichRanAndForcesEither) {
  const testing::CommandResult ref = RunVs11(Sh9Run("--engine ref --out " + (dir_ / "ref.csv").string()));
  ASSERT_EQ(ref.status, 0) << ref.output;
  for (const char* path : {"auto", "compute", "transform-feedback"}) {
    const std::string csv = (dir_ / (std::string(path) + ".csv")).string();
    const testing::CommandResult run = RunVs11(Sh9Run(std::string("--engine gl --gl-path ") + path + " --out " + csv));
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string ran = std::string(path) == "auto" ? "compute" : path;
    EXPECT_THAT(run.output, HasSubstr("note: --engine gl runs the " + ran + " path")) << path;
    EXPECT_EQ(ReadFile(csv), ReadFile(dir_ / "ref.csv")) << path;
  }
  ScopedEnvironment es30("MESA_GLES_VERSION_OVERRIDE", "3.0");
  const testing::CommandResult automatic = RunVs11(Sh9Run("--engine gl --out " + (dir_ / "es30.csv").string()));
  ASSERT_EQ(automatic.status, 0) << automatic.output;
  EXPECT_THAT(automatic.output, HasSubstr("note: --engine gl runs the transform-feedback path"));
  EXPECT_EQ(ReadFile(dir_ / "es30.csv"), ReadFile(dir_ / "ref.csv"));
  const testing::CommandResult forced = RunVs11(Sh9Run("--engine gl --gl-path compute --out " + (dir_ / "x.csv").string()));
  EXPECT_EQ(forced.status, 1) << forced.output;
  EXPECT_THAT(forced.output, HasSubstr("--gl-path compute needs OpenGL ES 3.1"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.csv"));
  const testing::CommandResult word = RunVs11(Sh9Run("--engine gl --gl-path vertex"));
  EXPECT_EQ(word.status, 2) << word.output;
}

TEST_F(GlEngineCliTest, VerifyComparesItLikeTheOtherEngines) {
  const testing::CommandResult against = RunVs11("verify " + kSource + "/programs/skinning.vsh --engine gl --against-engine ref");
  EXPECT_EQ(against.status, 0) << against.output;
  EXPECT_THAT(against.output, HasSubstr("engines gl and ref"));
  EXPECT_THAT(against.output, HasSubstr("IDENTICAL"));
  const testing::CommandResult reference = RunVs11("verify " + kSource + "/programs/sh9_irradiance.vsh --engine gl");
  EXPECT_EQ(reference.status, 0) << reference.output;
  EXPECT_THAT(reference.output, HasSubstr("PASS"));
}

TEST_F(GlEngineCliTest, DeviceListNamesLlvmpipe) {
  const testing::CommandResult list = RunVs11("run " + kSource + "/programs/fog.vsh --gl-device list");
  EXPECT_EQ(list.status, 0) << list.output;
  EXPECT_THAT(list.output, HasSubstr("llvmpipe"));
  EXPECT_THAT(list.output, HasSubstr("0: "));
}

TEST_F(GlEngineCliTest, ADeviceEglDoesNotListIsAnError) {
  const testing::CommandResult run = RunVs11(Sh9Run("--engine gl --gl-device 99"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_THAT(run.output, HasSubstr("error: the gl engine has no OpenGL ES 3.0 device: no EGL device 99"));
  const testing::CommandResult word = RunVs11(Sh9Run("--engine gl --gl-device first"));
  EXPECT_EQ(word.status, 2) << word.output;  // a usage error
}

TEST_F(GlEngineCliTest, WithoutAnEglDriverEveryCommandSaysSoAndExits1) {
  ScopedEnvironment no_driver(kNoEglDriver, "/nonexistent/vs11_no_egl_vendor.json");
  const std::string program = kSource + "/programs/skinning.vsh";
  for (const std::string& args : {Sh9Run("--engine gl"), "verify " + program + " --engine gl",
                                  "verify " + program + " --against-engine gl", "run " + program + " --gl-device list"}) {
    const testing::CommandResult result = RunVs11(args);
    EXPECT_EQ(result.status, 1) << args << "\n" << result.output;
    EXPECT_THAT(result.output, HasSubstr("error: ")) << args;
    EXPECT_THAT(result.output, HasSubstr("EGL")) << args;
  }
  const testing::CommandResult irrmap =
      RunIrrmap("gradient --face-size 16 --engine gl --no-ground-truth --out " + (dir_ / "out").string());
  EXPECT_EQ(irrmap.status, 1) << irrmap.output;
  EXPECT_THAT(irrmap.output, HasSubstr("irrmap: error: --engine gl: the gl engine has no OpenGL ES 3.0 device"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "irradiance.exr"));
}

// irrmap's irradiance map evaluated by the gl engine holds the jit's values, bit for bit.
TEST(GlEngineIrrmap, IrradianceMapEqualsTheJitsOnLlvmpipe) {
  gl::RegisterGlEngine();
  irradiance::CubeMap maps[2];
  const char* engines[2] = {"jit", "gl"};
  for (int i = 0; i < 2; ++i) {
    irradiance::IrrmapOptions options;
    options.environment = "spot";
    options.face_size = 16;
    options.map_size = 16;
    options.no_ground_truth = true;
    options.write_files = false;
    options.threads = 1;
    options.engine = engines[i];
    irradiance::IrrmapReport report;
    ASSERT_EQ(irradiance::RunIrrmap(options, report, {}).message(), "") << engines[i];
    maps[i] = report.irradiance_map;
  }
  ASSERT_EQ(maps[0].faces.size(), 6u);
  for (std::size_t f = 0; f < 6; ++f) {
    ASSERT_EQ(maps[1].faces[f].pixels.size(), 16u * 16u);
    for (std::size_t p = 0; p < maps[0].faces[f].pixels.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(std::bit_cast<std::uint32_t>(maps[1].faces[f].pixels[p][c]),
                  std::bit_cast<std::uint32_t>(maps[0].faces[f].pixels[p][c]))
            << "face " << f << " texel " << p << " channel " << c;
      }
    }
  }
}

}  // namespace
}  // namespace vs11
