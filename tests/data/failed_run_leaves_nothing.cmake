# ctest helper: a run that fails while writing its outputs leaves none of them.
# -DMO2D=exe -DSCENE=pendulum.yaml -DDIR=out: DIR/pendulum_inverse.json is made a folder, so the
# JSON cannot be written; the CSV (written first) must not be left either, nor a temporary.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/pendulum_inverse.json")
execute_process(COMMAND "${MO2D}" inverse "${SCENE}" --out "${DIR}" RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "status ${status}\n${out}${err}")
if(status EQUAL 0)
  message(FATAL_ERROR "expected a failure")
endif()
if(NOT err MATCHES "mo2d: error: .*pendulum_inverse.json")
  message(FATAL_ERROR "the error does not name the file: ${err}")
endif()
file(GLOB left LIST_DIRECTORIES true "${DIR}/*" "${DIR}/.*")
list(REMOVE_ITEM left "${DIR}/pendulum_inverse.json")
if(left)
  message(FATAL_ERROR "files left by a failed run: ${left}")
endif()
