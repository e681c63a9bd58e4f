# Pupwave as a library (docs/api.md): the public C/C++ API (codec/include/pupwave/, implemented
# in codec/api/ inside pupwave_codec), the installed shared and static libraries, the CMake
# package and pkg-config file, the Python module and the OpenImageIO plugin, and their tests.
include(CMakePackageConfigHelpers)
enable_language(C)

# The codec goes into a shared library and Python/OIIO modules: compile it position independent.
set_target_properties(pupwave_codec pupwave_transforms PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_include_directories(pupwave_codec PUBLIC ${PROJECT_SOURCE_DIR}/codec/include)
target_compile_definitions(pupwave_codec PRIVATE PUPWAVE_VERSION_STRING="${PROJECT_VERSION}")

set(PUPWAVE_LIB_DIR ${CMAKE_BINARY_DIR}/lib)

# libpupwave.so: every codec object (the API entry points are referenced by nobody inside).
file(WRITE ${CMAKE_BINARY_DIR}/pupwave_shared_stub.cpp "// The shared library's objects come from pupwave_codec.\n")
add_library(pupwave_shared SHARED ${CMAKE_BINARY_DIR}/pupwave_shared_stub.cpp)
target_link_libraries(pupwave_shared PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,pupwave_codec>")
target_include_directories(pupwave_shared INTERFACE ${PROJECT_SOURCE_DIR}/codec/include)
set_target_properties(pupwave_shared PROPERTIES OUTPUT_NAME pupwave VERSION ${PROJECT_VERSION}
                      SOVERSION ${PROJECT_VERSION_MAJOR} LIBRARY_OUTPUT_DIRECTORY ${PUPWAVE_LIB_DIR})

# libpupwave.a: the codec and transforms archives merged into one (GNU ar MRI script).
set(PUPWAVE_STATIC ${PUPWAVE_LIB_DIR}/libpupwave.a)
file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/pupwave_static.mri CONTENT
"CREATE ${PUPWAVE_STATIC}
ADDLIB $<TARGET_FILE:pupwave_codec>
ADDLIB $<TARGET_FILE:pupwave_transforms>
SAVE
END
")
add_custom_command(OUTPUT ${PUPWAVE_STATIC}
                   COMMAND ${CMAKE_COMMAND} -E make_directory ${PUPWAVE_LIB_DIR}
                   COMMAND ${CMAKE_COMMAND} -E rm -f ${PUPWAVE_STATIC}
                   COMMAND ${CMAKE_AR} -M < ${CMAKE_BINARY_DIR}/pupwave_static.mri
                   DEPENDS pupwave_codec pupwave_transforms ${CMAKE_BINARY_DIR}/pupwave_static.mri
                   COMMENT "Merging libpupwave.a" VERBATIM)
add_custom_target(pupwave_static ALL DEPENDS ${PUPWAVE_STATIC})

# Install: libraries, public headers only, CMake package, pkg-config file, CLI + its loader module.
install(TARGETS pupwave_shared LIBRARY DESTINATION lib)
install(FILES ${PUPWAVE_STATIC} DESTINATION lib)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/codec/include/pupwave DESTINATION include)
if(PUPWAVE_BUILD_TOOLS)
  install(TARGETS pupwave RUNTIME DESTINATION bin)
  install(TARGETS pupwave_oiio LIBRARY DESTINATION bin)  # the CLI loads it from beside its binary
endif()
if(PUPWAVE_BUILD_VDB)
  install(TARGETS pupwave_vdb LIBRARY DESTINATION bin)  # likewise, for .vdb files
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/PupwaveConfig.cmake.in ${CMAKE_BINARY_DIR}/PupwaveConfig.cmake @ONLY)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/PupwaveConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/PupwaveConfig.cmake ${CMAKE_BINARY_DIR}/PupwaveConfigVersion.cmake
        DESTINATION lib/cmake/Pupwave)
string(REPLACE ";" " " PUPWAVE_COMPONENTS_PC "${PUPWAVE_COMPONENTS_BUILT}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/pupwave.pc.in ${CMAKE_BINARY_DIR}/pupwave.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/pupwave.pc DESTINATION lib/pkgconfig)

if(PUPWAVE_BUILD_PYTHON)
  add_subdirectory(${PROJECT_SOURCE_DIR}/tools/python ${CMAKE_BINARY_DIR}/python_module)
endif()
if(PUPWAVE_BUILD_OIIO_PLUGIN)
  add_subdirectory(${PROJECT_SOURCE_DIR}/tools/oiio_plugin ${CMAKE_BINARY_DIR}/oiio_plugin)
endif()

if(PUPWAVE_BUILD_TESTS)
  # The C API from a C program, against the shared library.
  add_executable(c_api_test ${PROJECT_SOURCE_DIR}/tests/api/c_api_test.c)
  target_link_libraries(c_api_test PRIVATE pupwave_shared m)
  set_target_properties(c_api_test PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON)
  target_compile_definitions(c_api_test PRIVATE PUPWAVE_TESTIMAGES_DIR="${PUPWAVE_TESTIMAGES_DIR}")
  add_test(NAME api.c_api COMMAND c_api_test)
  # Install to a temporary prefix, then build and run tests/consumer against it.
  add_test(NAME api.install_consumer
           COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${CMAKE_BINARY_DIR} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
                   -DWORK_DIR=${CMAKE_BINARY_DIR}/consumer_test -DPYTHON=${Python_EXECUTABLE} -P ${PROJECT_SOURCE_DIR}/tests/consumer/run.cmake)
  set_tests_properties(api.install_consumer PROPERTIES TIMEOUT 600)
  # The library configures alone (Eigen, oneTBB, zstd) and its package lists only the library.
  add_test(NAME api.core_only_configure
           COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DWORK_DIR=${CMAKE_BINARY_DIR}/core_only_test
                   -P ${PROJECT_SOURCE_DIR}/tests/consumer/core_only.cmake)
endif()

if(PUPWAVE_BUILD_BENCH)
  # The C++ side of bench/api_overhead.py (Python call path vs the library).
  add_executable(api_encode_timer ${PROJECT_SOURCE_DIR}/bench/api_encode_timer.cpp)
  target_link_libraries(api_encode_timer PRIVATE pupwave_codec)
  set_target_properties(api_encode_timer PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
endif()
