// Drawing primitives of mechanism figures (pixels, y down).
#include "symbols.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "canvas.hpp"

namespace mo2d::detail {

namespace {

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

Rgb dark_shade(const Rgb& c) {
  return mix(c, {0, 0, 0}, 0.28);
}
Rgb light_tint(const Rgb& c) {
  return mix(c, {1, 1, 1}, 0.55);
}

void draw_body(cairo_t* cr, const std::vector<Vec2>& hull, const Rgb& colour, double width,
               double line) {
  if (hull.empty()) return;
  auto path = [&] {
    cairo_move_to(cr, hull[0].x(), hull[0].y());
    if (hull.size() == 1) cairo_line_to(cr, hull[0].x(), hull[0].y());
    for (size_t k = 1; k < hull.size(); ++k) cairo_line_to(cr, hull[k].x(), hull[k].y());
    if (hull.size() >= 3) cairo_close_path(cr);
  };
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  path();
  set_colour(cr, dark_shade(colour));
  cairo_set_line_width(cr, width);
  cairo_stroke_preserve(cr);
  set_colour(cr, light_tint(colour));
  cairo_set_line_width(cr, std::max(width - 2 * line, 0.0));
  cairo_stroke_preserve(cr);
  if (hull.size() >= 3) cairo_fill(cr);
  cairo_new_path(cr);
}

void draw_com(cairo_t* cr, const Vec2& c, double r, const Rgb& ink, double line) {
  const double pi = std::numbers::pi;
  cairo_new_path(cr);
  cairo_arc(cr, c.x(), c.y(), r, 0, 2 * pi);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_fill(cr);
  set_colour(cr, ink);
  for (double a0 : {-pi / 2, pi / 2}) {  // upper-right and lower-left quadrants (y down)
    cairo_move_to(cr, c.x(), c.y());
    cairo_arc(cr, c.x(), c.y(), r, a0, a0 + pi / 2);
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  cairo_arc(cr, c.x(), c.y(), r, 0, 2 * pi);
  cairo_set_line_width(cr, line);
  cairo_stroke(cr);
}

void draw_pin(cairo_t* cr, const Vec2& c, double r, const Rgb& fill, const Rgb& ink, double line) {
  cairo_new_path(cr);
  cairo_arc(cr, c.x(), c.y(), r, 0, 2 * std::numbers::pi);
  set_colour(cr, fill);
  cairo_fill_preserve(cr);
  set_colour(cr, ink);
  cairo_set_line_width(cr, line);
  cairo_stroke(cr);
}

void draw_hatched_line(cairo_t* cr, const Vec2& a, const Vec2& b, const Vec2& side, double depth,
                       const Rgb& ink, double line) {
  set_colour(cr, ink);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_set_line_width(cr, 1.4 * line);
  cairo_move_to(cr, a.x(), a.y());
  cairo_line_to(cr, b.x(), b.y());
  cairo_stroke(cr);
  const double len = (b - a).norm();
  if (len <= 0) return;
  const Vec2 e = (b - a) / len;
  const Vec2 slant = (side - e).normalized() * depth * std::sqrt(2.0);
  const double spacing = std::max(depth * 0.8, 2.0);
  cairo_set_line_width(cr, 0.7 * line);
  for (double s = spacing * 0.5 + depth; s <= len + 1e-9; s += spacing) {
    const Vec2 p = a + s * e;
    cairo_move_to(cr, p.x(), p.y());
    cairo_line_to(cr, p.x() + slant.x(), p.y() + slant.y());
  }
  cairo_stroke(cr);
}

void draw_ground_pivot(cairo_t* cr, const Vec2& c, double r, const Rgb& ink, double line) {
  const double h = 2.9 * r, w = 1.9 * r;
  cairo_new_path(cr);
  cairo_move_to(cr, c.x(), c.y());
  cairo_line_to(cr, c.x() - w, c.y() + h);
  cairo_line_to(cr, c.x() + w, c.y() + h);
  cairo_close_path(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_fill_preserve(cr);
  set_colour(cr, ink);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  cairo_set_line_width(cr, line);
  cairo_stroke(cr);
  const double half = w + 1.1 * r;
  draw_hatched_line(cr, {c.x() - half, c.y() + h}, {c.x() + half, c.y() + h}, {0, 1}, 0.9 * r, ink,
                    line);
}

void draw_arrow_head(cairo_t* cr, const Vec2& tip, const Vec2& dir, double length,
                     double half_width) {
  const Vec2 n(-dir.y(), dir.x());
  const Vec2 base = tip - length * dir;
  cairo_new_path(cr);
  cairo_move_to(cr, tip.x(), tip.y());
  cairo_line_to(cr, base.x() + half_width * n.x(), base.y() + half_width * n.y());
  cairo_line_to(cr, base.x() - half_width * n.x(), base.y() - half_width * n.y());
  cairo_close_path(cr);
  cairo_fill(cr);
}

}  // namespace mo2d::detail
