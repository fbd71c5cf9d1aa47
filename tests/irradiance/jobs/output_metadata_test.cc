// What every output that holds coefficients says about itself (irradiance/jobs/output_metadata.h):
// the input's size and SHA-256, the schema version that --resume checks, and the convention and
// provenance of coeffs.json and of irrmap batch's records, from which a record is made again.
#include "irradiance/jobs/output_metadata.h"

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/irrmap_job.h"
#include "vm/core/version.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputMetadata : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("vs11_metadata_{}_{}", getpid(), ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Path(const std::string& name) const { return dir_ / name; }

  static std::string ReadText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // A 16 x 8 lat-long map with a bright spot, written as a little-endian PFM.
  std::string WriteLatLong(const std::string& name) {
    std::string bytes = "PF\n16 8\n-1.0\n";
    for (int texel = 0; texel < 16 * 8; ++texel) {
      for (float value : texel == 35 ? std::array<float, 3>{40.0f, 30.0f, 20.0f} : std::array<float, 3>{0.25f, 0.5f, 0.75f}) {
        bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
      }
    }
    std::ofstream(Path(name), std::ios::binary) << bytes;
    return Path(name).string();
  }

  fs::path dir_;
};

TEST_F(OutputMetadata, AFileIsDigestedWithItsSizeAndSha256) {
  std::ofstream(Path("abc.txt"), std::ios::binary) << "abc";
  InputFileDigest digest;
  ASSERT_EQ(DigestInputFile(Path("abc.txt"), digest).message(), "");
  EXPECT_EQ(digest.size_bytes, 3u);
  EXPECT_EQ(digest.sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");  // FIPS 180-2's "abc"
  EXPECT_EQ(digest.path, Path("abc.txt").string());
  const Status missing = DigestInputFile(Path("gone.exr"), digest);
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.message(), HasSubstr("gone.exr"));
}

TEST(OutputSchema, OnlyThisVersionPassesAndOthersAreNamed) {
  EXPECT_EQ(OtherSchemaVersion({{"schema_version", kOutputSchemaVersion}}).message(), "");
  EXPECT_EQ(OtherSchemaVersion(nlohmann::json::object()).error().code, DiagnosticCode::kBatchRecord);
  EXPECT_THAT(OtherSchemaVersion(nlohmann::json::object()).message(), HasSubstr("schema version 1 (an older"));
  EXPECT_THAT(OtherSchemaVersion({{"schema_version", kOutputSchemaVersion + 1}}).message(),
              HasSubstr(fmt::format("schema version {} (a newer", kOutputSchemaVersion + 1)));
  EXPECT_THAT(OtherSchemaVersion({{"schema_version", "2"}}).message(), HasSubstr("not a positive integer"));
  EXPECT_THAT(OtherSchemaVersion({{"schema_version", 0}}).message(), HasSubstr("not a positive integer"));
}

TEST_F(OutputMetadata, CoeffsJsonSaysItsConventionAndProvenance) {
  IrrmapOptions options;
  options.environment = WriteLatLong("pano.pfm");
  options.face_size = 8;
  options.coefficients_only = true;
  options.out_dir = Path("out");
  IrrmapReport report;
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  const nlohmann::json json = nlohmann::json::parse(ReadText(Path("out") / "coeffs.json"));
  EXPECT_EQ(json["schema_version"], kOutputSchemaVersion);
  EXPECT_EQ(json["convention"]["quantity"], "radiance");
  EXPECT_EQ(json["convention"]["frame"], "direct3d_cube");
  EXPECT_EQ(json["convention"]["source_kind"], "latlong");  // the --sh-export frames' column
  const nlohmann::json& provenance = json["provenance"];
  EXPECT_EQ(provenance["vs11_version"], std::string(Vs11Version()));
  EXPECT_EQ(provenance["input_kind"], "latlong");
  ASSERT_EQ(provenance["files"].size(), 1u);
  InputFileDigest digest;
  ASSERT_EQ(DigestInputFile(options.environment, digest).message(), "");
  EXPECT_EQ(provenance["files"][0]["sha256"], digest.sha256);
  EXPECT_EQ(provenance["files"][0]["size_bytes"], digest.size_bytes);
  EXPECT_EQ(provenance["options"]["face_size"], 8);
  EXPECT_FALSE(provenance["options"].contains("level"));  // chosen by max_error

  options.environment = "sky";  // a built-in reads no file
  options.out_dir = Path("sky");
  ASSERT_EQ(RunIrrmap(options, report).message(), "");
  const nlohmann::json sky = nlohmann::json::parse(ReadText(Path("sky") / "coeffs.json"));
  EXPECT_EQ(sky["provenance"]["input_kind"], "builtin");
  EXPECT_EQ(sky["convention"]["source_kind"], "cube");
  EXPECT_TRUE(sky["provenance"]["files"].empty());
}

