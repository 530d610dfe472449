#pragma once
// Internal: numbers in messages.
#include <string>

namespace mo2d::detail {

std::string fmt(double v);              // 6 significant digits (std::ostream precision 6)
std::string fmt(double v, int digits);  // `digits` significant digits (as printf's %.<digits>g)

}  // namespace mo2d::detail
