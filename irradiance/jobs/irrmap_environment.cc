// What irrmap projects. See irrmap_environment.h.
#include "irradiance/jobs/irrmap_environment.h"

#include <cassert>

#include "irradiance/io/environment_io.h"

namespace vs11::irradiance {

Sh9Rgb IrrmapEnvironment::Project(int level) const {
  if (panorama) return ProjectLatLongLevel(panorama->level(level), threads);
  assert(mips && basis);
  return ProjectLevel(*mips, *basis, level);
}

const CubeMap& IrrmapEnvironment::Cube() {
  if (!panorama) return mips->levels[0];
  if (!resampled) resampled = ResampleLatLong(panorama->distinct[0].image, face_size);
  return *resampled;
}

}  // namespace vs11::irradiance
