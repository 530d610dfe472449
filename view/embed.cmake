# cmake -DIN=viewer.html -DOUT=viewer_template.cpp -P embed.cmake: the page as a C++ raw string.
file(READ ${IN} page)
string(FIND "${page}" ")mo2d_page\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw string's end )mo2d_page\"")
endif()
file(WRITE ${OUT}.tmp "// Generated from view/viewer.html by view/embed.cmake: do not edit.\n"
  "#include \"viewer_template.hpp\"\n"
  "namespace mo2d::detail {\n"
  "const char* const kViewerTemplate = R\"mo2d_page(${page})mo2d_page\";\n"
  "}  // namespace mo2d::detail\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUT}.tmp)
