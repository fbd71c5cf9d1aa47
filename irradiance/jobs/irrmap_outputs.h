// The names of the files irrmap writes into its output folder (irrmap_job.h describes each), and the
// files of an earlier run that a run into the same folder did not replace.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vs11::irradiance {

inline constexpr std::string_view kCoefficientsFile = "coeffs.json";
inline constexpr std::string_view kConstantsFile = "constants.vsh";
inline constexpr std::string_view kProgramFile = "program.vsh";
inline constexpr std::string_view kPreviewFile = "preview.png";
inline constexpr std::string_view kMeshFile = "mesh.ply";
inline constexpr std::string_view kMeshPictureFile = "mesh.png";

// One warning for each file in `out_dir` that some irrmap run writes but this one did not
// (`written`): "DIR/preview.png is left from an earlier run ...", so that nobody takes an earlier
// environment's preview for this one's.
std::vector<std::string> LeftoverOutputWarnings(const std::filesystem::path& out_dir,
                                                std::span<const std::filesystem::path> written);

}  // namespace vs11::irradiance
