// Built-in procedural environments (linear RGB radiance on a cube map), for tests, demos and
// benchmarks that need no image file. Directions are in the cube map's D3D frame: +y is up.
// Azimuth is measured in the horizontal plane from +z towards +x, elevation from the horizon up:
//   direction(azimuth, elevation) = (cos(el) sin(az), sin(el), cos(el) cos(az)).
// Light sources are specified by the irradiance they give a surface facing them (radiance times the
// source's solid angle), so changing a source's size does not change how bright it lights things.
// The defaults keep irradiance of order 1..10.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

// Unit direction for an azimuth and an elevation in degrees (see the convention above).
glm::dvec3 DirectionFromAzimuthElevation(double azimuth_degrees, double elevation_degrees);

// Fills every texel of a face_size (>= 1) cube map with the mean of `radiance` over a 2 x 2 grid of
// unit directions inside the texel (at texel offsets 0.25 and 0.75), which smooths hard edges.
// `radiance` receives unit vectors.
CubeMap CubeMapFromFunction(int face_size, const std::function<glm::vec3(glm::dvec3)>& radiance);

struct SkyParams {
  glm::vec3 zenith_radiance{0.25f, 0.45f, 0.95f};   // straight up
  glm::vec3 horizon_radiance{0.75f, 0.8f, 0.9f};    // just above the horizon
  glm::vec3 ground_radiance{0.18f, 0.15f, 0.12f};   // everywhere below the horizon
  double sun_azimuth_degrees = 40.0;
  double sun_elevation_degrees = 35.0;
  double sun_angular_radius_degrees = 2.0;  // > 0; the real sun is about 0.27 degrees
  glm::vec3 sun_irradiance{3.0f, 2.8f, 2.4f};  // the sun's "power": irradiance facing it
};
// A sky whose radiance blends from horizon to zenith with the square root of sin(elevation), a
// uniformly bright sun disk, and a flat darker ground below the horizon. Preconditions: face_size
// >= 1 and sun_angular_radius_degrees in (0, 90].
CubeMap MakeSky(int face_size, const SkyParams& params = {});

// A rectangular area light: the rectangle of the plane at unit distance perpendicular to `center`
// spanning +/- tan(half_width) along `right` and +/- tan(half_height) along center x right.
struct RectLight {
  glm::dvec3 center{0.0, 1.0, 0.0};  // direction to the light's centre (normalised when used)
  glm::dvec3 right{1.0, 0.0, 0.0};   // width axis; made perpendicular to `center` when used
  double half_width_degrees = 20.0;
  double half_height_degrees = 10.0;
  glm::vec3 radiance{1.0f};
};

struct StudioParams {
  glm::vec3 room_radiance{0.03f, 0.03f, 0.035f};
  // Defaults: a warm key light above-front-right, a cool fill on the left, a reddish rim behind.
  std::vector<RectLight> lights = {
      {{0.5, 0.7, 0.5}, {1.0, 0.0, -1.0}, 20.0, 12.0, {14.0f, 11.0f, 8.0f}},
      {{-1.0, 0.2, 0.3}, {0.0, 0.0, 1.0}, 12.0, 18.0, {3.0f, 4.5f, 7.0f}},
      {{0.0, 0.4, -1.0}, {1.0, 0.0, 0.0}, 25.0, 6.0, {8.0f, 3.0f, 2.5f}},
  };
};
// A dark room lit by rectangular area lights of different colours. Precondition: face_size >= 1.
CubeMap MakeStudio(int face_size, const StudioParams& params = {});

struct SpotParams {
  double azimuth_degrees = -30.0;
  double elevation_degrees = 50.0;
  double angular_radius_degrees = 3.0;   // > 0
  glm::vec3 irradiance{5.0f};            // irradiance facing the light
};
// One small round light on black. Preconditions: face_size >= 1, angular radius in (0, 90].
CubeMap MakeSpot(int face_size, const SpotParams& params = {});

// Radiance `radiance` in every direction (a white furnace when it is grey); irradiance is pi times it.
CubeMap MakeConstant(int face_size, glm::vec3 radiance = glm::vec3(1.0f));

struct GradientParams {
  glm::vec3 mean_radiance{0.45f, 0.5f, 0.6f};
  glm::vec3 slope{0.25f, 0.3f, 0.4f};  // per channel, <= mean_radiance so nothing is negative
  glm::dvec3 direction{0.3, 0.9, 0.3}; // brightest way (normalised when used)
};
// A smooth gradient: radiance mean + slope (d . direction), linear in the direction, so its SH
// bands above 1 vanish (up to the cube map's texel averaging) and the three-instruction order-1
// program (irradiance/sh/sh_order.h) is exact for it. Precondition: face_size >= 1.
CubeMap MakeGradient(int face_size, const GradientParams& params = {});

// "constant", "gradient", "sky", "spot", "studio".
std::vector<std::string> BuiltinEnvironmentNames();

// The named environment with default parameters, or std::nullopt for an unknown name or a
// face_size < 1.
std::optional<CubeMap> MakeBuiltinEnvironment(std::string_view name, int face_size);

}  // namespace vs11::irradiance
