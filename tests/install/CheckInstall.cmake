# Installs ThinTool to a fresh prefix and builds examples/minimal against the installed package
# with find_package(ThinTool), then runs it; where the package has the haptic layer, does the same
# with tests/install/haptics (ThinTool::haptics). Invoked by CTest:
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -DSHARED=ON|OFF [-DBUILD_DIR=<built tree to install>]
#         [-DBULLET_DOUBLE=ON|OFF] -P CheckInstall.cmake
# Without BUILD_DIR the library is configured and built here first (the shared case).
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${output}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
if(NOT BUILD_DIR)
  set(BUILD_DIR ${WORK_DIR}/library)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=${SHARED}
      -DTHINTOOL_BULLET_DOUBLE=${BULLET_DOUBLE}
      -DTHINTOOL_BUILD_TESTS=OFF -DTHINTOOL_BUILD_EXAMPLES=OFF -DTHINTOOL_BUILD_BENCHMARKS=OFF)
  run(${CMAKE_COMMAND} --build ${BUILD_DIR} --parallel 2)
endif()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

if(SHARED)
  file(GLOB libraries ${prefix}/lib*/libthintool.so*)
else()
  file(GLOB libraries ${prefix}/lib*/libthintool.a)
endif()
if(NOT libraries)
  message(FATAL_ERROR "the installed prefix has no ThinTool library of the expected kind (shared=${SHARED})")
endif()

set(consumer ${WORK_DIR}/minimal)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/minimal -B ${consumer} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${consumer})
run(${consumer}/thintool_minimal)
message(STATUS "examples/minimal built against ${prefix} and ran")

# The haptic layer, where the package has it: a loop against a device, from the installed package.
file(GLOB hapticsLibraries ${prefix}/lib*/libthintool_haptics.*)
if(hapticsLibraries)
  set(hapticsConsumer ${WORK_DIR}/haptics)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/haptics -B ${hapticsConsumer} -DCMAKE_PREFIX_PATH=${prefix}
      -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${hapticsConsumer})
  run(${hapticsConsumer}/thintool_haptics_consumer)
  message(STATUS "a haptic loop built against ${prefix} and ran")
endif()
