// Simple pendulum: a massless link O-P with a point mass at P (centre of mass at node P, zero
// centroidal inertia), pivot actuated for inverse dynamics.
#include <cmath>

#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

Example pendulum(const PendulumParams& p) {
  System s("pendulum");
  const Vec2 tip(p.L * std::cos(p.theta0), p.L * std::sin(p.theta0));
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", tip}},
              .mass = p.m,
              .inertia = 0.0,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O", .actuated = true});
  s.add_coordinate({.name = "link.angle", .rate = {{"link.w", 1.0}}});
  s.set_gravity({0, -p.g});
  Example e{std::move(s), {}, {}};
  const double th0 = p.theta0;
  e.motion.push_back({"link.angle", [th0](Jet t) { return th0 + 0.5 * sin(3.0 * t) + t * t; }});
  e.run.t0 = 0;
  e.run.t1 = 2;
  e.run.samples = 201;
  return e;
}

}  // namespace mo2d::mechanisms
