// Input files of vertex data (meshes, .npy arrays, raw buffers) must be regular files: their size is
// checked against the limits before they are read, and a named pipe or a device has none (reading
// /dev/zero would never end). This says what a path is instead when it is not one.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace vs11 {

// nullopt for a regular file (or a link to one); otherwise why it cannot be read as one, e.g.
// "no such file", "a folder, not a regular file", "a named pipe (FIFO), not a regular file".
std::optional<std::string> WhyNotARegularFile(const std::filesystem::path& path);

}  // namespace vs11
