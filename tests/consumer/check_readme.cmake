# ctest driver for "readme.example": the first ```cpp block of README.md must be identical to
# tests/consumer/readme_main.cpp, which consumer.find_package compiles and runs on the README's
# fourbar.yaml, so the README's example is known to compile and to work.
#   cmake -DREADME=README.md -DMAIN=tests/consumer/readme_main.cpp -P check_readme.cmake
file(READ "${README}" readme)
file(READ "${MAIN}" main)
set(fence "```cpp\n")
string(FIND "${readme}" "${fence}" begin)
if(begin LESS 0)
  message(FATAL_ERROR "${README} has no ```cpp block")
endif()
string(LENGTH "${fence}" fence_length)
math(EXPR begin "${begin} + ${fence_length}")
string(SUBSTRING "${readme}" ${begin} -1 rest)
string(FIND "${rest}" "```" end)
if(end LESS 0)
  message(FATAL_ERROR "${README}: the first ```cpp block is not closed")
endif()
string(SUBSTRING "${rest}" 0 ${end} example)
if(NOT example STREQUAL main)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/readme_example.cpp" "${example}")
  message(FATAL_ERROR "The first ```cpp block of ${README} differs from ${MAIN} (written to "
                      "${CMAKE_CURRENT_BINARY_DIR}/readme_example.cpp): update one from the other")
endif()
message(STATUS "README example is identical to ${MAIN}")
