# Installs the library into a scratch prefix (library only, no tests), then configures, builds and
# runs tests/packaging/CMakeLists.txt against it with find_package(fremond).
file(REMOVE_RECURSE ${BINARY_DIR})
set(prefix ${BINARY_DIR}/prefix)
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE_DIR};-B;${BINARY_DIR}/lib;-DFREMOND_BUILD_TESTS=OFF;-DFREMOND_BUILD_CLI=OFF;-DFREMOND_BUILD_BENCHMARKS=OFF;-DFREMOND_BUILD_PYTHON=OFF;-DCMAKE_INSTALL_PREFIX=${prefix}"
    "${CMAKE_COMMAND};--build;${BINARY_DIR}/lib;-j2"
    "${CMAKE_COMMAND};--install;${BINARY_DIR}/lib"
    "${CMAKE_COMMAND};-S;${CONSUMER_DIR};-B;${BINARY_DIR}/consumer;-DCMAKE_PREFIX_PATH=${prefix}"
    "${CMAKE_COMMAND};--build;${BINARY_DIR}/consumer"
    "${BINARY_DIR}/consumer/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "packaging step failed: ${step}\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "consumer printed: ${out}")
