# The build's components and their dependencies. The library (transforms + codec) needs only
# Eigen, oneTBB and zstd; every other component has its own option and packages. A component
# that is ON but lacks a package stops the configure with the Debian package to install; the
# end of the configure prints what is built and with which versions (pupwave_component_summary).
include(CMakeDependentOption)

option(PUPWAVE_BUILD_TOOLS "Build the pupwave CLI (OpenImageIO, OpenEXR, CLI11, nlohmann_json)" ON)
cmake_dependent_option(PUPWAVE_BUILD_VDB "Build the CLI's OpenVDB module for .vdb volumes (OpenVDB)" ON
                       "PUPWAVE_BUILD_TOOLS" OFF)
option(PUPWAVE_BUILD_HDF5 "Build the HDF5 filter plugin (HDF5 headers)" ON)
option(PUPWAVE_BUILD_PYTHON "Build the Python module (pybind11, Python 3 development files)" ON)
cmake_dependent_option(PUPWAVE_BUILD_OIIO_PLUGIN "Build the OpenImageIO plugin pw.imageio.so" ON
                       "PUPWAVE_BUILD_TOOLS" OFF)
# Tests and benchmarks drive the CLI and read OpenVDB grids, so they need both components.
cmake_dependent_option(PUPWAVE_BUILD_TESTS "Build the GoogleTest suite (needs the tools and vdb components)" ON
                       "PUPWAVE_BUILD_TOOLS;PUPWAVE_BUILD_VDB" OFF)
cmake_dependent_option(PUPWAVE_BUILD_BENCH "Build the Google Benchmark programs (needs the tools component)" ON
                       "PUPWAVE_BUILD_TOOLS" OFF)
option(PUPWAVE_BUILD_FUZZERS "Build the libFuzzer targets fuzz_* (clang, ASan + UBSan)" OFF)
if(PUPWAVE_BUILD_FUZZERS AND NOT PUPWAVE_BUILD_TOOLS)
  message(FATAL_ERROR "PUPWAVE_BUILD_FUZZERS needs PUPWAVE_BUILD_TOOLS (the PNM fuzz target uses its reader)")