// A record lists every option that changes its numbers; irrmap's job run with them gives the same
// numbers, bit for bit.
TEST_F(OutputMetadata, ABatchRecordIsMadeAgainFromItsOwnMetadata) {
  const std::string cross = Path("sky.exr").string();
  ASSERT_EQ(WriteCrossExr(MakeSky(16), cross).message(), "");
  BatchOptions batch;
  batch.inputs = {cross, WriteLatLong("pano.pfm")};
  batch.output = Path("out.jsonl");
  batch.face_size = 8;
  batch.window = ShWindow::kLanczos;
  batch.window_width = 3.0;
  batch.max_error = 0.02;
  BatchSummary summary;
  ASSERT_EQ(RunBatch(batch, summary).message(), "");
  ASSERT_EQ(summary.succeeded, 2u);
  std::ifstream in(batch.output);
  std::string line;
  int records = 0;
  while (std::getline(in, line)) {
    const nlohmann::json record = nlohmann::json::parse(line);
    ++records;
    EXPECT_EQ(record["schema_version"], kOutputSchemaVersion);
    EXPECT_EQ(record["convention"]["window"], "lanczos");
    const nlohmann::json& provenance = record["provenance"];
    const nlohmann::json& listed = provenance["options"];
    EXPECT_EQ(provenance["input_kind"], record["layout"]);
    EXPECT_EQ(record["convention"]["source_kind"], record["layout"] == "latlong" ? "latlong" : "cube");
    IrrmapOptions again;
    again.environment = provenance["input"];
    again.layout = kLayoutNames.Parse(listed["layout"].get<std::string>());
    again.face_size = listed["face_size"];
    if (listed.contains("level")) again.level = listed["level"].get<int>();
    again.max_error = listed["max_error"];
    again.error_metric = kErrorMetricNames.Parse(listed["error_metric"].get<std::string>());
    again.order = kShOrderNames.Find(listed["order"].get<std::string>());  // "auto": nullopt
    again.window = kShWindowNames.Parse(listed["window"].get<std::string>());
    again.window_width = listed["window_width"];
    again.coefficients_only = true;
    again.write_files = false;
    IrrmapReport report;
    ASSERT_EQ(RunIrrmap(again, report).message(), "");
    EXPECT_EQ(record["level"], report.level);
    for (int i = 0; i < kSh9Coefficients; ++i) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(record["coefficients"][i][c].get<double>(), report.coefficients.coefficients[i][c]) << i << c;
      }
    }
    EXPECT_EQ(record["constants"]["cC"][0].get<float>(), report.constants.registers[6][0]);
  }
  EXPECT_EQ(records, 2);
}

TEST_F(OutputMetadata, ResumeRefusesRecordsOfAnotherSchemaVersionAndChangesNothing) {
  BatchOptions batch;
  batch.inputs = {WriteLatLong("a.pfm")};
  batch.output = Path("out.jsonl");
  batch.face_size = 8;
  BatchSummary summary;
  ASSERT_EQ(RunBatch(batch, summary).message(), "");
  const std::string written = ReadText(batch.output);
  const std::string current = fmt::format("\"schema_version\":{},", kOutputSchemaVersion);
  ASSERT_NE(written.find(current), std::string::npos);
  batch.inputs.push_back(WriteLatLong("b.pfm"));
  batch.resume = true;
  for (const std::string& other : {std::string(""), fmt::format("\"schema_version\":{},", kOutputSchemaVersion + 1)}) {
    std::string text = written;
    text.replace(text.find(current), current.size(), other);
    std::ofstream(batch.output, std::ios::binary) << text;
    const Status error = RunBatch(batch, summary);
    ASSERT_FALSE(error.ok()) << other;
    EXPECT_THAT(error.message(), HasSubstr(batch.output.string() + ":1: a record of schema version"));
    EXPECT_EQ(ReadText(batch.output), text);
  }
}

}  // namespace
}  // namespace vs11::irradiance
