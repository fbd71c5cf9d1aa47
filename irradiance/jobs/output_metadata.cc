// The metadata of vs11's outputs. See output_metadata.h.
#include "irradiance/jobs/output_metadata.h"

#include <openssl/evp.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/irrmap_job.h"
#include "vm/core/version.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kDigestChunkBytes = 1 << 20;

std::string Replaced(std::string text, std::string_view token, std::string_view by) {
  for (std::size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + by.size())) {
    text.replace(at, token.size(), by);
  }
  return text;
}

nlohmann::ordered_json ConventionJson(ShSourceKind kind, std::string_view window) {
  return {
      {"quantity", "radiance"},
      {"basis",
       "real spherical harmonics, bands l <= 2, of Ramamoorthi & Hanrahan 2001 (Ai, Peng & Zhang 2008 eq. 5), "
       "without the Condon-Shortley phase: y00 = 0.282095, y1-1 = 0.488603 y, y10 = 0.488603 z, y11 = 0.488603 x, "
       "y2-2 = 1.092548 xy, y2-1 = 1.092548 yz, y20 = 0.315392 (3z^2 - 1), y21 = 1.092548 xz, "
       "y22 = 0.546274 (x^2 - y^2)"},
      {"coefficient_order", {"L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"}},
      {"channels", {"r", "g", "b"}},
      {"frame", "direct3d_cube"},
      {"frame_description",
       "left-handed, +y up, +z forward, +x right looking at +z from inside (the +y face and a lat-long image's "
       "top row are up; a lat-long image's centre looks at +z, three quarters across at +x)"},
      {"source_kind", std::string(ShSourceKindName(kind))},
      {"units",
       "the input's linear pixel values times steradians: L_lm is the integral of L y_lm over the sphere, "
       "with no exposure, no 1/pi and no clamped-cosine factor"},
      {"scale", 1.0},
      {"window", std::string(window)},
      {"constants",
       "Table 1 of Ai, Peng & Zhang 2008 (cAr cAg cAb cBr cBg cBb cC), float32: irradiance E(n) = "
       "sum of A_l L_lm y_lm(n), A = (pi, 2 pi / 3, pi / 4)"}};
}

}  // namespace

Status DigestInputFile(const fs::path& path, InputFileDigest& digest) {
  const auto fail = [&path](std::string_view why) {
    return Failure(DiagnosticCode::kCannotReadFile, fmt::format("{}: {}", path.string(), why));
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(fmt::format("cannot be read to hash it ({})", std::strerror(errno)));
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) {
    return fail("OpenSSL's SHA-256 is not available");
  }
  std::vector<char> chunk(kDigestChunkBytes);
  std::uintmax_t size = 0;
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const std::streamsize got = in.gcount();
    if (got > 0 && EVP_DigestUpdate(context.get(), chunk.data(), static_cast<std::size_t>(got)) != 1) {
      return fail("hashing failed");
    }
    size += static_cast<std::uintmax_t>(got);
  }
  if (in.bad()) return fail("cannot be read to hash it");
  std::array<unsigned char, EVP_MAX_MD_SIZE> bytes{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(context.get(), bytes.data(), &length) != 1) return fail("hashing failed");
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  digest.path = (ec ? path : absolute.lexically_normal()).string();
  digest.size_bytes = size;
  digest.sha256.clear();
  for (unsigned int i = 0; i < length; ++i) digest.sha256 += fmt::format("{:02x}", bytes[i]);
  return {};
}

std::vector<fs::path> EnvironmentFiles(const std::string& environment) {
  if (environment.find(kFaceToken) == std::string::npos) return {environment};
  std::vector<fs::path> files;
  for (int face = 0; face < kCubeFaceCount; ++face) {
    const std::string short_name = Replaced(environment, kFaceToken, kFaceFileNames[face]);
    std::error_code ec;
    files.emplace_back(fs::exists(short_name, ec) ? short_name
                                                  : Replaced(environment, kFaceToken, kSignedFaceFileNames[face]));
  }
  return files;
}

std::string_view ShSourceKindName(ShSourceKind kind) { return kind == ShSourceKind::kLatLong ? "latlong" : "cube"; }

nlohmann::ordered_json OutputMetadata(const IrrmapReport& report, const IrrmapOptions& options) {
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const InputFileDigest& file : report.input_files) {
    files.push_back({{"path", file.path}, {"size_bytes", file.size_bytes}, {"sha256", file.sha256}});
  }
  // No null for an unset level: a null in vs11's JSON means a figure that was not finite.
  nlohmann::ordered_json numbers = {{"layout", std::string(LayoutName(options.layout))}, {"face_size", options.face_size}};
  if (options.level) numbers["level"] = *options.level;
  numbers.update({{"max_error", options.max_error},
                  {"error_metric", std::string(ErrorMetricName(options.error_metric))},
                  {"order", std::string(options.order ? ShOrderName(*options.order) : kAutoOrderName)},
                  {"window", std::string(ShWindowName(options.window))},
                  {"window_width", options.window_width}});
  return {{"schema_version", kOutputSchemaVersion},
          {"convention", ConventionJson(report.sh_source, ShWindowName(options.window))},
          {"provenance",
           {{"vs11_version", std::string(Vs11Version())},
            {"input", report.environment},
            {"input_kind", report.layout},
            {"files", std::move(files)},
            {"options", std::move(numbers)}}}};
}

std::optional<int> OutputSchemaVersion(const nlohmann::json& output) {
  if (!output.is_object() || !output.contains("schema_version")) return 1;
  const nlohmann::json& version = output["schema_version"];
  if (!version.is_number_integer() || version.get<long long>() < 1 || version.get<long long>() > 1000000) {
    return std::nullopt;
  }
  return version.get<int>();
}

Status OtherSchemaVersion(const nlohmann::json& record) {
  const std::optional<int> version = OutputSchemaVersion(record);
  if (!version) return Failure(DiagnosticCode::kBatchRecord, "a \"schema_version\" that is not a positive integer");
  if (*version == kOutputSchemaVersion) return {};
  return Failure(DiagnosticCode::kBatchRecord,
                 fmt::format("a record of schema version {} ({} vs11's; this vs11 {} writes version {})", *version,
                             *version < kOutputSchemaVersion ? "an older" : "a newer", Vs11Version(),
                             kOutputSchemaVersion));
}

}  // namespace vs11::irradiance
