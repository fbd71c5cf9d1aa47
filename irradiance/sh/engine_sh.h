// The nine coefficients in the conventions of the engines that read them (irrmap --sh-export), each
// written in that engine's own world frame.
//
// vs11's coefficients L_lm (sh9.h) are radiance coefficients in the real basis of the paper's eq. (5)
// without the Condon-Shortley sign, taken over directions of the cube map's frame: Direct3D's, left-
// handed, +y up (the +y face and the top row of a lat-long image are up), +z forward, +x to the right
// when looking at +z from inside. The polynomial of eq. (7) reads the normal in that same frame, so
// the basis's "z" (its polar axis in eq. (5)) is a horizontal axis here, exactly as in the engines,
// which all feed their world normal (+y up) into the same polynomial. What differs between engines is
// the handedness, the basis signs and the scale:
//
//   format    stores                               frame                   engine direction of vs11's d
//   three     L_lm (radiance)                      right-handed, +y up     (-dx, dy, dz)
//   filament  k_i L_lm (E/pi pre-scaled)           right-handed, +y up     (-dx, dy, dz)
//   unity     the seven Table 1 constants / pi     left-handed, +y up      d
//   gltf      A_l L_lm, Condon-Shortley basis      the cube map's own      d
//   glsl      E(n) as a function, constants baked  the cube map's own      d
//   hlsl      E(n) as a function, constants baked  the cube map's own      d
//
// A right-handed engine sees a cube map mirrored in x unless it flips it: three.js samples a
// CubeTexture at (-x, y, z), and cmgen mirrors the cube in x by default. Those two engines' exports
// are of the environment as they show it, so their coefficients of x, xy and xz change sign
// (MirrorX). Unity is left-handed like D3D and samples a cube map with the world direction as it is.
// EXT_lights_image_based's coefficients are evaluated by its reference loader (Babylon.js) at the
// same vector as its specular cube lookup, so they stay in the cube's frame. The shader functions
// take the direction a cube map lookup takes, so they equal a lookup of the irradiance cube irrmap
// writes (--map-format dds or ktx2).
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

namespace vs11::irradiance {

enum class ShExportFormat { kThree, kFilament, kUnity, kGltf, kGlsl, kHlsl };
inline constexpr std::array<ShExportFormat, 6> kAllShExportFormats = {
    ShExportFormat::kThree, ShExportFormat::kFilament, ShExportFormat::kUnity,
    ShExportFormat::kGltf,  ShExportFormat::kGlsl,     ShExportFormat::kHlsl};

// "three", "filament", "unity", "gltf", "glsl", "hlsl" and back (nullopt for another name).
std::string_view ShExportFormatName(ShExportFormat format);
std::optional<ShExportFormat> ParseShExportFormat(std::string_view name);
std::string ShExportFormatNames();  // "three, filament, unity, gltf, glsl, hlsl"
// sh_three.json, sh_filament.txt, sh_unity.json, sh_gltf.json, sh_irradiance.glsl, sh_irradiance.hlsl
std::string_view ShExportFileName(ShExportFormat format);

// Whether the engine's world is vs11's cube frame mirrored in x (the right-handed engines).
bool MirrorsX(ShExportFormat format);
// The engine's direction for a direction `d` of vs11's cube frame (the table above).
glm::dvec3 EngineDirection(ShExportFormat format, glm::dvec3 d);

// The coefficients of the environment mirrored in x, L'(x, y, z) = L(-x, y, z): those of x (1,1),
// xy (2,-2) and xz (2,1) negated.
Sh9Rgb MirrorX(const Sh9Rgb& sh);

inline constexpr std::array<double, kSh9Coefficients> kEnginePreScale = {
    kShC0 / kShA0, kShC1 / kShA0, kShC1 / kShA0, kShC1 / kShA0, kShC2 / kShA0,
    kShC2 / kShA0, kShC3 / kShA0, kShC2 / kShA0, kShC4 / kShA0};  // k_i (kShA0 is pi)

using ShTriples = std::array<glm::dvec3, kSh9Coefficients>;

// three.js SphericalHarmonics3.coefficients: L_lm in three.js's frame.
ShTriples ThreeJsCoefficients(const Sh9Rgb& sh);
// Filament's irradiance(3, sh): k_i L_lm in Filament's frame.
ShTriples FilamentIrradianceSh(const Sh9Rgb& sh);
// EXT_lights_image_based irradianceCoefficients: A_l L_lm in the cube's frame, with the
// Condon-Shortley sign of (1,-1), (1,1), (2,-1) and (2,1).
ShTriples GltfIrradianceCoefficients(const Sh9Rgb& sh);
// unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC: PackTable1(sh)'s registers divided by pi (Unity's
// frame is vs11's), with SHC.w = 1 as Unity sets it.
std::array<glm::dvec4, 7> UnityShConstants(const Sh9Rgb& sh);

// The file of `format`: the convention at the top (comment lines, or a "convention" member first in
// JSON), `source` (where the coefficients come from) under it, then the numbers.
std::string ShExportText(ShExportFormat format, const Sh9Rgb& sh, std::string_view source);

}  // namespace vs11::irradiance
