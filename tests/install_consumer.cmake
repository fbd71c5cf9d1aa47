# Installs the built project into a scratch prefix, then configures, builds and runs tests/consumer
# against it. Arguments: -DBINARY_DIR=<build tree> -DSOURCE_DIR=<source tree> -DWORK_DIR=<scratch>
# -DCXX_COMPILER=<the build's compiler> -DLINK_FLAGS=<extra link flags, e.g. the sanitizers>.
# The README's "Use it from C++" shows the consumer's two files verbatim: the example that is
# built here is the one users read.
file(READ "${SOURCE_DIR}/README.md" readme)
foreach(shown cmake:CMakeLists.txt cpp:main.cc)
  string(REPLACE ":" ";" shown "${shown}")
  list(GET shown 0 language)
  list(GET shown 1 file)
  file(READ "${SOURCE_DIR}/tests/consumer/${file}" text)
  string(FIND "${readme}" "```${language}\n${text}```" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "README.md does not show tests/consumer/${file} verbatim in a ```${language} block")
  endif()
endforeach()
include(${CMAKE_CURRENT_LIST_DIR}/install_steps.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
vs11_install_build("${BINARY_DIR}" "${WORK_DIR}/prefix")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/build"
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}"
                RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "configuring the consumer failed: ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK_DIR}/build" RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "building the consumer failed: ${status}")
endif()
execute_process(COMMAND "${WORK_DIR}/build/vs11_consumer" RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "the consumer failed: ${status}")
endif()
# Without CMake: the same example built with `pkg-config --cflags --libs vs11` alone.
vs11_installed_pkg_config("${WORK_DIR}/prefix" vs11 pkg_flags lib_dir)
separate_arguments(link_flags UNIX_COMMAND "${LINK_FLAGS}")
execute_process(COMMAND ${CXX_COMPILER} "${SOURCE_DIR}/tests/consumer/main.cc" -o "${WORK_DIR}/vs11_consumer_pkgconfig"
                        ${pkg_flags} ${link_flags}
                RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "building the consumer with pkg-config's flags (${pkg_flags}) failed: ${status}")
endif()
execute_process(COMMAND "${WORK_DIR}/vs11_consumer_pkgconfig" RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "the consumer built with pkg-config's flags failed: ${status}")
endif()
if(NOT EXISTS "${WORK_DIR}/prefix/include/vs11/vm/core/machine.h" OR EXISTS "${WORK_DIR}/prefix/include/vm")
  message(FATAL_ERROR "the headers are not installed under include/vs11/ alone")
endif()
# One entry header and what it reaches (cmake/vs11PublicHeaders.cmake): the engines' internals, the
# tools' code and the libraries that are not installed stay out.
if(NOT EXISTS "${WORK_DIR}/prefix/include/vs11/vs11.h")
  message(FATAL_ERROR "the entry header include/vs11/vs11.h was not installed")
endif()
foreach(internal vm/engines/batch_plan.h vm/engines/jit_compiler.h vm/cli vm/mesh vm/translate vm/gl irradiance/cli)
  if(EXISTS "${WORK_DIR}/prefix/include/vs11/${internal}")
    message(FATAL_ERROR "include/vs11/${internal} was installed: it is internal, not reached from vs11/vs11.h")
  endif()
endforeach()
if(NOT EXISTS "${WORK_DIR}/prefix/bin/vs11")
  message(FATAL_ERROR "the vs11 binary was not installed")
endif()
