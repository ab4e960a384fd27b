# Installs the build tree into a scratch prefix, then configures, builds and runs the consumer
# project against it, and runs the installed command.
# Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR, GRAPH.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer ${GRAPH})
# The installed command, and the embedded data it finds beside itself (share/dynslam/).
run(${WORK_DIR}/prefix/bin/dynslam --version)
run(${WORK_DIR}/prefix/bin/dynslam simulate --seq 0003 --frames 0:3 --out ${WORK_DIR}/simulated)
if(NOT EXISTS ${WORK_DIR}/simulated.g2o)
  message(FATAL_ERROR "the installed dynslam simulate wrote no ${WORK_DIR}/simulated.g2o")
endif()
