# cmake -D SOURCE_DIR=... -D BINARY_DIR=... -D PREFIX=<install prefix> [-D BUILD_TYPE=...]
#       [-D C_COMPILER=... -D CXX_COMPILER=... -D COMPILER_LAUNCHER=...] -P BuildConsumer.cmake
# Configures, builds and runs the consumer project against the package installed in PREFIX.
function (run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed: ${result}")
  endif ()
endfunction ()

file(REMOVE_RECURSE "${BINARY_DIR}")
set(options
  "-DCMAKE_PREFIX_PATH=${PREFIX}"
  "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  "-DCMAKE_C_COMPILER=${C_COMPILER}"
  "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
if (COMPILER_LAUNCHER)
  list(APPEND options "-DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER}")
endif ()
run("configuring the consumer"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" ${options})
run("building the consumer" "${CMAKE_COMMAND}" --build "${BINARY_DIR}")
run("running the consumer" "${BINARY_DIR}/savr_consumer")
