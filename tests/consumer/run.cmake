# Installs the build tree into a scratch prefix, then configures, builds and runs the consumer
# project against it, and runs the installed command.
# Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR, GRAPH, FRONTEND.
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

# A graph-only consumer (COMPONENTS graph): built, run, and no Ceres on its compile or link lines.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer_graph -B ${WORK_DIR}/graph_build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/graph_build)
run(${WORK_DIR}/graph_build/graph_consumer ${FRONTEND})
file(READ ${WORK_DIR}/graph_build/compile_commands.json compile_line)
file(GLOB_RECURSE link_files ${WORK_DIR}/graph_build/CMakeFiles/graph_consumer.dir/link.txt)
file(READ ${link_files} link_line)
foreach(line compile_line link_line)
  string(TOLOWER "${${line}}" lowered)
  if(lowered MATCHES "ceres")
    message(FATAL_ERROR "the graph-only consumer's ${line} names Ceres:\n${${line}}")
  endif()
endforeach()
if(NOT compile_line MATCHES "-std=(c|gnu)\\+\\+17")
  message(FATAL_ERROR "the C++14 consumer of dynslam::graph was not compiled as C++17:\n${compile_line}")
endif()
