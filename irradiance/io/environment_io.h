// Environment maps in and out of a CubeMap (linear RGB float radiance), all file I/O through
// OpenImageIO. Faces are always in D3DCUBEMAP_FACES order (+x -x +y -y +z -z) and each face is
// oriented as in cube_map.h: row 0 at the top, texel (s, t) looking along FaceDirection().
//
// Layouts (N = face size):
//
//   kFaces            six square files of one size. The path holds "{face}", which is replaced by
//                     px nx py ny pz nz, or by +x -x +y -y +z -z (both spellings are tried for each
//                     face, the short one first): "sky_{face}.hdr" -> sky_px.hdr, sky_nx.hdr, ...
//   kHorizontalCross  4N x 3N, as drawn in cube_map.h:        .  +y  .   .
//                                                            -x  +z  +x  -z
//                                                             .  -y  .   .
//   kVerticalCross    3N x 4N:                                .  +y  .
//                                                            -x  +z  +x
//                                                             .  -y  .
//                                                             .  -z  .     (-z rotated 180 degrees)
//                     The classic vertical-cross convention: the +z column folds on downwards, so
//                     -z is stored upside down and mirrored (its stored top row is its bottom row,
//                     right to left), and its stored top edge meets the bottom edge of -y.
//   kHorizontalStrip  6N x N, +x -x +y -y +z -z from left to right.
//   kVerticalStrip    N x 6N, +x -x +y -y +z -z from top to bottom. A DDS cube map is read this way
//                     (OpenImageIO and dds_reader.h present its six faces stacked in that order).
//   kLatLong          equirectangular W x H with W = 2 H. The centre of pixel (x, y) has
//                       u = (x + 0.5) / W,  v = (y + 0.5) / H,
//                       phi = 2 pi (u - 0.5)    azimuth, 0 at the centre column
//                       theta = pi v            angle from +y
//                       direction = (sin(phi) sin(theta), cos(theta), cos(phi) sin(theta))
//                     Top row +y, bottom row -y; the centre column looks at +z, three quarters
//                     across at +x, one quarter across at -x, the left and right edges at -z. Seen
//                     from inside the sphere the middle of the image looks like the +z face, with
//                     +x to the right and +y up (not mirrored).
//   kAngular          Debevec's angular map ("light probe"), square N x N, a disk. The centre of
//                     pixel (x, y) has
//                       a = 2 (x + 0.5) / N - 1 (to the right),  b = 1 - 2 (y + 0.5) / N (up),
//                       r = sqrt(a^2 + b^2),  theta = pi r,
//                       direction = (a / r sin(theta), b / r sin(theta), cos(theta))   for r <= 1,
//                     so the centre looks at +z and the rim at -z, +y up and +x to the right: seen
//                     from inside, like the +z face (Debevec's probes, whose centre looks down -z
//                     of a right-handed frame, read the same once z is flipped into D3D's frame,
//                     as Ramamoorthi & Hanrahan's prefilter reads them). Pixels whose centre lies
//                     outside the disk are never used.
//
// Pixel values. Float and half images are taken as linear. Integer images (8-bit PNG and JPEG,
// 8- or 16-bit TIFF, uncompressed or BC1-BC5/BC7 DDS, ...) are decoded from sRGB to linear unless
// OpenImageIO tags them "Linear" (for example a PNG with gAMA 1.0). Only the first three channels
// are used; a one- or two-channel image (grey, grey + alpha) has its first channel replicated.
// NaN, infinite and negative values are not rejected: NaN and infinities become 0, negatives are
// clamped to 0, and LoadedEnvironment::warnings says in which file and how many texels were
// changed (irrmap prints these warnings). Sanitising rather than refusing because real probes
// carry a few such texels (a sensor's hot pixel, a signed BC6H block ringing below 0) and radiance
// is never negative; a file of nothing but bad texels loads as black, with all of them counted.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "irradiance/io/cube_map.h"
#include "vm/core/name_table.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

