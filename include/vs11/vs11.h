// vs11's public C++ interface: the one header a program using an installed vs11 includes
// (`#include <vs11/vs11.h>`; README, "Use it from C++"). Installed are this header and the headers
// it reaches (cmake/vs11PublicHeaders.cmake); every other header of the tree is internal.
#pragma once

// The machine: programs, assembling, validating, loading program files, the disassembler.
#include "vm/asm/assembler.h"
#include "vm/asm/disassembler.h"
#include "vm/asm/program_file.h"
#include "vm/asm/validator.h"
#include "vm/core/version.h"

// Running programs: constant banks, vertex arrays, engines by name, constant and vertex text files.
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/io/vertex_io.h"

// The double-precision references of programs/, `verify`, and the nine-coefficient SH core.
#include "vm/reference/sh9.h"
#include "vm/reference/verify.h"

// Irradiance environment maps: environments, SH windows, the paper's program, irrmap's and the
// batch job's work as library calls.
#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/batch_output.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/paper_program.h"
#include "irradiance/sh/sh9.h"
