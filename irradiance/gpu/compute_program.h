// A GLSL ES compute shader compiled and linked on the current context.
#pragma once

#include <string>

namespace vs11::irradiance::gpu {

// The program object, or 0 with `error` holding the compiler's or linker's log.
unsigned LinkComputeProgram(const std::string& source, std::string& error);

}  // namespace vs11::irradiance::gpu
