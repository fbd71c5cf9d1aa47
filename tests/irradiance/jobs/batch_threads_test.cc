// `irrmap batch` on several threads (irradiance/jobs/batch_job.h): inputs of several formats and
// face sizes processed at once, sharing the job's basis pyramids, must give every record of a
// one-thread run, bit for bit (the JSON holds each double exactly). CI's ThreadSanitizer stage
// (.ci/tsan) runs this.
//
// BC6H DDS files are not among the inputs: OpenImageIO 2.4 decodes them wrongly on several threads
// at once (issue #18, section 1), which the concurrent-read tests of the environment loader cover.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using envtest::TempFolderTest;

// Lat-long maps are resampled to this; the cube inputs keep their own face sizes.
constexpr int kResampledFace = 16;

class BatchJobThreads : public TempFolderTest {
 protected:
  // Inputs in seven formats, faces of 8 to 64 texels, each environment different.
  std::vector<std::string> WriteInputs() {
    std::vector<std::string> inputs;
    auto add = [&](const std::string& name) { inputs.push_back(Path(name).string()); };
    auto sky = [](int face, double azimuth) {
      SkyParams params;
      params.sun_azimuth_degrees = azimuth;
      return MakeSky(face, params);
    };
    EXPECT_EQ(WriteCrossExr(sky(16, 10.0), Path("sky16.exr")).message(), "");
    add("sky16.exr");
    EXPECT_EQ(WriteCrossExr(sky(64, 100.0), Path("sky64.exr")).message(), "");
    add("sky64.exr");
    EXPECT_EQ(WriteCubeMap(MakeStudio(32), Path("studio32.hdr"), EnvironmentLayout::kVerticalCross).message(), "");
    add("studio32.hdr");
    EXPECT_EQ(WriteImage(CubeMapToImage(MakeSpot(32), EnvironmentLayout::kLatLong), Path("spot_latlong.tif")).message(),
              "");
    add("spot_latlong.tif");
    // (Not an angular map: auto refuses a square image, and one batch has one --layout.)
    EXPECT_EQ(WriteImage(CubeMapToImage(sky(16, 250.0), EnvironmentLayout::kHorizontalStrip), Path("sky_strip.exr"))
                  .message(),
              "");
    add("sky_strip.exr");
    EXPECT_EQ(WriteImage(CubeMapToImage(MakeGradient(8), EnvironmentLayout::kHorizontalCross), Path("gradient8.png"))
                  .message(),
              "");
    add("gradient8.png");
    envtest::WritePfm(Path("studio16.pfm"), CubeMapToImage(MakeStudio(16), EnvironmentLayout::kHorizontalCross));
    add("studio16.pfm");
    const std::vector<CubeFace> all_faces(kAllCubeFaces.begin(), kAllCubeFaces.end());
    envtest::WriteBytes(Path("cube8bit.dds"), envtest::Dds8BitCube(16, all_faces, envtest::DdsTestBytes));
    add("cube8bit.dds");
    envtest::WriteBytes(Path("cube_float.dds"), FloatDdsCube(sky(8, 300.0)));
    add("cube_float.dds");
    return inputs;
  }

  // A legacy A32B32G32R32F cube map (read by irradiance/io/dds_reader.h, not OpenImageIO).
  static std::string FloatDdsCube(const CubeMap& cube) {
    std::uint32_t caps2 = envtest::kDdsCaps2Cubemap;
    for (std::uint32_t face_flag : envtest::kDdsCaps2Face) caps2 |= face_flag;
    const envtest::DdsPixelFormat format = {envtest::kDdpfFourCc, envtest::kD3dFmtA32B32G32R32F, 0, {0, 0, 0, 0}};
    constexpr int kBytesPerTexel = 16;
    std::string bytes = envtest::DdsHeader(cube.face_size, caps2, format, cube.face_size * kBytesPerTexel);
    for (CubeFace face : kAllCubeFaces) {
      for (const glm::vec3& texel : cube.face(face).pixels) {
        for (int c = 0; c < 3; ++c) envtest::Append(bytes, texel[c]);
        envtest::Append(bytes, 1.0f);
      }
    }
    return bytes;
  }

  // The records of a run at `threads`, by input.
  std::map<std::string, std::string> Run(const std::vector<std::string>& inputs, int threads) {
    BatchOptions options;
    options.inputs = inputs;
    options.output = Path("out" + std::to_string(threads) + ".jsonl");
    options.threads = threads;
    options.face_size = kResampledFace;
    BatchSummary summary;
    EXPECT_EQ(RunBatch(options, summary).message(), "");
    for (const BatchFailure& failure : summary.failures) ADD_FAILURE() << failure.input << ": " << failure.reason;
    EXPECT_EQ(summary.succeeded, inputs.size()) << threads << " threads";
    std::map<std::string, std::string> records;
    std::ifstream in(options.output);
    for (std::string line; std::getline(in, line);) {
      const nlohmann::ordered_json record = nlohmann::ordered_json::parse(line);
      EXPECT_EQ(records.count(record["input"]), 0u) << record["input"] << " twice";
      records[record["input"]] = line;
    }
    return records;
  }
};

TEST_F(BatchJobThreads, EveryThreadCountWritesTheRecordsOfOneThread) {
  const std::vector<std::string> inputs = WriteInputs();
  const std::map<std::string, std::string> one = Run(inputs, 1);
  ASSERT_EQ(one.size(), inputs.size());
  // Face sizes 8 to 64 among the records, so that several basis pyramids are built at once.
  std::set<int> face_sizes;
  for (const auto& [input, line] : one) face_sizes.insert(nlohmann::json::parse(line)["face_size"].get<int>());
  EXPECT_EQ(face_sizes, (std::set<int>{8, 16, 32, 64}));
  for (int threads : {2, 4, 8}) {
    const std::map<std::string, std::string> many = Run(inputs, threads);
    ASSERT_EQ(many.size(), one.size()) << threads << " threads";
    for (const auto& [input, line] : one) {
      const auto found = many.find(input);
      ASSERT_NE(found, many.end()) << input << " missing at " << threads << " threads";
      EXPECT_EQ(found->second, line) << input << " at " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace vs11::irradiance
