#include "irradiance/sh/engine_sh.h"

#include <cassert>
#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace vs11::irradiance {
namespace {

struct FormatInfo {
  ShExportFormat format;
  std::string_view file_name;
  // The engine's world, for the convention text.
  std::string_view world;
  // AssumedView and OtherView, indexed by ShSourceKind (kCube, kLatLong); other may be nullptr.
  std::array<const EngineView*, 2> assumed;
  std::array<const EngineView*, 2> other;
};

constexpr SignedAxes kUnchanged = {{0, 1, 2}, {1, 1, 1}};
constexpr SignedAxes kMirroredInX = {{0, 1, 2}, {-1, 1, 1}};

constexpr EngineView kThreeEquirect = {
    "equirect",
    "an equirectangular texture (scene.background or scene.environment with "
    "THREE.EquirectangularReflectionMapping, PMREMGenerator.fromEquirectangular, "
    "WebGLCubeRenderTarget.fromEquirectangularTexture: all through equirectUv, u = atan2(z, x) / 2pi + 0.5, "
    "v = asin(y) / pi + 0.5, so the image centre is three.js's +X and three quarters across is +Z): vs11's "
    "direction (x, y, z) is three.js's (z, y, x)",
    {{2, 1, 0}, {1, 1, 1}}};
constexpr EngineView kThreeCubeTexture = {
    "cube_texture",
    "a THREE.CubeTexture of six faces in the Direct3D/OpenGL face table (CubeTextureLoader; a cube map file, "
    "or a panorama turned into faces by irrmap, cmgen or Babylon.js), which three.js samples at (-x, y, z): "
    "vs11's direction (x, y, z) is three.js's (-x, y, z)",
    kMirroredInX};
constexpr EngineView kThreeCubeRenderTarget = {
    "cube_render_target",
    "the same six faces in a WebGLCubeRenderTarget (LightProbeGenerator.fromCubeRenderTarget), which three.js "
    "samples without the mirror: vs11's direction (x, y, z) is three.js's (x, y, z)",
    kUnchanged};
constexpr EngineView kFilamentCmgen = {
    "cmgen",
    "the cube cmgen makes (of a lat-long image through its equirectangularToCubemap, which gives the same cube "
    "vs11 makes), mirrored in x as cmgen does by default: vs11's direction (x, y, z) is Filament's (-x, y, z)",
    kMirroredInX};
constexpr EngineView kFilamentNoMirror = {
    "cmgen_no_mirror",
    "the cube of cmgen --no-mirror: vs11's direction (x, y, z) is Filament's (x, y, z), so sh[3], sh[4] and "
    "sh[7] change sign",
    kUnchanged};
constexpr EngineView kUnityPanoramic = {
    "panoramic",
    "the Skybox/Panoramic shader's lat-long mapping (ToRadialCoords: u = 0.5 - atan2(z, x) / 2pi, "
    "v = 1 - acos(y) / pi, so the image centre is Unity's +X and a quarter across is +Z; a Cubemap imported "
    "with the Latitude-Longitude mapping is taken to match it, the importer's source not being public): vs11's "
    "direction (x, y, z) is Unity's (z, y, -x)",
    {{2, 1, 0}, {1, 1, -1}}};
constexpr EngineView kUnityCubemap = {
    "cubemap",
    "a Cubemap of six faces in the Direct3D face table (a cube map file, or a panorama turned into faces by "
    "irrmap, cmgen or Babylon.js), sampled with the world direction as it is (Unity is left-handed like "
    "Direct3D): vs11's direction (x, y, z) is Unity's (x, y, z)",
    kUnchanged};
constexpr EngineView kGltfCube = {
    "cube",
    "the cube map's own frame, in which Babylon.js (the extension's reference loader) evaluates the "
    "coefficients: at the very vector it samples the light's specularImages cube with (its reflection matrix, "
    "and z flipped in right-handed scenes, apply to both alike); the cube Babylon.js makes of a panorama "
    "(HDRCubeTexture, PanoramaToCubeMapTools) is the one vs11 makes: vs11's direction (x, y, z) unchanged",
    kUnchanged};
constexpr EngineView kShaderCube = {
    "cube",
    "the direction of a cube map lookup of the irradiance.dds or irradiance.ktx2 irrmap writes (Direct3D's "
    "and Vulkan's face table: left-handed, +Y up), which for a panorama is the direction vs11's lat-long "
    "convention gives its pixels (image centre +Z, three quarters across +X): vs11's direction unchanged",
    kUnchanged};

constexpr std::array<FormatInfo, 6> kFormats = {{
    {ShExportFormat::kThree, "sh_three.json", "three.js's world, right-handed, +Y up",
     {&kThreeCubeTexture, &kThreeEquirect}, {&kThreeCubeRenderTarget, &kThreeCubeTexture}},
    {ShExportFormat::kFilament, "sh_filament.txt", "Filament's world, right-handed, +Y up",
     {&kFilamentCmgen, &kFilamentCmgen}, {&kFilamentNoMirror, &kFilamentNoMirror}},
    {ShExportFormat::kUnity, "sh_unity.json", "Unity's world, left-handed, +Y up",
     {&kUnityCubemap, &kUnityPanoramic}, {nullptr, &kUnityCubemap}},
    {ShExportFormat::kGltf, "sh_gltf.json", "glTF's world, +Y up", {&kGltfCube, &kGltfCube},
     {nullptr, nullptr}},
    {ShExportFormat::kGlsl, "sh_irradiance.glsl", "the cube map's own, +Y up", {&kShaderCube, &kShaderCube},
     {nullptr, nullptr}},
    {ShExportFormat::kHlsl, "sh_irradiance.hlsl", "the cube map's own, +Y up", {&kShaderCube, &kShaderCube},
     {nullptr, nullptr}},
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

int KindIndex(ShSourceKind kind) { return kind == ShSourceKind::kLatLong ? 1 : 0; }

// "Frame: WORLD, the lat-long panorama shown as VIEW. Shown instead as OTHER, ...": the convention
// text's frame sentence for `format` and `kind`.
std::string FrameSentence(ShExportFormat format, ShSourceKind kind, std::string_view other_where) {
  const EngineView& view = AssumedView(format, kind);
  std::string text = fmt::format("Frame: {}, with the {} shown as {}.", Info(format).world,
                                 kind == ShSourceKind::kLatLong ? "lat-long panorama irrmap read" : "cube map irrmap read",
                                 view.description);
  if (const EngineView* other = OtherView(format, kind)) {
    text += fmt::format(" Shown instead as {}: {}.", other->description, other_where);
  }
  return text;
}

constexpr std::string_view kOtherViewInJson = "the numbers for that are under \"other_view\"";

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
    "{frame} Load with new THREE.LightProbe(new THREE.SphericalHarmonics3().fromArray(json.sh), "
    "json.intensity).";

constexpr std::string_view kFilamentConvention =
    "Filament IndirectLight::Builder::irradiance(3, sh), as cmgen --sh-shader prints it: the irradiance "
    "divided by pi, pre-scaled for Filament's shader, sh[i] = k_i L_lm with k = 0.282095, 0.325735 (x3), "
    "0.273137 (x2), 0.078848, 0.273137, 0.136569 (A_l |Y_lm| / pi). The shader computes max(0, sum sh[i] "
    "p_i(n)), p = 1, y, z, x, yx, yz, 3z^2-1, zx, x^2-y^2, and multiplies by the diffuse colour.\n"
    "{frame}\n"
    "The nine lines below the comment are cmgen's format; Filament's samples read sh.txt from its first line, "
    "so drop the comment lines for them.";

constexpr std::string_view kUnityConvention =
    "Unity's ShadeSH9 constants: ShadeSH9(float4(n, 1)) = dot(unity_SHA[rgb], float4(n, 1)) + "
    "dot(unity_SHB[rgb], n.xyzz * n.yzzx) + unity_SHC.rgb * (n.x^2 - n.y^2) = E(n) / pi, the radiance a "
    "white Lambertian surface reflects. These seven vectors are the paper's Table 1 registers (cAr cAg cAb "
    "cBr cBg cBb cC, as in constants.vsh) of the coefficients in Unity's frame, divided by pi, in the same "
    "packing (for a cube map Unity's frame is vs11's, so they are constants.vsh's over pi); only SHC.w "
    "differs (Unity stores 1, vs11's cC.w is unused). {frame}";

constexpr std::string_view kGltfConvention =
    "glTF EXT_lights_image_based irradianceCoefficients: 9 x [r, g, b], the irradiance SH coefficients "
    "E_lm = A_l L_lm (A = pi, 2pi/3, pi/4) in the real basis with the Condon-Shortley sign, as Babylon.js "
    "(the extension's reference loader) reads them: E(n) = sum E_lm Y_lm(n) with Y = 0.282095, "
    "-0.488603 y, 0.488603 z, -0.488603 x, 1.092548 xy, -1.092548 yz, 0.315392 (3z^2-1), -1.092548 xz, "
    "0.546274 (x^2-y^2), order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2). {frame} They "
    "agree with the cube irrmap read, or wrote, used as specularImages. Put the array in a light of "
    "\"extensions\": {{\"EXT_lights_image_based\": {{\"lights\": [...]}}}}.";

constexpr std::string_view kShaderConvention =
    "{function}: the irradiance E(n) of the nine SH terms (not divided by pi: multiply by albedo / pi for a "
    "Lambertian surface's radiance), as the paper's 11-instruction vs_1_1 program computes it, with vs11's "
    "seven constants (constants.vsh, Table 1) baked in. n: a unit normal. {frame} So vs11Irradiance(n) equals "
    "the lookup {lookup}; a right-handed engine that mirrors cube maps in x (three.js's CubeTexture, Filament) "
    "passes {minus_x} instead of n, and three.js showing the panorama as an equirectangular texture passes "
    "{swap_xz}.";

std::string ConventionText(std::string_view convention, ShExportFormat format, ShSourceKind kind,
                           std::string_view other_where) {
  return fmt::format(fmt::runtime(convention), fmt::arg("frame", FrameSentence(format, kind, other_where)));
}

// A JSON export: "convention", "source", "view", the numbers of the assumed view (`numbers`), then
// "other_view" with the other view's numbers where the engine has one.
std::string JsonFile(ShExportFormat format, ShSourceKind kind, std::string_view convention, std::string_view source,
                     const std::function<void(const EngineView&, nlohmann::ordered_json&)>& numbers) {
  nlohmann::ordered_json json;
  json["convention"] = ConventionText(convention, format, kind, kOtherViewInJson);
  json["source"] = std::string(source);
  const EngineView& view = AssumedView(format, kind);
  json["view"] = std::string(view.name);
  numbers(view, json);
  if (const EngineView* other = OtherView(format, kind)) {
    nlohmann::ordered_json alternative;
    alternative["view"] = std::string(other->name);
    numbers(*other, alternative);
    json["other_view"] = std::move(alternative);
  }
  return json.dump(2) + "\n";
}

void ThreeNumbers(const Sh9Rgb& sh, const EngineView& view, nlohmann::ordered_json& json) {
  nlohmann::ordered_json flat = nlohmann::ordered_json::array();
  for (const glm::dvec3& c : ThreeJsCoefficients(sh, view)) flat.insert(flat.end(), {c.r, c.g, c.b});
  json["sh"] = std::move(flat);
  json["intensity"] = 1.0;
}

void UnityNumbers(const Sh9Rgb& sh, const EngineView& view, nlohmann::ordered_json& json) {
  const std::array<glm::dvec4, 7> vectors = UnityShConstants(sh, view);
  for (int i = 0; i < 7; ++i) json[kUnityNames[i]] = {vectors[i].x, vectors[i].y, vectors[i].z, vectors[i].w};
}

std::string FilamentText(ShSourceKind kind, const Sh9Rgb& sh, std::string_view source) {
  std::string out = CommentLines(
      "// ", ConventionText(kFilamentConvention, ShExportFormat::kFilament, kind, "run cmgen so, or negate those three"));
  out += CommentLines("// ", source);
  const ShTriples triples = FilamentIrradianceSh(sh, AssumedView(ShExportFormat::kFilament, kind));
  for (int i = 0; i < kSh9Coefficients; ++i) {
    const glm::dvec3& c = triples[i];
    out += fmt::format("({:.9g}, {:.9g}, {:.9g}); // {}, irradiance, pre-scaled base\n", c.r, c.g, c.b,
                       kCoefficientNames[i]);
  }
  return out;
}

// The shader function, in GLSL (vec3/vec4) or HLSL (float3/float4). Its frame is the cube's for every
// input, so the baked constants are vs11's own.
std::string ShaderText(ShExportFormat format, ShSourceKind kind, const Sh9Rgb& sh, std::string_view source) {
  const bool hlsl = format == ShExportFormat::kHlsl;
  const std::string_view vec3 = hlsl ? "float3" : "vec3";
  const std::string_view vec4 = hlsl ? "float4" : "vec4";
  const std::string function = fmt::format("{} vs11Irradiance({} n)", vec3, vec3);
  std::string out = CommentLines(
      "// ", fmt::format(fmt::runtime(kShaderConvention), fmt::arg("function", function),
                         fmt::arg("frame", FrameSentence(format, kind, "")),
                         fmt::arg("lookup", hlsl ? "TextureCube.Sample(sampler, n).rgb" : "texture(samplerCube, n).rgb"),
                         fmt::arg("minus_x", fmt::format("{}(-n.x, n.y, n.z)", vec3)),
                         fmt::arg("swap_xz", fmt::format("{}(n.z, n.y, n.x)", vec3))));
  out += CommentLines("// ", source);
  out += function + " {\n";
  const SevenConstants constants = PackTable1(InEngineFrame(AssumedView(format, kind), sh));
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

std::string_view ShExportFileName(ShExportFormat format) { return Info(format).file_name; }

const EngineView& AssumedView(ShExportFormat format, ShSourceKind kind) {
  return *Info(format).assumed[KindIndex(kind)];
}

const EngineView* OtherView(ShExportFormat format, ShSourceKind kind) { return Info(format).other[KindIndex(kind)]; }

glm::dvec3 EngineDirection(const EngineView& view, glm::dvec3 d) {
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) out[i] = view.to_engine.sign[i] * d[view.to_engine.axis[i]];
  return out;
}

Sh9Rgb InEngineFrame(const EngineView& view, const Sh9Rgb& sh) {
  // The engine's direction is R d; the environment there is E(R^T n). Band 1 is v . d with
  // v = (L11, L1-1, L10), so v' = R v; band 2 is d^T M d with M symmetric, so M' = R M R^T.
  glm::dmat3 r(0.0);  // glm is column-major: r[column][row]
  for (int i = 0; i < 3; ++i) r[view.to_engine.axis[i]][i] = view.to_engine.sign[i];
  Sh9Rgb out;
  for (int c = 0; c < 3; ++c) {
    const auto l = [&](int i) { return sh.coefficients[i][c]; };
    out.coefficients[0][c] = l(0);
    const glm::dvec3 v = r * glm::dvec3(l(3), l(1), l(2));
    out.coefficients[3][c] = v.x;
    out.coefficients[1][c] = v.y;
    out.coefficients[2][c] = v.z;
    // xy, yz, xz terms kShN2 L; 3z^2 - 1 = 2z^2 - x^2 - y^2 on the sphere; x^2 - y^2.
    const double off_xy = 0.5 * kShN2 * l(4), off_yz = 0.5 * kShN2 * l(5), off_xz = 0.5 * kShN2 * l(7);
    const double zonal = kShN3 * l(6), sectoral = kShN4 * l(8);
    const glm::dmat3 m(-zonal + sectoral, off_xy, off_xz,  //
                       off_xy, -zonal - sectoral, off_yz,  //
                       off_xz, off_yz, 2.0 * zonal);
    const glm::dmat3 m2 = r * m * glm::transpose(r);
    out.coefficients[4][c] = 2.0 * m2[0][1] / kShN2;
    out.coefficients[5][c] = 2.0 * m2[1][2] / kShN2;
    out.coefficients[7][c] = 2.0 * m2[0][2] / kShN2;
    out.coefficients[6][c] = m2[2][2] / (2.0 * kShN3);
    out.coefficients[8][c] = (m2[0][0] - m2[1][1]) / (2.0 * kShN4);
  }
  return out;
}

Sh9Rgb MirrorX(const Sh9Rgb& sh) {
  Sh9Rgb mirrored;
  for (int i = 0; i < kSh9Coefficients; ++i) mirrored.coefficients[i] = kMirrorXSign[i] * sh.coefficients[i];
  return mirrored;
}

ShTriples ThreeJsCoefficients(const Sh9Rgb& sh, const EngineView& view) { return InEngineFrame(view, sh).coefficients; }

ShTriples FilamentIrradianceSh(const Sh9Rgb& sh, const EngineView& view) {
  ShTriples out = InEngineFrame(view, sh).coefficients;
  for (int i = 0; i < kSh9Coefficients; ++i) out[i] *= kEnginePreScale[i];
  return out;
}

ShTriples GltfIrradianceCoefficients(const Sh9Rgb& sh, const EngineView& view) {
  ShTriples out = InEngineFrame(view, sh).coefficients;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    out[i] *= kShBandFactor[kBandOf[i]] * kCondonShortleySign[i];
  }
  return out;
}

std::array<glm::dvec4, 7> UnityShConstants(const Sh9Rgb& sh, const EngineView& view) {
  const SevenConstants constants = PackTable1(InEngineFrame(view, sh));
  std::array<glm::dvec4, 7> out;
  for (int i = 0; i < 7; ++i) out[i] = glm::dvec4(constants.registers[i]) / std::numbers::pi;
  out[SevenConstants::kC].w = kUnitySHCw;
  return out;
}

std::string ShExportText(ShExportFormat format, ShSourceKind kind, const Sh9Rgb& sh, std::string_view source) {
  switch (format) {
    case ShExportFormat::kThree:
      return JsonFile(format, kind, kThreeConvention, source,
                      [&sh](const EngineView& view, nlohmann::ordered_json& json) { ThreeNumbers(sh, view, json); });
    case ShExportFormat::kFilament: return FilamentText(kind, sh, source);
    case ShExportFormat::kUnity:
      return JsonFile(format, kind, kUnityConvention, source,
                      [&sh](const EngineView& view, nlohmann::ordered_json& json) { UnityNumbers(sh, view, json); });
    case ShExportFormat::kGltf:
      return JsonFile(format, kind, kGltfConvention, source, [&sh](const EngineView& view, nlohmann::ordered_json& json) {
        json["irradianceCoefficients"] = TriplesJson(GltfIrradianceCoefficients(sh, view));
      });
    case ShExportFormat::kGlsl:
    case ShExportFormat::kHlsl: return ShaderText(format, kind, sh, source);
  }
  return {};
}

}  // namespace vs11::irradiance
