#pragma once
// The picture of an inverse cross-check (mo2d crosscheck, crosscheck_picture.cpp): panels stacked
// in one PNG so that a gap of 0.1 % can be seen.
#include <string>
#include <vector>

#include "mo2d/crosscheck.hpp"
#include "mo2d/render/plot.hpp"

namespace mo2d::cli {

// The panels, top to bottom: mo2d (solid) and Box2D (dashed) efforts; their difference
// Box2D - mo2d; when the report has reactions, the magnitude of every joint's reaction force
// (mo2d solid, Box2D dashed) and its difference |F_box2d| - |F_mo2d|.
std::vector<Plot> crosscheck_panels(const CrosscheckReport& r);
// The panels stacked into `path` (PNG, atomic); returns the number of panels.
int write_crosscheck_picture(const CrosscheckReport& r, const std::string& path);

}  // namespace mo2d::cli
