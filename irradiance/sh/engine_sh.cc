#include "irradiance/sh/engine_sh.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace vs11::irradiance {
namespace {

struct FormatInfo {
  ShExportFormat format;
  std::string_view name;
  std::string_view file_name;
  bool mirrors_x;
};
constexpr std::array<FormatInfo, 6> kFormats = {{
    {ShExportFormat::kThree, "three", "sh_three.json", true},
    {ShExportFormat::kFilament, "filament", "sh_filament.txt", true},
    {ShExportFormat::kUnity, "unity", "sh_unity.json", false},
    {ShExportFormat::kGltf, "gltf", "sh_gltf.json", false},
    {ShExportFormat::kGlsl, "glsl", "sh_irradiance.glsl", false},
    {ShExportFormat::kHlsl, "hlsl", "sh_irradiance.hlsl", false},
}};

const FormatInfo& Info(ShExportFormat format) { return kFormats[static_cast<int>(format)]; }

// The sign each basis function takes when x changes sign: x, xy and xz are odd in x.
constexpr std::array<double, kSh9Coefficients> kMirrorXSign = {1, 1, 1, -1, -1, 1, 1, -1, 1};
// The Condon-Shortley phase (-1)^m on the real basis: the odd positive and negative m of bands 1, 2.
constexpr std::array<double, kSh9Coefficients> kCondonShortleySign = {1, -1, 1, -1, 1, -1, 1, -1, 1};
constexpr std::array<int, kSh9Coefficients> kBandOf = {0, 1, 1, 1, 2, 2, 2, 2, 2};
constexpr std::array<const char*, kSh9Coefficients> kCoefficientNames = {"L00", "L1-1", "L10", "L11", "L2-2",
                                                                         "L2-1", "L20", "L21", "L22"};
constexpr std::array<const char*, 7> kUnityNames = {"unity_SHAr", "unity_SHAg", "unity_SHAb", "unity_SHBr",
                                                    "unity_SHBg", "unity_SHBb", "unity_SHC"};
constexpr double kUnitySHCw = 1.0;  // what Unity stores in the unused w of SHC

// The coefficients as the engine's frame sees them.
Sh9Rgb InEngineFrame(ShExportFormat format, const Sh9Rgb& sh) { return MirrorsX(format) ? MirrorX(sh) : sh; }

nlohmann::ordered_json TriplesJson(const ShTriples& triples) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const glm::dvec3& c : triples) rows.push_back({c.r, c.g, c.b});
  return rows;
}

