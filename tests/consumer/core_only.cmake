# ctest api.core_only_configure: the library configures with Eigen, oneTBB and zstd alone.
# Every other component is off and its packages are hidden from find_package; the generated
# CMake package and pkg-config file then list only the library, and asking the package for a
# component that was not built fails with a message naming it. A wanted component whose package
# is missing stops the configure with the Debian package to install.
# Arguments: -DSOURCE_DIR= -DWORK_DIR=
file(REMOVE_RECURSE ${WORK_DIR})
set(hidden "")
foreach(p OpenImageIO OpenEXR Imath OpenVDB CLI11 nlohmann_json pybind11 Python GTest benchmark OpenMesh HDF5)
  list(APPEND hidden -DCMAKE_DISABLE_FIND_PACKAGE_${p}=ON)
endforeach()
function(configure dir expect_rc)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/${dir} ${hidden} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc AND NOT (expect_rc STREQUAL "fail" AND NOT rc EQUAL 0))
    message(FATAL_ERROR "configure ${dir} ${ARGN}: exit ${rc}\n${out}\n${err}")
  endif()
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

configure(core 0 -DPUPWAVE_BUILD_TOOLS=OFF -DPUPWAVE_BUILD_HDF5=OFF -DPUPWAVE_BUILD_PYTHON=OFF
          -DPUPWAVE_HDF5_INCLUDE_DIR=PUPWAVE_HDF5_INCLUDE_DIR-NOTFOUND)
foreach(line "library \\(transforms, codec\\) +yes" "cli \\(the pupwave CLI\\) +no" "also built: nothing else")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "the component summary lacks '${line}':\n${out}")
  endif()
endforeach()
file(READ ${WORK_DIR}/core/pupwave.pc pc)
if(NOT pc MATCHES "\ncomponents=library\n")
  message(FATAL_ERROR "pupwave.pc does not say components=library:\n${pc}")
endif()
file(GLOB makefiles ${WORK_DIR}/core/tools/* ${WORK_DIR}/core/tests/*)
if(makefiles)
  message(FATAL_ERROR "the library-only configure generated tools or tests: ${makefiles}")
endif()

# The package of that build: the library is there, the CLI is not.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/components -B ${WORK_DIR}/want_library
                        -DPupwave_DIR=${WORK_DIR}/core -DWANT=library RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "Pupwave components: library")
  message(FATAL_ERROR "find_package(Pupwave COMPONENTS library) failed on the library-only build:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/components -B ${WORK_DIR}/want_cli
                        -DPupwave_DIR=${WORK_DIR}/core -DWANT=cli RESULT_VARIABLE rc OUTPUT_VARIABLE out
                        ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "built without the component cli")
  message(FATAL_ERROR "find_package(Pupwave COMPONENTS cli) did not fail on the library-only build:\n${out}${err}")
endif()

# The CLI wanted without OpenImageIO: the configure names the Debian package.
configure(missing fail -DPUPWAVE_BUILD_HDF5=OFF -DPUPWAVE_BUILD_PYTHON=OFF)
string(REGEX REPLACE "[ \n]+" " " out "${out}")  # CMake wraps its error messages
if(NOT out MATCHES "PUPWAVE_BUILD_TOOLS needs OpenImageIO: install the Debian package libopenimageio-dev")
  message(FATAL_ERROR "a missing OpenImageIO was not reported with its package:\n${out}")
endif()
message(STATUS "library-only configure: components=library; a missing package names its Debian package")