enum class EnvironmentLayout {
  kAuto,
  kFaces,
  kHorizontalCross,
  kVerticalCross,
  kHorizontalStrip,
  kVerticalStrip,
  kLatLong,
  kAngular,
};

// Default face size of a built-in environment and of the cube a lat-long or angular map is resampled to
// (the tools' --face-size, the Python module's face_size).
inline constexpr int kDefaultFaceSize = 256;

inline constexpr NameTable kLayoutNames("layout", {
    Choice(EnvironmentLayout::kAuto, "auto",
           "by aspect ratio (a cross, a strip or a 2:1 latlong); a square image, an angular map or one cube "
           "face, must be named"),
    Choice(EnvironmentLayout::kFaces, "faces"), Choice(EnvironmentLayout::kHorizontalCross, "hcross"),
    Choice(EnvironmentLayout::kVerticalCross, "vcross"), Choice(EnvironmentLayout::kHorizontalStrip, "hstrip"),
    Choice(EnvironmentLayout::kVerticalStrip, "vstrip"), Choice(EnvironmentLayout::kLatLong, "latlong"),
    Choice(EnvironmentLayout::kAngular, "angular")});
inline std::string_view LayoutName(EnvironmentLayout layout) { return kLayoutNames.Name(layout); }

// The placeholder in a six-face path, and what it is replaced by for each face (CubeFace order).
inline constexpr std::string_view kFaceToken = "{face}";
inline constexpr std::array<std::string_view, kCubeFaceCount> kFaceFileNames = {"px", "nx", "py",
                                                                                "ny", "pz", "nz"};
inline constexpr std::array<std::string_view, kCubeFaceCount> kSignedFaceFileNames = {
    "+x", "-x", "+y", "-y", "+z", "-z"};

// Largest face size the lat-long and angular resamplers build (16384^2 x 6 texels is 19 GB).
inline constexpr int kMaxFaceSize = 16384;
// The face-size rules, each stated once (IsPowerOfTwo is in cube_map.h). An option naming a face
// size (`option`: "--face-size" or "face_size", irradiance/io/option_names.h) must be a power of two from 1 to
// `max_size`: success if it is, else the error (kFaceSize). A loaded cube's face must be a power of two for the mip
// pyramid (exact 2x2 parents down to 1x1): success if it is, else the error, its message prefixed with "SOURCE: " when
// `source` is not empty.
Status CheckFaceSizeOption(std::string_view option, int face_size, int max_size = kMaxFaceSize);
Status CheckPyramidFaceSize(std::string_view source, int face_size);

// Largest image read, in pixels (2^28: a 16384 x 16384 image, 3 GB as float RGB); larger headers
// are rejected as corrupt rather than allocated.
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 28;

struct LoadOptions {
  EnvironmentLayout layout = EnvironmentLayout::kAuto;
  // Face size of the cube built from a lat-long or angular map, in [1, kMaxFaceSize]. Cube layouts
  // keep their own face size.
  int face_size = kDefaultFaceSize;
  // A lat-long map is kept as it is (LoadedEnvironment::latlong, sanitised) and no cube is built:
  // for callers that project it in place (irradiance/sh/latlong_projection.h).
  bool keep_latlong = false;
};

struct LoadedEnvironment {
  CubeMap cube;  // empty (face_size 0) where `latlong` is set
  std::optional<Image> latlong;  // with LoadOptions::keep_latlong, a lat-long map as read
  EnvironmentLayout layout = EnvironmentLayout::kAuto;  // the layout read (never kAuto)
  // Why that layout: "as given", "detected from the 2:1 aspect ratio of the 512 x 256 image", "a DDS
  // cube map", "six files: the path holds "{face}"".
  std::string layout_reason;
  std::vector<std::string> warnings;                    // e.g. how many texels were sanitised
};