endif()
option(PUPWAVE_SANITIZE "Build everything with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)

set(PUPWAVE_COMPONENT_LINES "")
set(PUPWAVE_COMPONENTS_BUILT library)

# pupwave_require(<option> <debian package> <what> <found?>): a missing package of a wanted
# component is a configure error that says what to install or which option turns it off.
function(pupwave_require option package what found)
  if(found)
    return()
  endif()
  if(option STREQUAL "library")
    message(FATAL_ERROR "the library needs ${what}: install the Debian package ${package} "
                        "(apt-get install ${package})")
  endif()
  message(FATAL_ERROR "${option} needs ${what}: install the Debian package ${package} "
                      "(apt-get install ${package}) or configure with -D${option}=OFF")
endfunction()

# pupwave_component(<name> <option or ""> <description> <dependency versions>): one summary line.
function(pupwave_component name option description deps)
  set(built TRUE)
  if(NOT option STREQUAL "")
    set(built ${${option}})
  endif()
  if(built)
    set(state "yes  ${deps}")
    if(NOT name STREQUAL "library")
      set(PUPWAVE_COMPONENTS_BUILT ${PUPWAVE_COMPONENTS_BUILT} ${name} PARENT_SCOPE)
    endif()
  else()
    set(state "no   (-D${option}=ON to build it)")
  endif()
  string(LENGTH "${name} (${description})" len)
  math(EXPR pad "44 - ${len}")
  if(pad LESS 1)
    set(pad 1)
  endif()
  string(REPEAT " " ${pad} spaces)
  list(APPEND PUPWAVE_COMPONENT_LINES "  ${name} (${description})${spaces}${state}")
  set(PUPWAVE_COMPONENT_LINES "${PUPWAVE_COMPONENT_LINES}" PARENT_SCOPE)
endfunction()

# --- library: transforms and codec -------------------------------------------------------------
find_package(Threads REQUIRED)
find_package(Eigen3 3.3 QUIET NO_MODULE)
pupwave_require(library libeigen3-dev "Eigen 3.3 or later" "${Eigen3_FOUND}")
# oneTBB: the shared thread pool behind the default executor (transforms/executor.h).
find_package(TBB QUIET CONFIG)
pupwave_require(library libtbb-dev "oneTBB" "${TBB_FOUND}")
find_package(zstd QUIET CONFIG)
add_library(pupwave_zstd INTERFACE)
if(TARGET zstd::libzstd_shared)
  target_link_libraries(pupwave_zstd INTERFACE zstd::libzstd_shared)
  set(PUPWAVE_ZSTD_VERSION ${zstd_VERSION})
elseif(TARGET zstd::libzstd_static)
  target_link_libraries(pupwave_zstd INTERFACE zstd::libzstd_static)
  set(PUPWAVE_ZSTD_VERSION ${zstd_VERSION})
else()
  # Debian 12's libzstd-dev ships no CMake config: fall back to pkg-config.
  find_package(PkgConfig QUIET)
  pupwave_require(library pkg-config "pkg-config (to find zstd)" "${PkgConfig_FOUND}")
  pkg_check_modules(ZSTD QUIET IMPORTED_TARGET libzstd)
  pupwave_require(library libzstd-dev "zstd" "${ZSTD_FOUND}")
  target_link_libraries(pupwave_zstd INTERFACE PkgConfig::ZSTD)
  set(PUPWAVE_ZSTD_VERSION ${ZSTD_VERSION})
endif()
pupwave_component(library "" "transforms, codec"
                  "Eigen ${Eigen3_VERSION}, oneTBB ${TBB_VERSION}, zstd ${PUPWAVE_ZSTD_VERSION}")

# --- tools: the pupwave CLI and its OpenImageIO module -----------------------------------------
if(PUPWAVE_BUILD_TOOLS)
  find_package(OpenImageIO QUIET CONFIG)
  pupwave_require(PUPWAVE_BUILD_TOOLS libopenimageio-dev "OpenImageIO" "${OpenImageIO_FOUND}")
  # Debian 12's OpenImageIO config names /usr/include/opencv4 even when OpenCV is not installed;
  # drop include directories that do not exist so configuring does not require OpenCV.
  foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs OpenImageIO::OpenImageIO ${prop})
    if(dirs)
      set(kept "")
      foreach(dir ${dirs})
        if(EXISTS "${dir}")
          list(APPEND kept "${dir}")
        endif()
      endforeach()
      set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${prop} "${kept}")
    endif()
  endforeach()
  find_package(OpenEXR QUIET CONFIG)
  pupwave_require(PUPWAVE_BUILD_TOOLS libopenexr-dev "OpenEXR and Imath" "${OpenEXR_FOUND}")
  find_package(nlohmann_json 3 QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS nlohmann-json3-dev "nlohmann_json 3" "${nlohmann_json_FOUND}")
  find_package(CLI11 QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS libcli11-dev "CLI11" "${CLI11_FOUND}")
  find_package(PNG QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS libpng-dev "libpng" "${PNG_FOUND}")
  find_package(TIFF QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS libtiff-dev "libtiff" "${TIFF_FOUND}")
  find_package(JPEG QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS libjpeg-dev "libjpeg" "${JPEG_FOUND}")
  # Debian 12's libexif-dev ships no CMake config: found with pkg-config.
  find_package(PkgConfig QUIET)
  pupwave_require(PUPWAVE_BUILD_TOOLS pkg-config "pkg-config (to find libexif)" "${PkgConfig_FOUND}")
  pkg_check_modules(LIBEXIF QUIET IMPORTED_TARGET libexif)
  pupwave_require(PUPWAVE_BUILD_TOOLS libexif-dev "libexif" "${LIBEXIF_FOUND}")
endif()
pupwave_component(cli PUPWAVE_BUILD_TOOLS "the pupwave CLI"
                  "OpenImageIO ${OpenImageIO_VERSION}, OpenEXR ${OpenEXR_VERSION}, libpng ${PNG_VERSION_STRING}, libtiff ${TIFF_VERSION}, libjpeg ${JPEG_VERSION}, libexif ${LIBEXIF_VERSION}, CLI11 ${CLI11_VERSION}, nlohmann_json ${nlohmann_json_VERSION}")

