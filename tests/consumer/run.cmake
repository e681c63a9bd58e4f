# ctest api.install_consumer: `cmake --install` the build into a temporary prefix, then build and
# run this consumer against it with find_package (shared and static) and with pkg-config (C),
# run the installed CLI (with its OIIO loader module) and import the installed Python module.
# Arguments: -DBUILD_DIR= -DSOURCE_DIR= -DWORK_DIR=
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST)
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(images ${SOURCE_DIR}/testimages)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f lib/libpupwave.a lib/cmake/Pupwave/PupwaveConfig.cmake lib/cmake/Pupwave/PupwaveConfigVersion.cmake
          lib/pkgconfig/pupwave.pc include/pupwave/pupwave.h include/pupwave/pupwave.hpp bin/pupwave)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/*)
if(NOT headers STREQUAL "pupwave/pupwave.h;pupwave/pupwave.hpp")
  message(FATAL_ERROR "installed headers are not only the public ones: ${headers}")
endif()

# The installed CLI converts a real PNG (through its OIIO module) for the consumer.
run(${prefix}/bin/pupwave convert ${images}/camera.png ${WORK_DIR}/camera.pgm)

# find_package(Pupwave): shared and static library.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
foreach(kind shared static)
  run(${WORK_DIR}/build/consumer_${kind} ${WORK_DIR}/camera.pgm ${images}/wmag91.float 91 91 91)
endforeach()

# pkg-config: the C consumer against the shared library.
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
execute_process(COMMAND pkg-config --cflags --libs pupwave OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs pupwave failed")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")

# The package describes exactly what was installed: each component's files exist if and only if
# the .pc file's components (and PupwaveConfig.cmake's Pupwave_COMPONENTS) list it.
execute_process(COMMAND pkg-config --variable=components pupwave OUTPUT_VARIABLE components
                OUTPUT_STRIP_TRAILING_WHITESPACE)
set(marker_library lib/libpupwave.a)
set(marker_cli bin/pupwave)
set(marker_vdb bin/libpupwave_vdb.so)
set(marker_hdf5 lib/hdf5/plugins/libh5pupwave.so)
set(marker_python lib/python3/dist-packages/pupwave/__init__.py)
set(marker_oiio_plugin lib/openimageio/pw.imageio.so)
separate_arguments(components UNIX_COMMAND "${components}")
foreach(c library cli vdb hdf5 python oiio_plugin)
  set(listed FALSE)
  if(c IN_LIST components)
    set(listed TRUE)
  endif()
  set(present FALSE)
  if(EXISTS ${prefix}/${marker_${c}})
    set(present TRUE)
  endif()
  if(NOT listed STREQUAL present)
    message(FATAL_ERROR "component ${c}: listed in pupwave.pc ${listed}, ${marker_${c}} installed ${present}")
  endif()
endforeach()
file(READ ${prefix}/lib/cmake/Pupwave/PupwaveConfig.cmake config)
string(REPLACE ";" " " components_text "${components}")
string(REPLACE " " ";" components_cmake "${components_text}")
if(NOT config MATCHES "set\\(Pupwave_COMPONENTS \"${components_cmake}\"\\)")
  message(FATAL_ERROR "PupwaveConfig.cmake does not list the components ${components_text}")
endif()
run(cc -std=c99 -o ${WORK_DIR}/consumer_c ${SOURCE_DIR}/tests/consumer/consumer.c ${flags} -lm)
set(ENV{LD_LIBRARY_PATH} ${prefix}/lib)
run(${WORK_DIR}/consumer_c ${images}/wmag91.float 91 91 91)

# The installed Python package.
if(EXISTS ${prefix}/lib/python3/dist-packages/pupwave/__init__.py)
  set(ENV{PYTHONPATH} ${prefix}/lib/python3/dist-packages)
  run(${PYTHON} -c "import numpy, pupwave; a = numpy.fromfile('${images}/wmag91.float', 'f4').reshape(91, 91, 91); \
b = pupwave.decompress_volume(pupwave.compress_volume(a, max_error=0.1)); assert abs(b - a).max() <= 0.1; \
print('installed python module', pupwave.__file__)")
endif()

# The installed OIIO plugin: oiiotool writes and reads .pw through it.
if(EXISTS ${prefix}/lib/openimageio/pw.imageio.so)
  set(ENV{OIIO_LIBRARY_PATH} ${prefix}/lib/openimageio)
  run(oiiotool ${images}/camera.png --attrib pupwave:bpp 1 -o ${WORK_DIR}/camera.pw)
  run(oiiotool ${WORK_DIR}/camera.pw -o ${WORK_DIR}/camera.exr)
  run(${prefix}/bin/pupwave info ${WORK_DIR}/camera.pw)
endif()
message(STATUS "installed tree works: find_package (shared, static), pkg-config, CLI")
