# ctest driver for "readme.example": the first ```cpp block of README.md must be identical to
# tests/consumer/readme_main.cpp, which consumer.find_package compiles and runs on the README's
# fourbar.yaml, so the README's example is known to compile and to work.
#   cmake -DREADME=README.md -DMAIN=tests/consumer/readme_main.cpp -P check_readme.cmake
include(${CMAKE_CURRENT_LIST_DIR}/readme_block.cmake)
file(READ "${MAIN}" main)
readme_block("${README}" "```cpp" example)
if(NOT example STREQUAL main)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/readme_example.cpp" "${example}")
  message(FATAL_ERROR "The first ```cpp block of ${README} differs from ${MAIN} (written to "
                      "${CMAKE_CURRENT_BINARY_DIR}/readme_example.cpp): update one from the other")
endif()
message(STATUS "README example is identical to ${MAIN}")
