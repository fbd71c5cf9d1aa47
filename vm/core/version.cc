// vs11's version. See version.h. VS11_VERSION is set for this file alone by vm/CMakeLists.txt from
// PROJECT_VERSION, so that a version change recompiles one file.
#include "vm/core/version.h"

namespace vs11 {

std::string_view Vs11Version() { return VS11_VERSION; }

}  // namespace vs11
