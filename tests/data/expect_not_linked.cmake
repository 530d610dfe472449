# ctest helper: the mo2d executable (-DEXE=...) must not list Cairo, the X11/xcb chain nor Box2D
# among its shared libraries (they are loaded by the drawing module only, apps/draw_module.hpp);
# with -DLIBS=a,b,... it must not list those instead (the ones linked statically, CMakeLists.txt
# MO2D_CLI_STATIC_DEPS).
execute_process(COMMAND readelf -d "${EXE}" OUTPUT_VARIABLE out RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "readelf -d ${EXE} failed (${status})")
endif()
string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*" needed "${out}")
message(STATUS "${needed}")
if(DEFINED LIBS)
  string(REPLACE "," ";" LIBS "${LIBS}")
else()
  set(LIBS cairo X11 xcb fontconfig box2d)
endif()
foreach(lib ${LIBS})
  if("${needed}" MATCHES "${lib}")
    message(FATAL_ERROR "${EXE} links ${lib}")
  endif()
endforeach()