# --- vdb: the CLI's OpenVDB module ------------------------------------------------------------
if(PUPWAVE_BUILD_VDB)
  # OpenVDB ships its FindOpenVDB.cmake in a non-default module directory on Debian.
  list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB
       /usr/share/cmake/OpenVDB)
  find_package(OpenVDB QUIET)
  pupwave_require(PUPWAVE_BUILD_VDB libopenvdb-dev "OpenVDB" "${OpenVDB_FOUND}")
endif()
pupwave_component(vdb PUPWAVE_BUILD_VDB "the CLI's .vdb module" "OpenVDB ${OpenVDB_VERSION}")

# --- hdf5: the HDF5 filter plugin (headers only; libhdf5 is the host's at run time) ------------
if(PUPWAVE_BUILD_HDF5)
  find_path(PUPWAVE_HDF5_INCLUDE_DIR H5PLextern.h PATHS /usr/include/hdf5/serial)
  pupwave_require(PUPWAVE_BUILD_HDF5 libhdf5-dev "the HDF5 headers (H5PLextern.h)" "${PUPWAVE_HDF5_INCLUDE_DIR}")
  file(STRINGS ${PUPWAVE_HDF5_INCLUDE_DIR}/H5public.h hdf5_version_line REGEX "#define H5_VERS_INFO")
  string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" PUPWAVE_HDF5_VERSION "${hdf5_version_line}")
endif()
pupwave_component(hdf5 PUPWAVE_BUILD_HDF5 "the HDF5 filter plugin" "HDF5 headers ${PUPWAVE_HDF5_VERSION}")

# --- python: the Python module ----------------------------------------------------------------
if(PUPWAVE_BUILD_PYTHON)
  # The Debian interpreter (whose dist-packages hold python3-numpy and python3-pytest) unless the
  # caller names another with -DPython_EXECUTABLE: a pyenv shim first in PATH must not win.
  if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python for the module and its tests")
  endif()
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  pupwave_require(PUPWAVE_BUILD_PYTHON "pybind11-dev python3-dev" "pybind11 and the Python headers"
                  "${pybind11_FOUND}")
endif()
pupwave_component(python PUPWAVE_BUILD_PYTHON "the Python module"
                  "pybind11 ${pybind11_VERSION}, Python ${Python_VERSION}")

# --- oiio_plugin: pw.imageio.so for OpenImageIO programs (found with the tools) ----------------
pupwave_component(oiio_plugin PUPWAVE_BUILD_OIIO_PLUGIN "OpenImageIO's .pw plugin"
                  "OpenImageIO ${OpenImageIO_VERSION}")

# --- tests and benchmarks -----------------------------------------------------------------------
if(PUPWAVE_BUILD_TESTS)
  find_package(GTest QUIET)
  pupwave_require(PUPWAVE_BUILD_TESTS "libgtest-dev libgmock-dev" "GoogleTest" "${GTest_FOUND}")
endif()
if(PUPWAVE_BUILD_BENCH)
  find_package(benchmark QUIET)
  pupwave_require(PUPWAVE_BUILD_BENCH libbenchmark-dev "Google Benchmark" "${benchmark_FOUND}")
endif()

# Prints the component table; called at the end of the top-level CMakeLists.
function(pupwave_component_summary)
  set(extras "")
  foreach(opt TESTS BENCH FUZZERS SANITIZE)
    if(PUPWAVE_BUILD_${opt} OR (opt STREQUAL "SANITIZE" AND PUPWAVE_SANITIZE))
      string(TOLOWER ${opt} name)
      list(APPEND extras ${name})
    endif()
  endforeach()
  string(REPLACE ";" ", " extras "${extras}")
  if(extras STREQUAL "")
    set(extras "nothing else")
  endif()
  message(STATUS "Pupwave ${PROJECT_VERSION} components:")
  foreach(line IN LISTS PUPWAVE_COMPONENT_LINES)
    message(STATUS "${line}")
  endforeach()
  message(STATUS "  also built: ${extras}")
endfunction()
