# ctest helper: the mo2d executable (-DEXE=...) must not list Cairo, the X11/xcb chain nor Box2D
# among its shared libraries (they are loaded by the drawing module only, apps/draw_module.hpp).
execute_process(COMMAND readelf -d "${EXE}" OUTPUT_VARIABLE out RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "readelf -d ${EXE} failed (${status})")
endif()
string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*" needed "${out}")
message(STATUS "${needed}")
foreach(lib cairo X11 xcb fontconfig box2d)
  if("${needed}" MATCHES "${lib}")
    message(FATAL_ERROR "${EXE} links ${lib}")
  endif()
endforeach()
