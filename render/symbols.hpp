#pragma once
// Drawing primitives of mechanism figures, in pixels: rounded body outlines, the centre-of-mass
// symbol, hatched ground, arrow heads. Internal to mo2d_render.
#include <cairo.h>

#include <vector>

#include "mo2d/render/image.hpp"
#include "mo2d/system.hpp"

namespace mo2d::detail {

// Convex hull, counter-clockwise in its own coordinates (Andrew's monotone chain); collinear and
// repeated points removed.
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

// A body: the hull of its nodes stroked `width` wide with round joins (a bar for two nodes, a
// rounded polygon for more, a disc for one), outlined in a dark shade of `colour` and filled with
// a light tint.
void draw_body(cairo_t* cr, const std::vector<Vec2>& hull, const Rgb& colour, double width,
               double line);
Rgb dark_shade(const Rgb& c);
Rgb light_tint(const Rgb& c);

// Quartered circle: white with the first and third quadrants in ink.
void draw_com(cairo_t* cr, const Vec2& c, double r, const Rgb& ink, double line);
// A circle filled with `fill`, outlined in ink.
void draw_pin(cairo_t* cr, const Vec2& c, double r, const Rgb& fill, const Rgb& ink, double line);
// A ground line from a to b with hatching on the side of `side` (unit vector, pixels).
void draw_hatched_line(cairo_t* cr, const Vec2& a, const Vec2& b, const Vec2& side, double depth,
                       const Rgb& ink, double line);
// A ground pivot below the joint at c: a triangle down to a hatched base.
void draw_ground_pivot(cairo_t* cr, const Vec2& c, double r, const Rgb& ink, double line);
// A filled arrow head with its tip at `tip` pointing along `dir` (unit).
void draw_arrow_head(cairo_t* cr, const Vec2& tip, const Vec2& dir, double length,
                     double half_width);

}  // namespace mo2d::detail
