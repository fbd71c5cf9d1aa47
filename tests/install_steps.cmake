# The steps the install tests share (tests/install_consumer.cmake, tests/c_consumer/install_test.cmake),
# for cmake -P scripts: install the build into a scratch prefix, and read a package's pkg-config flags
# from what was installed there.

# cmake --install BINARY_DIR into PREFIX, which is emptied first.
function(vs11_install_build binary_dir prefix)
  file(REMOVE_RECURSE "${prefix}")
  execute_process(COMMAND ${CMAKE_COMMAND} --install "${binary_dir}" --prefix "${prefix}"
                  RESULT_VARIABLE status OUTPUT_QUIET)
  if(status)
    message(FATAL_ERROR "cmake --install failed: ${status}")
  endif()
endfunction()

# `pkg-config --cflags --libs PACKAGE` for the PACKAGE.pc installed under PREFIX, as a list in
# OUT_FLAGS; OUT_LIBDIR gets the folder above the .pc file's (the library folder).
function(vs11_installed_pkg_config prefix package out_flags out_libdir)
  find_program(PKG_CONFIG pkg-config REQUIRED)
  file(GLOB_RECURSE pc_file "${prefix}/*/${package}.pc")
  if(NOT pc_file)
    message(FATAL_ERROR "cmake --install put no ${package}.pc under ${prefix}")
  endif()
  get_filename_component(pc_dir "${pc_file}" DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs ${package} OUTPUT_VARIABLE flags
                  RESULT_VARIABLE status OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_VARIABLE pkg_error)
  if(status)
    message(FATAL_ERROR "pkg-config --cflags --libs ${package} failed: ${pkg_error}")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  get_filename_component(libdir "${pc_dir}" DIRECTORY)
  set(${out_flags} ${flags} PARENT_SCOPE)
  set(${out_libdir} ${libdir} PARENT_SCOPE)
endfunction()
