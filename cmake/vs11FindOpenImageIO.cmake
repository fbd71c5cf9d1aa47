# Debian 12's OpenImageIO package config lists /usr/include/opencv4 among its include directories even
# when OpenCV is not installed, which makes CMake refuse the target. Keep only folders that exist.
find_package(OpenImageIO REQUIRED)
get_target_property(_vs11_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_vs11_oiio_includes)
  set(_vs11_existing "")
  foreach(_dir IN LISTS _vs11_oiio_includes)
    if(EXISTS "${_dir}" OR _dir MATCHES "^\\$<")
      list(APPEND _vs11_existing "${_dir}")
    endif()
  endforeach()
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_vs11_existing}")
endif()
