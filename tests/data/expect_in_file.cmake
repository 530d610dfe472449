# ctest helper: fail unless FILE exists and contains TEXT.
if(NOT EXISTS "${FILE}")
  message(FATAL_ERROR "no file ${FILE}")
endif()
file(READ "${FILE}" content)
string(FIND "${content}" "${TEXT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${FILE} does not contain '${TEXT}'")
endif()
