# Every dependency comes from Debian 12's packages (scripts/install-deps.sh installs them).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
pkg_check_modules(epoxy REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(egl REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(xxhash REQUIRED IMPORTED_TARGET libxxhash)
pkg_check_modules(libzip REQUIRED IMPORTED_TARGET libzip)
pkg_check_modules(glfw3 REQUIRED IMPORTED_TARGET glfw3)
if(VT_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(VT_BUILD_BENCHMARKS)
  find_package(benchmark CONFIG REQUIRED)
endif()

# Debian 12's OpenImageIO target names /usr/include/opencv4 as an include directory although
# libopenimageio-dev does not depend on OpenCV; drop the directories that do not exist.
foreach(_property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  get_target_property(_dirs OpenImageIO::OpenImageIO ${_property})
  if(_dirs)
    set(_existing)
    foreach(_dir IN LISTS _dirs)
      if(_dir MATCHES "^\\$<" OR EXISTS "${_dir}")
        list(APPEND _existing "${_dir}")
      endif()
    endforeach()
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${_property} "${_existing}")
  endif()
endforeach()

# libsquish (block-compressed pages): Debian 12's libsquish.pc has an empty prefix (it names
# /include), so the header and the library are found directly.
find_path(SQUISH_INCLUDE_DIR squish.h REQUIRED)
find_library(SQUISH_LIBRARY squish REQUIRED)
add_library(squish::squish UNKNOWN IMPORTED)
set_target_properties(squish::squish PROPERTIES IMPORTED_LOCATION "${SQUISH_LIBRARY}"
                                                INTERFACE_INCLUDE_DIRECTORIES "${SQUISH_INCLUDE_DIR}")
