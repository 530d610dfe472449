#pragma once
// The example mechanisms of mo2d, written as a user would write them. Each returns the System and
// the prescribed motion of the inverse-dynamics run described with it.
#include <vector>

#include "mo2d/inverse.hpp"
#include "mo2d/system.hpp"

namespace mo2d::mechanisms {

struct Example {
  System system;
  std::vector<Prescribed> motion;  // as many coordinates as the mechanism has DOF
  InverseOptions run;              // time span and samples of the reference run
};

// Whitworth quick-return mechanism (Orsino §5.3.1): crank driven at pi/2 rad/s for 16 s.
Example whitworth();

// One RRR leg (ground pivot, actuated; proximal link; elbow; distal link ending at node "P"),
// defined once in its own frame and placed three times by rrr3().
System rrr3_leg();
// 3RRR parallel mechanism (Orsino §5.3.2) built from three instances of rrr3_leg().
Example rrr3();

// Offset slider-crank: crank r = 0.1 m, rod 0.35 m, offset 0.03 m, slider 1 kg, under gravity.
struct SliderCrankParams {
  double r = 0.1, L = 0.35, e = 0.03;
  double m_crank = 0.5, m_rod = 0.3, m_slider = 1.0;
  double omega = 4 * 3.14159265358979323846;  // crank speed, rad/s
  double gravity = 9.81;
};
Example slider_crank(const SliderCrankParams& p = {});

// Crank-rocker four-bar under gravity: ground 0.4 m, crank 0.1 m, coupler 0.35 m, rocker 0.3 m.
Example fourbar();

// Simple pendulum: point mass m at the tip of a massless link of length L, actuated pivot,
// released from angle theta0 (from +x, counter-clockwise), gravity -g y.
struct PendulumParams {
  double L = 1.0, m = 1.0, g = 9.81, theta0 = 0.0;
};
Example pendulum(const PendulumParams& p = {});

// IFToMM double four-bar (forward-dynamics benchmark): five 1 m, 1 kg bars; start with the crank
// rate "crank0.w" = -1 rad/s. Passive (no inputs).
System double_fourbar();

}  // namespace mo2d::mechanisms
