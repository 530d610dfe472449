#pragma once
// The viewer page's template (view/viewer.html), embedded at build time (view/CMakeLists.txt).
// Its data slot, /*MO2D_DATA*/null, receives the run's JSON; <!--MO2D_TITLE--> the title.
namespace mo2d::detail {
extern const char* const kViewerTemplate;
}  // namespace mo2d::detail
