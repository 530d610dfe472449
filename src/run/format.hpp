#pragma once
// Internal: numbers in messages.
#include <string>

namespace mo2d::detail {

std::string fmt(double v);  // 6 significant digits (std::ostream precision 6)

}  // namespace mo2d::detail
