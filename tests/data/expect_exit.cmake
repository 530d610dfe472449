# ctest helper: run PROGRAM with ARGS (a ;-list), fail unless it exits with status EXIT and its
# standard output matches REGEX (ctest's PASS_REGULAR_EXPRESSION alone ignores the exit status).
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT status EQUAL EXIT)
  message(FATAL_ERROR "exit status ${status}, expected ${EXIT}\n${out}\n${err}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}':\n${out}\n${err}")
endif()