// A float as a shader literal: the shortest text that reads back as the same float, always with a
// decimal point or an exponent so that GLSL and HLSL read it as a float.
std::string ShaderLiteral(float value) {
  assert(std::isfinite(value));
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string CommentLines(std::string_view prefix, std::string_view text) {
  std::string out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    out += fmt::format("{}{}\n", prefix, text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

constexpr std::string_view kThreeConvention =
    "three.js SphericalHarmonics3 (LightProbe.sh): plain radiance coefficients L_lm, not irradiance: three.js's "
    "shGetIrradianceAt applies the cosine lobe (pi, 2pi/3, pi/4) itself, and the renderer then multiplies by "
    "albedo / pi. Real SH basis without the Condon-Shortley sign, order (0,0), (1,-1) y, (1,0) z, (1,1) x, "
    "(2,-2) xy, (2,-1) yz, (2,0) 3z^2-1, (2,1) xz, (2,2) x^2-y^2; the r, g, b of coefficient i at sh[3i..3i+2]. "
    "Frame: three.js's world, right-handed, +Y up, the environment as a THREE.CubeTexture of the same cube "
    "shows it (three.js mirrors cube textures in x): vs11's cube direction (x, y, z) is three.js's (-x, y, z). "
    "Load with new THREE.LightProbe().fromJSON(json), or new THREE.LightProbe(new "
    "THREE.SphericalHarmonics3().fromArray(json.sh)).";

constexpr std::string_view kFilamentConvention =
    "Filament IndirectLight::Builder::irradiance(3, sh), as cmgen --sh-shader prints it: the irradiance "
    "divided by pi, pre-scaled for Filament's shader, sh[i] = k_i L_lm with k = 0.282095, 0.325735 (x3), "
    "0.273137 (x2), 0.078848, 0.273137, 0.136569 (A_l |Y_lm| / pi). The shader computes max(0, sum sh[i] "
    "p_i(n)), p = 1, y, z, x, yx, yz, 3z^2-1, zx, x^2-y^2, and multiplies by the diffuse colour.\n"
    "Frame: Filament's world, right-handed, +Y up, with the environment mirrored in x as cmgen mirrors it by "
    "default: vs11's cube direction (x, y, z) is Filament's (-x, y, z). (cmgen --no-mirror would give "
    "sh[3], sh[4] and sh[7] with the opposite sign.)\n"
    "The nine lines below the comment are cmgen's format; Filament's samples read sh.txt from its first line, "
    "so drop the comment lines for them.";

constexpr std::string_view kUnityConvention =
    "Unity's ShadeSH9 constants: ShadeSH9(float4(n, 1)) = dot(unity_SHA[rgb], float4(n, 1)) + "
    "dot(unity_SHB[rgb], n.xyzz * n.yzzx) + unity_SHC.rgb * (n.x^2 - n.y^2) = E(n) / pi, the radiance a "
    "white Lambertian surface reflects. These seven vectors are vs11's seven constants (constants.vsh: the "
    "paper's Table 1 registers cAr cAg cAb cBr cBg cBb cC) divided by pi, in the same packing; only SHC.w "
    "differs (Unity stores 1, vs11's cC.w is unused). Frame: Unity's world, left-handed, +Y up, which is "
    "vs11's cube frame (Direct3D's) unchanged: a cube map irrmap read is the same cube map in Unity.";

constexpr std::string_view kGltfConvention =
    "glTF EXT_lights_image_based irradianceCoefficients: 9 x [r, g, b], the irradiance SH coefficients "
    "E_lm = A_l L_lm (A = pi, 2pi/3, pi/4) in the real basis with the Condon-Shortley sign, as Babylon.js "
    "(the extension's reference loader) reads them: E(n) = sum E_lm Y_lm(n) with Y = 0.282095, "
    "-0.488603 y, 0.488603 z, -0.488603 x, 1.092548 xy, -1.092548 yz, 0.315392 (3z^2-1), -1.092548 xz, "
    "0.546274 (x^2-y^2), order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2). Frame: the cube "
    "map's own, +Y up, in which Babylon.js evaluates them: at the very vector it samples the light's "
    "specularImages cube with (its reflection matrix, and z flipped in right-handed scenes, apply to both "
    "alike), so they agree with the cube irrmap read, or wrote, used as specularImages; vs11's cube direction "
    "(x, y, z) unchanged. Put the array in a light of "
    "\"extensions\": {\"EXT_lights_image_based\": {\"lights\": [...]}}.";

constexpr std::string_view kShaderConvention =
    "{function}: the irradiance E(n) of the nine SH terms (not divided by pi: multiply by albedo / pi for a "
    "Lambertian surface's radiance), as the paper's 11-instruction vs_1_1 program computes it, with vs11's "
    "seven constants (constants.vsh, Table 1) baked in. n: a unit normal in the cube map's own frame "
    "(Direct3D's and Vulkan's face table: left-handed, +Y up), so that vs11Irradiance(n) equals the lookup {lookup} "
    "of the irradiance.dds or irradiance.ktx2 irrmap writes; a right-handed engine that mirrors cube maps in "
    "x (three.js, Filament) passes {minus_x} instead of n.";

std::string JsonFile(std::string_view convention, std::string_view source, const char* key,
                     nlohmann::ordered_json value) {
  nlohmann::ordered_json json;
  json["convention"] = std::string(convention);
  json["source"] = std::string(source);
  json[key] = std::move(value);
  return json.dump(2) + "\n";
}

std::string ThreeText(const Sh9Rgb& sh, std::string_view source) {
  nlohmann::ordered_json flat = nlohmann::ordered_json::array();
  for (const glm::dvec3& c : ThreeJsCoefficients(sh)) flat.insert(flat.end(), {c.r, c.g, c.b});
  nlohmann::ordered_json json;
  json["convention"] = std::string(kThreeConvention);
  json["source"] = std::string(source);
  json["sh"] = std::move(flat);
  json["intensity"] = 1.0;
  return json.dump(2) + "\n";
}

std::string FilamentText(const Sh9Rgb& sh, std::string_view source) {
  std::string out = CommentLines("// ", kFilamentConvention) + CommentLines("// ", source);
  const ShTriples triples = FilamentIrradianceSh(sh);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    const glm::dvec3& c = triples[i];
    out += fmt::format("({:.9g}, {:.9g}, {:.9g}); // {}, irradiance, pre-scaled base\n", c.r, c.g, c.b,
                       kCoefficientNames[i]);
  }
  return out;
}

std::string UnityText(const Sh9Rgb& sh, std::string_view source) {
  nlohmann::ordered_json json;
  json["convention"] = std::string(kUnityConvention);
  json["source"] = std::string(source);
  const std::array<glm::dvec4, 7> vectors = UnityShConstants(sh);
  for (int i = 0; i < 7; ++i) json[kUnityNames[i]] = {vectors[i].x, vectors[i].y, vectors[i].z, vectors[i].w};
  return json.dump(2) + "\n";
}

// The shader function, in GLSL (vec3/vec4) or HLSL (float3/float4).
std::string ShaderText(const Sh9Rgb& sh, std::string_view source, bool hlsl) {
  const std::string_view vec3 = hlsl ? "float3" : "vec3";
  const std::string_view vec4 = hlsl ? "float4" : "vec4";
  const std::string function = fmt::format("{} vs11Irradiance({} n)", vec3, vec3);
  std::string out = CommentLines(
      "// ", fmt::format(fmt::runtime(kShaderConvention), fmt::arg("function", function),
                         fmt::arg("lookup", hlsl ? "TextureCube.Sample(sampler, n).rgb" : "texture(samplerCube, n).rgb"),
                         fmt::arg("minus_x", fmt::format("{}(-n.x, n.y, n.z)", vec3))));
  out += CommentLines("// ", source);
  out += function + " {\n";
  const SevenConstants constants = PackTable1(sh);
  for (int i = 0; i < 7; ++i) {
    const glm::vec4& r = constants.registers[i];
    out += fmt::format("  const {} {} = {}({}, {}, {}, {});\n", vec4, SevenConstants::kNames[i], vec4,
                       ShaderLiteral(r.x), ShaderLiteral(r.y), ShaderLiteral(r.z), ShaderLiteral(r.w));
  }
  out += fmt::format("  {} n1 = {}(n, 1.0);\n", vec4, vec4);
  out += fmt::format("  {} q = n.xyzz * n.yzzx;  // xy, yz, zz, zx\n", vec4);
  out += fmt::format("  return {}(dot(cAr, n1), dot(cAg, n1), dot(cAb, n1))\n", vec3);
  out += fmt::format("       + {}(dot(cBr, q), dot(cBg, q), dot(cBb, q))\n", vec3);
  out += "       + cC.rgb * (n.x * n.x - n.y * n.y);\n}\n";
  return out;
}

}  // namespace

std::string_view ShExportFormatName(ShExportFormat format) { return Info(format).name; }

std::optional<ShExportFormat> ParseShExportFormat(std::string_view name) {
  for (const FormatInfo& info : kFormats) {
    if (info.name == name) return info.format;
  }
  return std::nullopt;
}

std::string ShExportFormatNames() {
  std::string out;
  for (const FormatInfo& info : kFormats) out += fmt::format("{}{}", out.empty() ? "" : ", ", info.name);
  return out;
}

std::string_view ShExportFileName(ShExportFormat format) { return Info(format).file_name; }

bool MirrorsX(ShExportFormat format) { return Info(format).mirrors_x; }

glm::dvec3 EngineDirection(ShExportFormat format, glm::dvec3 d) {
  return MirrorsX(format) ? glm::dvec3(-d.x, d.y, d.z) : d;
}

Sh9Rgb MirrorX(const Sh9Rgb& sh) {
  Sh9Rgb mirrored;
  for (int i = 0; i < kSh9Coefficients; ++i) mirrored.coefficients[i] = kMirrorXSign[i] * sh.coefficients[i];
  return mirrored;
}

ShTriples ThreeJsCoefficients(const Sh9Rgb& sh) { return InEngineFrame(ShExportFormat::kThree, sh).coefficients; }

ShTriples FilamentIrradianceSh(const Sh9Rgb& sh) {
  ShTriples out = InEngineFrame(ShExportFormat::kFilament, sh).coefficients;
  for (int i = 0; i < kSh9Coefficients; ++i) out[i] *= kEnginePreScale[i];
  return out;
}

ShTriples GltfIrradianceCoefficients(const Sh9Rgb& sh) {
  ShTriples out = InEngineFrame(ShExportFormat::kGltf, sh).coefficients;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    out[i] *= kShBandFactor[kBandOf[i]] * kCondonShortleySign[i];
  }
  return out;
}

std::array<glm::dvec4, 7> UnityShConstants(const Sh9Rgb& sh) {
  const SevenConstants constants = PackTable1(sh);
  std::array<glm::dvec4, 7> out;
  for (int i = 0; i < 7; ++i) out[i] = glm::dvec4(constants.registers[i]) / std::numbers::pi;
  out[SevenConstants::kC].w = kUnitySHCw;
  return out;
}

std::string ShExportText(ShExportFormat format, const Sh9Rgb& sh, std::string_view source) {
  switch (format) {
    case ShExportFormat::kThree: return ThreeText(sh, source);
    case ShExportFormat::kFilament: return FilamentText(sh, source);
    case ShExportFormat::kUnity: return UnityText(sh, source);
    case ShExportFormat::kGltf:
      return JsonFile(kGltfConvention, source, "irradianceCoefficients", TriplesJson(GltfIrradianceCoefficients(sh)));
    case ShExportFormat::kGlsl: return ShaderText(sh, source, false);
    case ShExportFormat::kHlsl: return ShaderText(sh, source, true);
  }
  return {};
}

}  // namespace vs11::irradiance
