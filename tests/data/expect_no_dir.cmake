# ctest helper: fail if DIR exists and holds any file (a failed mo2d run must write nothing).
file(GLOB left "${DIR}/*")
if(left)
  message(FATAL_ERROR "files left by a failed run: ${left}")
endif()
