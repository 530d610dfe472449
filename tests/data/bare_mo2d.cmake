# ctest helper: a bare `mo2d` (no arguments) in an empty folder DIR prints its help, exits 0 and
# writes nothing (it ran the demo into ./out/ before).
#   -DMO2D=path of mo2d   -DDIR=scratch folder (emptied first)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
execute_process(COMMAND ${MO2D} WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE status
  OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "exit status ${status}, expected 0\n${out}\n${err}")
endif()
if(NOT out MATCHES "Usage:.*demo.*inverse.*forward.*plot")
  message(FATAL_ERROR "no help on stdout:\n${out}\n${err}")
endif()
file(GLOB_RECURSE left LIST_DIRECTORIES true "${DIR}/*")
if(left)
  message(FATAL_ERROR "a bare mo2d wrote ${left}")
endif()
