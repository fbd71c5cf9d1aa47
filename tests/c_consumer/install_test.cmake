# The C library from the installed tree alone: installs the built project into a scratch prefix,
# then compiles tests/c_consumer/*.c as C99 with `pkg-config --cflags --libs vs11c` (no CMake, no
# C++ compiler, no source tree include path) and runs them. example.c is the README's "C library"
# example, shown there verbatim with its output. Arguments: -DBINARY_DIR=<build tree>
# -DSOURCE_DIR=<source tree> -DWORK_DIR=<scratch> -DC_COMPILER=<the build's C compiler>
# -DLINK_FLAGS=<extra link flags, e.g. the sanitizers>.
cmake_minimum_required(VERSION 3.25)  # the policies of the project (CMP0054: quoted if() arguments)
file(READ "${SOURCE_DIR}/README.md" readme)
file(READ "${SOURCE_DIR}/tests/c_consumer/example.c" example)
string(FIND "${readme}" "```c\n${example}```" at)
if(at EQUAL -1)
  message(FATAL_ERROR "README.md does not show tests/c_consumer/example.c verbatim in a ```c block")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/../install_steps.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
vs11_install_build("${BINARY_DIR}" "${WORK_DIR}/prefix")
vs11_installed_pkg_config("${WORK_DIR}/prefix" vs11c pkg_flags lib_dir)
separate_arguments(link_flags UNIX_COMMAND "${LINK_FLAGS}")
# The installed shared library is found as a user's program finds it: here through LD_LIBRARY_PATH.
set(ENV{LD_LIBRARY_PATH} "${lib_dir}")
foreach(program example c_library_test)
  execute_process(COMMAND ${C_COMPILER} -std=c99 -pedantic -Wall -Wextra -Werror
                          "${SOURCE_DIR}/tests/c_consumer/${program}.c" -o "${WORK_DIR}/${program}" ${pkg_flags} -lm ${link_flags}
                  RESULT_VARIABLE status)
  if(status)
    message(FATAL_ERROR "compiling tests/c_consumer/${program}.c as C99 with pkg-config's flags (${pkg_flags}) failed")
  endif()
  execute_process(COMMAND "${WORK_DIR}/${program}" RESULT_VARIABLE status OUTPUT_VARIABLE output)
  message("${program}:\n${output}")
  if(status)
    message(FATAL_ERROR "${program} failed: ${status}")
  endif()
  if(program STREQUAL "example")
    string(FIND "${readme}" "```\n${output}```" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "README.md does not show the example's output verbatim:\n${output}")
    endif()
  endif()
endforeach()
# Only the C functions are exported: none of the C++ machine below them.
find_program(NM nm)
if(NM)
  file(GLOB library "${lib_dir}/libvs11c.so")
  execute_process(COMMAND ${NM} -D --defined-only "${library}" OUTPUT_VARIABLE symbols RESULT_VARIABLE status)
  string(REGEX MATCHALL "[^\n]* [TDBRW] [^\n]*" exported "${symbols}")
  foreach(line IN LISTS exported)
    if(NOT line MATCHES " vs11c_[a-z0-9_]+(@@VS11C_0)?$")
      message(FATAL_ERROR "libvs11c.so exports more than the C functions: ${line}")
    endif()
  endforeach()
endif()
