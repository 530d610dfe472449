// Label placement (render/labels.hpp): labels of bodies that cross do not overlap.
#include "../../render/labels.hpp"

#include <gtest/gtest.h>

#include <random>

namespace {

using mo2d::Vec2;
using mo2d::detail::LabelBox;

// Many random scenes of up to 8 labels, anchors crowded in a small square (bodies crossing):
// no two boxes overlap, every box is inside the bounds.
TEST(RenderLabels, CrowdedLabelsDoNotOverlap) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> at(150, 250), width(20, 60);
  const LabelBox bounds{0, 0, 400, 400};
  for (int scene = 0; scene < 200; ++scene) {
    const int n = 2 + scene % 7;
    std::vector<Vec2> anchors, sizes;
    for (int i = 0; i < n; ++i) {
      anchors.emplace_back(at(rng), at(rng));
      sizes.emplace_back(width(rng), 11);
    }
    if (scene % 3 == 0) anchors.assign(n, Vec2(200, 200));  // all bodies cross at one point
    const std::vector<LabelBox> b = mo2d::detail::place_labels(anchors, sizes, 7, bounds);
    ASSERT_EQ(b.size(), static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      EXPECT_GE(b[i].x, 0);
      EXPECT_LE(b[i].x + b[i].w, 400);
      for (int j = 0; j < i; ++j)
        EXPECT_FALSE(mo2d::detail::overlaps(b[i], b[j]))
            << "scene " << scene << ": " << i << ", " << j;
    }
  }
}

TEST(RenderLabels, AFreeLabelGoesUpAndRightOfItsAnchor) {
  const auto b = mo2d::detail::place_labels({Vec2(100, 100)}, {Vec2(30, 10)}, 7, {0, 0, 400, 400});
  EXPECT_DOUBLE_EQ(b[0].x, 107);
  EXPECT_DOUBLE_EQ(b[0].y, 83);
}

}  // namespace
