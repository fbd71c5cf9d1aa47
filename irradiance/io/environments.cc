// Procedural environments. See environments.h.
#include "irradiance/io/environments.h"

#include <array>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vs11::irradiance {
namespace {

// Sub-texel sample offsets of the 2 x 2 supersampling grid, in texels from the texel's corner.
constexpr std::array<double, 2> kSubsampleOffsets = {0.25, 0.75};

double Radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Radiance of a round source of the given angular radius r that gives `irradiance` to a surface
// facing it: the cosine-weighted solid angle of a cone of half-angle r is pi sin^2 r.
glm::vec3 DiskRadiance(glm::vec3 irradiance, double radius_degrees) {
  const double sin_r = std::sin(Radians(radius_degrees));
  return irradiance / static_cast<float>(std::numbers::pi * sin_r * sin_r);
}

}  // namespace

glm::dvec3 DirectionFromAzimuthElevation(double azimuth_degrees, double elevation_degrees) {
  const double az = Radians(azimuth_degrees);
  const double el = Radians(elevation_degrees);
  return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

CubeMap CubeMapFromFunction(int face_size, const std::function<glm::vec3(glm::dvec3)>& radiance) {
  assert(face_size >= 1);
  CubeMap map(face_size);
  const double samples = static_cast<double>(kSubsampleOffsets.size() * kSubsampleOffsets.size());
  for (CubeFace face : kAllCubeFaces) {
    Image& image = map.face(face);
    for (int y = 0; y < face_size; ++y) {
      for (int x = 0; x < face_size; ++x) {
        glm::dvec3 sum(0.0);
        for (double oy : kSubsampleOffsets) {
          for (double ox : kSubsampleOffsets) {
            const double s = 2.0 * (x + ox) / face_size - 1.0;
            const double t = 2.0 * (y + oy) / face_size - 1.0;
            sum += glm::dvec3(radiance(glm::normalize(FaceDirection(face, s, t))));
          }
        }
        image.at(x, y) = glm::vec3(sum / samples);
      }
    }
  }
  return map;
}

CubeMap MakeSky(int face_size, const SkyParams& p) {
  assert(p.sun_angular_radius_degrees > 0.0 && p.sun_angular_radius_degrees <= 90.0);
  const glm::dvec3 sun = DirectionFromAzimuthElevation(p.sun_azimuth_degrees, p.sun_elevation_degrees);
  const double cos_radius = std::cos(Radians(p.sun_angular_radius_degrees));
  const glm::vec3 sun_radiance = DiskRadiance(p.sun_irradiance, p.sun_angular_radius_degrees);
  return CubeMapFromFunction(face_size, [&](glm::dvec3 d) {
    if (glm::dot(d, sun) >= cos_radius) return sun_radiance;
    if (d.y < 0.0) return p.ground_radiance;
    // d.y is sin(elevation); its square root keeps the horizon band bright but narrow.
    const float blend = static_cast<float>(std::sqrt(d.y));
    return glm::mix(p.horizon_radiance, p.zenith_radiance, blend);
  });
}

CubeMap MakeStudio(int face_size, const StudioParams& p) {
  struct Frame {
    glm::dvec3 center, right, up;
    double tan_half_width, tan_half_height;
    glm::vec3 radiance;
  };
  std::vector<Frame> frames;
  for (const RectLight& light : p.lights) {
    const glm::dvec3 c = glm::normalize(light.center);
    const glm::dvec3 r = glm::normalize(light.right - glm::dot(light.right, c) * c);
    frames.push_back({c, r, glm::cross(c, r), std::tan(Radians(light.half_width_degrees)),
                      std::tan(Radians(light.half_height_degrees)), light.radiance});
  }
  return CubeMapFromFunction(face_size, [&](glm::dvec3 d) {
    glm::vec3 value = p.room_radiance;
    for (const Frame& f : frames) {  // later lights cover earlier ones where they overlap
      const double depth = glm::dot(d, f.center);
      if (depth <= 0.0) continue;
      const double u = glm::dot(d, f.right) / depth;
      const double v = glm::dot(d, f.up) / depth;
      if (std::abs(u) <= f.tan_half_width && std::abs(v) <= f.tan_half_height) value = f.radiance;
    }
    return value;
  });
}

CubeMap MakeSpot(int face_size, const SpotParams& p) {
  assert(p.angular_radius_degrees > 0.0 && p.angular_radius_degrees <= 90.0);
  const glm::dvec3 axis = DirectionFromAzimuthElevation(p.azimuth_degrees, p.elevation_degrees);
  const double cos_radius = std::cos(Radians(p.angular_radius_degrees));
  const glm::vec3 radiance = DiskRadiance(p.irradiance, p.angular_radius_degrees);
  return CubeMapFromFunction(face_size, [&](glm::dvec3 d) {
    return glm::dot(d, axis) >= cos_radius ? radiance : glm::vec3(0.0f);
  });
}

CubeMap MakeConstant(int face_size, glm::vec3 radiance) {
  assert(face_size >= 1);
  return CubeMap(face_size, radiance);
}

CubeMap MakeGradient(int face_size, const GradientParams& p) {
  const glm::dvec3 direction = glm::normalize(p.direction);
  return CubeMapFromFunction(face_size, [&](glm::dvec3 d) {
    return p.mean_radiance + p.slope * static_cast<float>(glm::dot(d, direction));
  });
}

std::vector<std::string> BuiltinEnvironmentNames() { return {"constant", "gradient", "sky", "spot", "studio"}; }

std::optional<CubeMap> MakeBuiltinEnvironment(std::string_view name, int face_size) {
  if (face_size < 1) return std::nullopt;
  if (name == "constant") return MakeConstant(face_size);
  if (name == "gradient") return MakeGradient(face_size);
  if (name == "sky") return MakeSky(face_size);
  if (name == "spot") return MakeSpot(face_size);
  if (name == "studio") return MakeStudio(face_size);
  return std::nullopt;
}

}  // namespace vs11::irradiance
