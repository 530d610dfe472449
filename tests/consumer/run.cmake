# ctest driver for "consumer.find_package": install the current mo2d build into a fresh prefix,
# then configure, build and run the stand-alone consumer project (this folder) against it.
#
#   cmake -DMO2D_BUILD_DIR=<mo2d build tree> -DWORK_DIR=<scratch dir> -DCONSUMER_DIR=<this dir>
#         -DREADME=<README.md, whose fourbar.yaml the README's C++ example reads> [-DBUILD_TYPE=Release] [-DCXX_COMPILER=...] [-DSANITIZE_FLAGS="-fsanitize=..."]
#         -P run.cmake
#
# SANITIZE_FLAGS: an mo2d built with MO2D_SANITIZE=ON is instrumented, and its static libraries
# need the sanitizer runtimes at link time, so the consumer is compiled and linked with the same
# flags (that is what a user of a sanitized build has to do too).
foreach(var MO2D_BUILD_DIR WORK_DIR CONSUMER_DIR README)
  if(NOT ${var})
    message(FATAL_ERROR "run.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

function(step name)
  message(STATUS "consumer test: ${name}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out
                  WORKING_DIRECTORY "${WORK_DIR}")
  if(NOT rc EQUAL 0)
    message("${out}")
    message(FATAL_ERROR "consumer test: '${name}' failed (${rc})")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

step("install mo2d into ${prefix}"
  "${CMAKE_COMMAND}" --install "${MO2D_BUILD_DIR}" --prefix "${prefix}" --config "${BUILD_TYPE}")

set(configure_args
  -S "${CONSUMER_DIR}" -B "${build}"
  "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  "-DCMAKE_PREFIX_PATH=${prefix}"
  -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(CXX_COMPILER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
if(SANITIZE_FLAGS)
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=${SANITIZE_FLAGS}"
       "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE_FLAGS}")
endif()
step("configure the consumer project" "${CMAKE_COMMAND}" ${configure_args})

# The package must come from the fresh prefix, not from a build tree or a system install.
file(STRINGS "${build}/CMakeCache.txt" mo2d_dir_line REGEX "^mo2d_DIR:")
string(REGEX REPLACE "^mo2d_DIR:[A-Z]+=" "" mo2d_dir "${mo2d_dir_line}")
file(REAL_PATH "${prefix}" real_prefix)
file(REAL_PATH "${mo2d_dir}" real_mo2d_dir)
string(FIND "${real_mo2d_dir}" "${real_prefix}/" pos)
if(NOT pos EQUAL 0)
  message(FATAL_ERROR "consumer test: mo2d was found in '${mo2d_dir}', not under '${prefix}'")
endif()
message(STATUS "consumer test: mo2d_DIR = ${mo2d_dir}")

step("build the consumer project" "${CMAKE_COMMAND}" --build "${build}")
step("run the consumer" "${build}/pendulum")
message("${step_output}")
if(NOT step_output MATCHES "DOF 1")
  message(FATAL_ERROR "consumer test: unexpected output (no 'DOF 1')")
endif()
# The README's scene block (```yaml {file=fourbar.yaml}) next to the README's C++ example.
include(${CMAKE_CURRENT_LIST_DIR}/readme_block.cmake)
readme_block("${README}" "```yaml {file=fourbar.yaml}" scene)
file(WRITE "${WORK_DIR}/fourbar.yaml" "${scene}")
step("run the README's example" "${build}/readme_fourbar")
message("${step_output}")
if(NOT step_output MATCHES "work per revolution")
  message(FATAL_ERROR "consumer test: unexpected output of readme_fourbar")
endif()
step("run the scene consumer" "${build}/scene_pendulum")
message("${step_output}")
if(NOT step_output MATCHES "scene pendulum: DOF 1")
  message(FATAL_ERROR "consumer test: unexpected output of scene_pendulum")
endif()
message(STATUS "consumer test: passed")
