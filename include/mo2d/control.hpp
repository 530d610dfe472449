#pragma once
// Controllers: an input effort written as feedback on the state, a Law (mo2d/law.hpp) that
// ForwardOptions::efforts takes like any other:
//   u(t) = u_ff(t) + kp (r(t) - x) + kd (r'(t) - x')      (PD on a coordinate x, reference r)
// with r' exact (the reference is evaluated on a Jet). With the exact feed-forward
// u_ff = the inverse-dynamics effort of the motion r (efforts_from_inverse), r is a solution
// of the closed loop and the tracking error stays at integration accuracy; without it, the
// error of a one-DOF mechanism follows e'' + (kd / m*) e' + (kp / m*) e = (what u_ff leaves out)
// / m*, m* its generalized inertia along x.
#include <functional>
#include <string>

#include "mo2d/jet.hpp"
#include "mo2d/law.hpp"

namespace mo2d {

// A PD controller with feed-forward on one input: u = u_ff(t) + kp (r(t) - q) + kd (r'(t) - v), q
// the controlled coordinate and v its rate (docs/scene-format.md, controllers); pd_control() makes
// its Law.
struct PdControl {
  std::string coordinate{};  // the controlled coordinate label ("crank.angle", "slide.q")
  std::string rate{};        // its quasi-velocity label; empty: rate_label(coordinate)
  std::function<Jet(Jet t)> reference{};           // r(t); empty: 0
  double kp = 0;                                   // N m / rad (a rotation) or N / m (a length)
  double kd = 0;                                   // N m s / rad or N s / m
  std::function<double(double t)> feed_forward{};  // u_ff(t); empty: 0
};

// The law of c (an Error if a gain is negative or not finite, naming the coordinate).
Law pd_control(PdControl c);

// The quasi-velocity label of a coordinate label, as build_model numbers them: "crank.A.x" ->
// "crank.A.vx", "rail.q" -> "rail.v", an extra coordinate "crank.angle" -> "crank.angle.rate".
std::string rate_label(const std::string& coordinate);

}  // namespace mo2d
