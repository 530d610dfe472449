#pragma once
// Pictures of vibration modes (mo2d modes): the mechanism at + and - amplitude along a mode drawn
// by the project's renderer (mo2d/render.hpp) and superposed (the darker pixel wins) over the
// equilibrium, drawn faded; and a filmstrip of one period.
#include <string>

#include "mo2d/model.hpp"
#include "mo2d/modes.hpp"

namespace mo2d::cli {

// amplitude: the largest node displacement (m). Written atomically (PNG); returns the path.
std::string write_mode_picture(const Model& m, const StateSpace& ss, const Mode& mode,
                               double amplitude, const std::string& path);
// Eight tiles over one period (of omega_d; 1 s for a mode that does not oscillate).
std::string write_mode_filmstrip(const Model& m, const StateSpace& ss, const Mode& mode,
                                 double amplitude, const std::string& path);

}  // namespace mo2d::cli
