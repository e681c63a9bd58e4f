# Runs GENERATOR, writes its standard output to OUTPUT and fails unless OUTPUT equals the
# COMMITTED file byte for byte.
# Usage: cmake -DGENERATOR=exe -DCOMMITTED=file -DOUTPUT=file -P check_generated.cmake
execute_process(COMMAND ${GENERATOR} OUTPUT_FILE ${OUTPUT} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} failed (${status})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUTPUT} ${COMMITTED} RESULT_VARIABLE differs)
if(NOT differs EQUAL 0)
  message(FATAL_ERROR "${COMMITTED} is not what ${GENERATOR} prints (its output: ${OUTPUT}); "
                      "regenerate it: ${GENERATOR} > ${COMMITTED}")
endif()
