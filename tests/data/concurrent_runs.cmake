# ctest helper: two runs into one --out folder at once leave the CSV and the JSON of one run, and
# no lock file.
# -DMO2D=exe -DSCENE=pendulum_samples_n.yaml -DDIR=out. Run A (n = 11) writes its CSV at once and
# its JSON 1.5 s later; run B (n = 21) writes both 0.5 s after it starts (MO2D_TEST_OUTPUT_DELAY,
# a test hook of mo2d/output.hpp). File by file, the folder would end with B's CSV and A's JSON.
file(REMOVE_RECURSE "${DIR}")
# (execute_process runs its commands at once, as a pipeline: A's stdout goes to a file, not to B)
execute_process(
  COMMAND sh -c "MO2D_TEST_OUTPUT_DELAY=0,1.5 exec \"$0\" inverse \"$1\" --set n=11 --out \"$2\" > \"$2.a.log\""
          "${MO2D}" "${SCENE}" "${DIR}"
  COMMAND env MO2D_TEST_OUTPUT_DELAY=0.5,0 "${MO2D}" inverse "${SCENE}" --set n=21 --out "${DIR}"
  RESULTS_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "status ${status}\n${out}${err}")
if(NOT status STREQUAL "0;0")
  message(FATAL_ERROR "a run failed: ${status}")
endif()
file(STRINGS "${DIR}/pendulum_inverse.csv" rows)
list(LENGTH rows n_rows)
math(EXPR csv_samples "${n_rows} - 1")
file(READ "${DIR}/pendulum_inverse.json" json)
string(JSON json_samples GET "${json}" samples)
string(JSON json_n GET "${json}" parameters n)
message(STATUS "CSV: ${csv_samples} samples; JSON: ${json_samples} samples (n = ${json_n})")
if(NOT csv_samples EQUAL json_samples)
  message(FATAL_ERROR "mixed outputs: the CSV has ${csv_samples} samples, the JSON ${json_samples}")
endif()
file(GLOB tmp "${DIR}/*.tmp.*" "${DIR}/.*.tmp.*")
if(tmp)
  message(FATAL_ERROR "temporaries left: ${tmp}")
endif()
# the folder's lock exists only while a run holds it (src/output/dir_lock.hpp)
if(EXISTS "${DIR}/.mo2d.lock")
  message(FATAL_ERROR "the lock file ${DIR}/.mo2d.lock was left behind")
endif()
