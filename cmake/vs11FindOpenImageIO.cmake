# Finds the OpenImageIO library and defines OpenImageIO::OpenImageIO, without Debian's package config.
#
# Debian 12's OpenImageIOConfig.cmake imports the command-line tools (iconvert, iv, ...) as targets
# and stops configuration when their files are missing. Those come in openimageio-tools, which pulls
# in Qt; vs11 links only the library. The config also lists /usr/include/opencv4 even when OpenCV is
# not installed. This module finds the headers and the two shared libraries directly instead and
# reads the version from oiioversion.h, so neither problem can stop a configure.
include_guard(GLOBAL)
include(FindPackageHandleStandardArgs)

# OpenImageIO's public headers include Imath's.
find_package(Imath CONFIG REQUIRED)
find_path(vs11_OpenImageIO_INCLUDE_DIR OpenImageIO/oiioversion.h)
find_library(vs11_OpenImageIO_LIBRARY NAMES OpenImageIO)
find_library(vs11_OpenImageIO_Util_LIBRARY NAMES OpenImageIO_Util)

if(vs11_OpenImageIO_INCLUDE_DIR)
  file(STRINGS "${vs11_OpenImageIO_INCLUDE_DIR}/OpenImageIO/oiioversion.h" _vs11_oiio_version_lines
    REGEX "^#define OIIO_VERSION_(MAJOR|MINOR|PATCH) ")
  foreach(_part MAJOR MINOR PATCH)
    string(REGEX REPLACE ".*#define OIIO_VERSION_${_part} ([0-9]+).*" "\\1" _vs11_oiio_${_part}
      "${_vs11_oiio_version_lines}")
  endforeach()
  set(OpenImageIO_VERSION "${_vs11_oiio_MAJOR}.${_vs11_oiio_MINOR}.${_vs11_oiio_PATCH}")
endif()

find_package_handle_standard_args(OpenImageIO
  REQUIRED_VARS vs11_OpenImageIO_LIBRARY vs11_OpenImageIO_Util_LIBRARY vs11_OpenImageIO_INCLUDE_DIR
  VERSION_VAR OpenImageIO_VERSION
  REASON_FAILURE_MESSAGE "install Debian's libopenimageio-dev (bash .ci/setup does)")
if(OpenImageIO_VERSION VERSION_LESS 2.4)
  message(FATAL_ERROR "vs11 needs OpenImageIO 2.4 or newer; found ${OpenImageIO_VERSION}")
endif()

if(NOT TARGET OpenImageIO::OpenImageIO)
  add_library(OpenImageIO::OpenImageIO_Util SHARED IMPORTED)
  set_target_properties(OpenImageIO::OpenImageIO_Util PROPERTIES
    IMPORTED_LOCATION "${vs11_OpenImageIO_Util_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${vs11_OpenImageIO_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "Imath::Imath")
  add_library(OpenImageIO::OpenImageIO SHARED IMPORTED)
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES
    IMPORTED_LOCATION "${vs11_OpenImageIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${vs11_OpenImageIO_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "OpenImageIO::OpenImageIO_Util")
endif()