// Loads an environment map of any layout above. With LoadOptions::layout == kAuto the layout is
// chosen in this order: a path holding "{face}" is six face files; a DDS file flagged as a cube map
// is its six faces; otherwise the aspect ratio: 4:3 hcross, 3:4 vcross, 6:1 hstrip, 1:6 vstrip,
// 2:1 latlong, anything else an error. A square image is refused (kOptionValue: the caller must name
// the layout, a usage error rather than a bad file): it may be an
// angular map or a single cube face, and guessing either gives plausible wrong numbers. An explicit
// layout must fit the image size (4N x 3N for hcross and so on, 2:1 for latlong, square for
// angular); a DDS cube map only fits kAuto and kVerticalStrip.
// Lat-long and angular maps are resampled to options.face_size by ResampleLatLong/ResampleAngular.
// Formats: whatever OpenImageIO reads, among them Radiance .hdr, OpenEXR, PFM, TIFF, PNG, JPEG and
// DDS (8-bit, BC1-BC5, BC6H unsigned and signed, BC7), plus the uncompressed float DDS formats
// OpenImageIO 2.4 refuses, read by dds_reader.h.
// Errors (never thrown), each naming the file: missing, empty, unreadable, truncated or corrupt
// files, formats nobody here reads, zero-size or oversized images (more than kMaxImagePixels,
// refused from the header before anything is allocated), sizes that do not fit the layout,
// non-square faces, six faces of different sizes, a face file missing, DDS texture arrays and
// volumes. Truncation: DDS, PFM and uncompressed TIFF files are checked against the size their
// header implies before any pixel is read; everything else by OpenImageIO's error state after
// reading, which it sets even where read_image succeeds (a short TIFF, DDS or BMP). A PNG cut only
// in its closing IEND chunk keeps all its pixels and loads.
// Codes: kNoSuchInput for a missing file or face, kOptionValue for the square image above,
// kFaceSize for options.face_size outside [1, kMaxFaceSize], kOutOfMemory, kCannotReadFile for the rest.
Result<LoadedEnvironment> LoadEnvironment(const std::filesystem::path& path, const LoadOptions& options = {});

// An image read as linear RGB as described above (sRGB decoded, channels fitted, not sanitised).
struct ImageRead {
  Image image;
  bool is_dds_cube_map = false;  // a DDS cube map with all six faces, laid out as kVerticalStrip
};
Result<ImageRead> ReadImage(const std::filesystem::path& path);

// Builds the cube from an image already in memory, in `layout` (kAuto: by aspect ratio as above;
// kFaces is an error). Sanitises the image first. `face_size` is used for kLatLong and kAngular;
// `keep_latlong` as LoadOptions::keep_latlong.
Result<LoadedEnvironment> EnvironmentFromImage(Image image, EnvironmentLayout layout, int face_size,
                                               bool keep_latlong = false);

// Replaces NaN and infinite channels by 0 and clamps negative ones to 0; returns how many pixels
// had at least one channel changed.
std::size_t SanitizeRadiance(Image& image);

// sRGB transfer function (IEC 61966-2-1), for values in [0, 1].
double SrgbToLinear(double encoded);
double LinearToSrgb(double linear);

// The lat-long convention above, for continuous u, v in [0, 1] (pixel centres at (x + 0.5) / W).
// DirectionToLatLong returns u in [0, 1), v in [0, 1]; `direction` need not be normalised.
glm::dvec3 LatLongDirection(double u, double v);
glm::dvec2 DirectionToLatLong(glm::dvec3 direction);
// The angular-map convention above, for a, b in [-1, 1] with a^2 + b^2 <= 1. DirectionToAngular
// returns a point of the unit disk (for exactly -z, the rim point (1, 0)).
glm::dvec3 AngularDirection(double a, double b);
glm::dvec2 DirectionToAngular(glm::dvec3 direction);

