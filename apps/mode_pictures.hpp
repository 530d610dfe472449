#pragma once
// Pictures of vibration modes (mo2d modes): the mechanism at + and - amplitude along a mode drawn
// by the project's renderer (mo2d/render.hpp) and superposed (the darker pixel wins) over the
// equilibrium, drawn faded; and a filmstrip of one period.
#include <string>

#include "mo2d/model.hpp"
#include "mo2d/modes.hpp"

namespace mo2d::cli {

// "mode 2: 3.41 Hz, damping ratio 0.052" (not oscillatory: its real eigenvalue): the title of
// both pictures of mode `number` (1-based).
std::string mode_title(const Mode& mode, int number);
// amplitude: the largest node displacement (m). Written atomically (PNG); returns the path.
std::string write_mode_picture(const Model& m, const StateSpace& ss, const Mode& mode, int number,
                               double amplitude, const std::string& path);
// Eight tiles over one period (of omega_d; 1 s for a mode that does not oscillate).
std::string write_mode_filmstrip(const Model& m, const StateSpace& ss, const Mode& mode, int number,
                                 double amplitude, const std::string& path);

}  // namespace mo2d::cli
