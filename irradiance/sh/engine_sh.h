// The nine coefficients in the conventions of the engines that read them (irrmap --sh-export), each
// written in that engine's own world frame, as that engine shows the input file.
//
// vs11's coefficients L_lm (sh9.h) are radiance coefficients in the real basis of the paper's eq. (5)
// without the Condon-Shortley sign, taken over directions of the cube map's frame: Direct3D's, left-
// handed, +y up (the +y face and the top row of a lat-long image are up), +z forward, +x to the right
// when looking at +z from inside; a lat-long image's centre looks at +z, three quarters across at +x
// (environment_io.h). The polynomial of eq. (7) reads the normal in that same frame, and every engine
// feeds its world normal (+y up) into the same polynomial, so what differs is where the engine puts
// vs11's direction d, and that depends on how it shows the file (ShSourceKind):
//
//   format    stores                        cube map (faces, cross, ...)   lat-long panorama
//   three     L_lm (radiance)               (-dx, dy, dz) CubeTexture      (dz, dy, dx) equirectUv
//   filament  k_i L_lm (E/pi pre-scaled)    (-dx, dy, dz) cmgen's mirror   (-dx, dy, dz) cmgen's cube
//   unity     Table 1 constants / pi        d  Cubemap                     (dz, dy, -dx) Skybox/Panoramic
//   gltf      A_l L_lm, Condon-Shortley     d  the cube's own              d  Babylon.js's cube of it
//   glsl      E(n), constants baked         d  a cube lookup's direction   d
//   hlsl      E(n), constants baked         d                              d
//
// From the engines' sources: three.js maps an equirectangular texture with equirectUv (u = atan2(z,
// x) / 2pi + 0.5: the image centre is its +X, three quarters across +Z) and samples a CubeTexture at
// (-x, y, z); Unity's Skybox/Panoramic maps u = 0.5 - atan2(z, x) / 2pi (centre +X, a quarter across
// +Z) and samples cube maps at the world direction; cmgen's equirectangularToCubemap and Babylon.js's
// PanoramaToCubeMapTools (HDRCubeTexture) build the same cube of a panorama as vs11 does, cmgen then
// mirrors it in x by default. Where one engine shows a file two ways the export assumes the first
// and names the second (OtherView): the JSON files hold it too, under "other_view".
//
// k_i = A_l |Y_lm constant| / pi: 0.282095, 0.325735 (x3), 0.273137 (x2), 0.078848, 0.273137,
// 0.136569 (the paper's c0..c4 of eq. (7) divided by pi).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "irradiance/sh/sh9.h"
#include "vm/core/name_table.h"

namespace vs11::irradiance {

enum class ShExportFormat { kThree, kFilament, kUnity, kGltf, kGlsl, kHlsl };
inline constexpr std::array<ShExportFormat, 6> kAllShExportFormats = {
    ShExportFormat::kThree, ShExportFormat::kFilament, ShExportFormat::kUnity,
    ShExportFormat::kGltf,  ShExportFormat::kGlsl,     ShExportFormat::kHlsl};

// The names of --sh-export.
inline constexpr NameTable kShExportFormatNames("--sh-export format", {
    Choice(ShExportFormat::kThree, "three"), Choice(ShExportFormat::kFilament, "filament"),
    Choice(ShExportFormat::kUnity, "unity"), Choice(ShExportFormat::kGltf, "gltf"),
    Choice(ShExportFormat::kGlsl, "glsl"), Choice(ShExportFormat::kHlsl, "hlsl")});
inline std::string_view ShExportFormatName(ShExportFormat format) { return kShExportFormatNames.Name(format); }
// sh_three.json, sh_filament.txt, sh_unity.json, sh_gltf.json, sh_irradiance.glsl, sh_irradiance.hlsl
std::string_view ShExportFileName(ShExportFormat format);

// How the engines see the input: a lat-long panorama, which each engine maps to directions with its
// own formula, or a cube map. Angular maps and the built-in environments reach an engine only as the
// cube irrmap makes of them, so they count as cube maps.
enum class ShSourceKind { kCube, kLatLong };

// A signed permutation of the axes: the engine's direction has component i = sign[i] d[axis[i]].
struct SignedAxes {
  std::array<int, 3> axis;
  std::array<int, 3> sign;
};

// One way an engine shows an environment file: a short name (written into the JSON files as
// "view"), what it is, and where vs11's direction lands in the engine's world.
struct EngineView {
  std::string_view name;
  std::string_view description;
  SignedAxes to_engine;
};

// The view the export of `format` assumes for an input of `kind` (the table above), and the other
// way the same engine shows such an input (nullptr where there is none).
const EngineView& AssumedView(ShExportFormat format, ShSourceKind kind);
const EngineView* OtherView(ShExportFormat format, ShSourceKind kind);
// The engine's direction for a direction `d` of vs11's cube frame, in `view`.
glm::dvec3 EngineDirection(const EngineView& view, glm::dvec3 d);
// The coefficients of the same environment in the engine's frame: L'(EngineDirection(view, d)) =
// L(d). Exact for any signed permutation (band 1 as a vector, band 2 as a quadratic form).
Sh9Rgb InEngineFrame(const EngineView& view, const Sh9Rgb& sh);

// The coefficients of the environment mirrored in x, L'(x, y, z) = L(-x, y, z): those of x (1,1),
// xy (2,-2) and xz (2,1) negated.
Sh9Rgb MirrorX(const Sh9Rgb& sh);

inline constexpr std::array<double, kSh9Coefficients> kEnginePreScale = {
    kShC0 / kShA0, kShC1 / kShA0, kShC1 / kShA0, kShC1 / kShA0, kShC2 / kShA0,
    kShC2 / kShA0, kShC3 / kShA0, kShC2 / kShA0, kShC4 / kShA0};  // k_i (kShA0 is pi)

using ShTriples = std::array<glm::dvec3, kSh9Coefficients>;

// Each engine's numbers for the environment whose vs11 coefficients are `sh`, in `view` (the
// engine's AssumedView or OtherView):
// three.js SphericalHarmonics3.coefficients: L_lm.
ShTriples ThreeJsCoefficients(const Sh9Rgb& sh, const EngineView& view);
// Filament's irradiance(3, sh): k_i L_lm.
ShTriples FilamentIrradianceSh(const Sh9Rgb& sh, const EngineView& view);
// EXT_lights_image_based irradianceCoefficients: A_l L_lm with the Condon-Shortley sign of (1,-1),
// (1,1), (2,-1) and (2,1).
ShTriples GltfIrradianceCoefficients(const Sh9Rgb& sh, const EngineView& view);
// unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC: PackTable1's registers divided by pi, with SHC.w = 1
// as Unity sets it.
std::array<glm::dvec4, 7> UnityShConstants(const Sh9Rgb& sh, const EngineView& view);

// The file of `format` for an input of `kind`: the convention at the top (comment lines, or a
// "convention" member first in JSON) naming the view assumed and the other one, `source` (where the
// coefficients come from) under it, then the numbers; the JSON files also hold "view" and, where the
// engine has another view, "other_view": {"view", the same numbers in that view}.
std::string ShExportText(ShExportFormat format, ShSourceKind kind, const Sh9Rgb& sh, std::string_view source);

}  // namespace vs11::irradiance
