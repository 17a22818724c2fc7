# Builds and runs tests/packaging/consumer.cpp, an outside project, against the fremond package:
#   ROUTE=build_tree  find_package(fremond) with fremond_DIR set to the build tree (no install);
#   ROUTE=install     the build tree installed into a scratch prefix, found through CMAKE_PREFIX_PATH.
# Both use the library already built, so the test costs one small compile.
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "packaging step failed: ${shown}\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${BINARY_DIR})
set(consumer_args -S ${CONSUMER_DIR} -B ${BINARY_DIR}/consumer -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
if(COMPILER_LAUNCHER)
  list(APPEND consumer_args -DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER})
endif()
if(ROUTE STREQUAL "build_tree")
  run_step(${CMAKE_COMMAND} ${consumer_args} -Dfremond_DIR=${PROJECT_BINARY_DIR})
elseif(ROUTE STREQUAL "install")
  set(prefix ${BINARY_DIR}/prefix)
  run_step(${CMAKE_COMMAND} --install ${PROJECT_BINARY_DIR} --prefix ${prefix})
  run_step(${CMAKE_COMMAND} ${consumer_args} -DCMAKE_PREFIX_PATH=${prefix})
else()
  message(FATAL_ERROR "ROUTE must be build_tree or install, not '${ROUTE}'")
endif()
run_step(${CMAKE_COMMAND} --build ${BINARY_DIR}/consumer)
run_step(${BINARY_DIR}/consumer/consumer)
message(STATUS "consumer printed: ${step_output}")
