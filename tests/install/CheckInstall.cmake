# Installs ThinTool to a fresh prefix, checks that a shared library exports its API and not the
# stages' insides, and builds examples/minimal against the installed package with
# find_package(ThinTool), and again with the compiler and pkg-config's thintool module alone, and
# runs both; where the package has the haptic layer, does the same with tests/install/haptics
# (ThinTool::haptics, pkg-config's thintool-haptics). Invoked by CTest:
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

# A shared library exports the API (THINTOOL_API) and hides the stages' insides.
if(SHARED)
  find_program(NM NAMES nm REQUIRED)
  list(GET libraries 0 library)
  execute_process(COMMAND ${NM} -D -C --defined-only ${library} RESULT_VARIABLE result OUTPUT_VARIABLE symbols
                  ERROR_VARIABLE symbols)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "nm could not read ${library}: ${symbols}")
  endif()
  foreach(api IN ITEMS "thintool::addTool" "thintool::SoftBodySolver::SoftBodySolver" "typeinfo for thintool::Error")
    string(FIND "${symbols}" "${api}" at)
    if(at LESS 0)
      message(FATAL_ERROR "${library} does not export ${api}")
    endif()
  endforeach()
  foreach(internal IN ITEMS "thintool::detectSwept" "thintool::computeResponse" "thintool::separateFromPiece")
    string(FIND "${symbols}" "${internal}" at)
    if(NOT at LESS 0)
      message(FATAL_ERROR "${library} exports ${internal}, which is no part of the API")
    endif()
  endforeach()
  message(STATUS "${library} exports the API and hides the stages")
endif()

set(consumer ${WORK_DIR}/minimal)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/minimal -B ${consumer} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${consumer})
run(${consumer}/thintool_minimal)
message(STATUS "examples/minimal built against ${prefix} and ran")

# The same programs without CMake: the compiler and pkg-config's flags for the installed modules.
find_program(PKG_CONFIG NAMES pkg-config REQUIRED)
find_program(CXX NAMES c++ g++ REQUIRED)
file(GLOB pcDirs ${prefix}/lib*/pkgconfig ${prefix}/lib/*/pkgconfig)
list(JOIN pcDirs ":" pcPath)
if(DEFINED ENV{PKG_CONFIG_PATH} AND NOT "$ENV{PKG_CONFIG_PATH}" STREQUAL "")
  set(pcPath "${pcPath}:$ENV{PKG_CONFIG_PATH}")
endif()
set(ENV{PKG_CONFIG_PATH} "${pcPath}")
function(build_with_pkg_config module source output)
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs ${module} RESULT_VARIABLE result
                  OUTPUT_VARIABLE flags ERROR_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "pkg-config does not find ${module} under ${prefix}: ${flags}")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  set(rpath)
  if(SHARED)
    foreach(dir IN LISTS pcDirs)
      get_filename_component(libDir ${dir} DIRECTORY)
      list(APPEND rpath -Wl,-rpath,${libDir})
    endforeach()
  endif()
  run(${CXX} -std=c++17 -O1 ${source} -o ${output} ${flags} ${rpath})
  run(${output})
  message(STATUS "${source} built with pkg-config's ${module} and ran")
endfunction()
build_with_pkg_config(thintool ${SOURCE_DIR}/examples/minimal/main.cpp ${WORK_DIR}/minimal-pkg-config)

# The haptic layer, where the package has it: a loop against a device, from the installed package.
file(GLOB hapticsLibraries ${prefix}/lib*/libthintool_haptics.*)
if(hapticsLibraries)
  set(hapticsConsumer ${WORK_DIR}/haptics)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/haptics -B ${hapticsConsumer} -DCMAKE_PREFIX_PATH=${prefix}
      -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${hapticsConsumer})
  run(${hapticsConsumer}/thintool_haptics_consumer)
  message(STATUS "a haptic loop built against ${prefix} and ran")
  build_with_pkg_config(thintool-haptics ${SOURCE_DIR}/tests/install/haptics/main.cpp ${WORK_DIR}/haptics-pkg-config)
endif()
