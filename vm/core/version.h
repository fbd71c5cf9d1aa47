// vs11's version, as CMake's project(VERSION) states it (the one place it is written): what the
// tools' --version, the Python module's __version__ and every output's provenance report.
#pragma once

#include <string_view>

namespace vs11 {

std::string_view Vs11Version();  // "0.1.0"

}  // namespace vs11
