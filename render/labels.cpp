// Label placement without overlap (labels.hpp): a greedy search over a fixed list of places.
#include "labels.hpp"

#include <array>

namespace mo2d::detail {

bool overlaps(const LabelBox& a, const LabelBox& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

namespace {

bool inside(const LabelBox& a, const LabelBox& bounds) {
  return a.x >= bounds.x && a.y >= bounds.y && a.x + a.w <= bounds.x + bounds.w &&
         a.y + a.h <= bounds.y + bounds.h;
}

}  // namespace

std::vector<LabelBox> place_labels(const std::vector<Vec2>& anchors, const std::vector<Vec2>& sizes,
                                   double gap, const LabelBox& bounds) {
  // directions on screen (y down): up-right, down-right, up-left, down-left, up, down, right, left
  constexpr std::array<std::array<double, 2>, 8> dirs{
      {{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {0, -1}, {0, 1}, {1, 0}, {-1, 0}}};
  std::vector<LabelBox> placed;
  placed.reserve(anchors.size());
  for (size_t i = 0; i < anchors.size(); ++i) {
    const double w = sizes[i].x(), h = sizes[i].y();
    LabelBox first{}, chosen{};
    bool found = false;
    for (int ring = 0; ring < 4 && !found; ++ring) {
      const double r = gap * (1 + 1.5 * ring);
      for (size_t d = 0; d < dirs.size() && !found; ++d) {
        const double dx = dirs[d][0], dy = dirs[d][1];
        // the box's nearest side (or corner) at distance r from the anchor along the direction
        const double cx = anchors[i].x() + dx * (r + 0.5 * w),
                     cy = anchors[i].y() + dy * (r + 0.5 * h);
        const LabelBox b{cx - 0.5 * w, cy - 0.5 * h, w, h};
        if (ring == 0 && d == 0) first = b;
        bool free = inside(b, bounds);
        for (const LabelBox& p : placed) free = free && !overlaps(b, p);
        if (free) chosen = b, found = true;
      }
    }
    placed.push_back(found ? chosen : first);
  }
  return placed;
}

}  // namespace mo2d::detail
