// What irrmap projects, and the cube the stages that need one read. A cube map (a file of cube
// layout, a built-in, an array of faces, an angular map resampled) is projected through its mip
// pyramid and the basis pyramid (irradiance/sh/sh_projection.h); a lat-long map where it lies, through
// its own pyramid (irradiance/sh/latlong_projection.h), and resampled to a cube only for the stages
// that read a cube (the ground truth, the preview, a mesh's exact lighting), at the face size asked
// for, once, on first use: with coefficients only, or without the ground truth and a mesh, no cube
// is ever built from it. (The irradiance map is the program evaluated per direction; it reads no
// environment texels.)
#pragma once

#include <memory>
#include <optional>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/latlong_projection.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {

struct IrrmapEnvironment {
  int face_size = 0;  // of the cube (for a panorama: the cube it stands for, whose grids its levels take)
  int threads = 1;
  std::optional<CubeMipChain> mips;  // a cube's, with `basis`
  std::shared_ptr<const BasisPyramid> basis;  // shared by a batch's inputs of one face size
  std::optional<LatLongPyramid> panorama;  // or a panorama's
  std::optional<CubeMap> resampled;        // the panorama as a cube, once a stage asked for it

  // Level `level`'s nine coefficients (0 <= level < LevelCount(face_size)).
  Sh9Rgb Project(int level) const;
  // Whether Cube() would resample first.
  bool NeedsResample() const { return panorama && !resampled; }
  // The environment as a cube of face_size: mips->levels[0], or the panorama resampled
  // (ResampleLatLong) on the first call.
  const CubeMap& Cube();
};

}  // namespace vs11::irradiance
