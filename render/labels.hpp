#pragma once
// Where the body names go (FrameOptions::show_labels): each label beside its body, moved to the
// first free place around it so that no two labels overlap (bodies cross in many mechanisms:
// the Watt six-bar). Internal to mo2d_render.
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d::detail {

struct LabelBox {
  double x = 0, y = 0, w = 0, h = 0;  // top-left corner and size, pixels
};
bool overlaps(const LabelBox& a, const LabelBox& b);

// One box per label, in order: `sizes` (width, height) placed near `anchors` (pixels), at the
// first of the candidate places around the anchor (up-right first, then the other diagonals,
// above, below, the sides; at growing distances from `gap`) that overlaps no box placed before
// it and lies inside `bounds`; the first candidate when no place is free.
std::vector<LabelBox> place_labels(const std::vector<Vec2>& anchors, const std::vector<Vec2>& sizes,
                                   double gap, const LabelBox& bounds);

}  // namespace mo2d::detail