// Resampling to a cube that preserves total energy. Each cube texel is the solid-angle-weighted
// average, over its footprint, of a smooth reconstruction of the source, sampled with n x n points
// where n gives kResampleSamplesPerSourcePixel points per source pixel across the largest
// (face-centre) texels. The reconstruction is the cubic B-spline, not bilinear: every source pixel
// keeps a mass of exactly one pixel either way, but bilinear's kinks alias with the point grid
// (measured: 0.4% of a one-pixel spot's energy) where the B-spline's error falls as sinc^4.
// Lat-long: wraps in azimuth, continues over the poles (row -1 is row 0 half a turn round), and
// widens the kernel in azimuth where pixels get narrower than the point spacing near the poles
// (blending two integer widths, so each pixel keeps its mass and the result stays continuous). A
// lat-long map much finer than the cube is first halved (2 x 2 solid-angle-weighted means, which
// keep its integral) while its pixels stay under half a texel across.
// Angular: only pixels whose centre lies in the disk are used (weights renormalised at the rim);
// texels towards -z, where a pixel spans only sin(pi r) / (pi r) of its radial angle across the
// radius, take proportionally more points (up to kMaxResampleSamples; a 1000^2 probe to a 128 cube
// takes a few seconds).
// No normalisation afterwards: the cube's integral matches the source's (sum of radiance x pixel
// solid angle). Measured with a single bright pixel as the only energy, anywhere but the two rows
// next to a lat-long pole or the outer tenth of the angular disk: worst 1e-3, rms 3e-4. The
// B-spline spreads a pixel over +-2 rows, which on the sphere moves about (pi / H)^2 / 8 of its
// energy (7.5e-5 at H = 128, 1.2e-3 at H = 32). Preconditions (asserted): latlong.width ==
// 2 latlong.height > 0, angular square and non-empty, 1 <= face_size <= kMaxFaceSize. The rows
// are shared among the threads of ThreadPool::Default() (vm/core/thread_pool.h) and the caller.
inline constexpr int kResampleSamplesPerSourcePixel = 3;
inline constexpr int kMaxResampleSamples = 32;  // per texel side
CubeMap ResampleLatLong(const Image& latlong, int face_size);
CubeMap ResampleAngular(const Image& angular, int face_size);

// Bilinear lookup of the cube in `direction` (filtered within the face it lands on).
glm::vec3 SampleCubeMap(const CubeMap& cube, glm::dvec3 direction);

// The cube laid out as one image: hcross 4N x 3N, vcross 3N x 4N, hstrip 6N x N, vstrip N x 6N
// (unused cells black), latlong 4N x 2N and angular 4N x 4N (both point-sampled with SampleCubeMap,
// for export and viewing; outside the angular disk black). Precondition (asserted): `layout` is
// none of kAuto and kFaces, cube.face_size > 0.
Image CubeMapToImage(const CubeMap& cube, EnvironmentLayout layout);

// Writers. Each returns success or the error (kCannotWriteFile) naming the file. Every file is written
// atomically: to a temporary file in the same folder, renamed over `path` once complete; on failure
// no temporary or partial file is left behind and an existing `path` is untouched.
//
// The format follows the extension. .exr (32-bit float, zip), .hdr (RGBE) and .tif/.tiff (32-bit
// float) keep linear floats; any other format OpenImageIO writes (.png, .jpg, ...) gets 8-bit sRGB,
// values clamped to [0, 1] and tagged sRGB. OpenImageIO 2.4 cannot write .pfm or .dds.
Status WriteImage(const Image& image, const std::filesystem::path& path);
// A horizontal cross of 32-bit floats in OpenEXR, whatever the extension; unused cells black.
Status WriteCrossExr(const CubeMap& cube, const std::filesystem::path& path);
// The cube in `layout`. kFaces writes six files: `path` must hold "{face}", replaced by
// kFaceFileNames (px nx ...); all six are written to temporaries first and renamed only if all
// succeed. kAuto means kFaces if `path` holds "{face}", else kHorizontalCross.
Status WriteCubeMap(const CubeMap& cube, const std::filesystem::path& path, EnvironmentLayout layout);

}  // namespace vs11::irradiance
