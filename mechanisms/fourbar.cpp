// Crank-rocker four-bar under gravity (Grashof: 0.1 + 0.4 < 0.35 + 0.3), crank driven at
// 1 rev/s from the vertical position.
#include <cmath>
#include <numbers>

#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

Example fourbar() {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4;
  const Vec2 A0(0, 0), B0(d, 0), A(0, a);
  // B: upper intersection of the circles (A, b) and (B0, c)
  const Vec2 AB0 = B0 - A;
  const double l = AB0.norm();
  const double x = (b * b - c * c + l * l) / (2 * l);
  const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
  const Vec2 B = A + x * ex + std::sqrt(b * b - x * x) * ey;

  System s("fourbar");
  s.add_ground_node("A0", A0).add_ground_node("B0", B0);
  s.add_body({.name = "crank",
              .nodes = {{"O", A0}, {"A", A}},
              .mass = 0.2,
              .inertia = 0.2 * a * a / 12,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "coupler",
              .nodes = {{"A", A}, {"B", B}},
              .mass = 0.5,
              .inertia = 0.5 * b * b / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "rocker",
              .nodes = {{"O", B0}, {"B", B}},
              .mass = 0.4,
              .inertia = 0.4 * c * c / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity({0, -9.81});

  Example e{std::move(s), {}, {}};
  e.motion.push_back(
      {"crank.angle", [](Jet t) { return std::numbers::pi / 2 + 2 * std::numbers::pi * t; }});
  e.run.t0 = 0;
  e.run.t1 = 2;
  e.run.samples = 401;
  return e;
}

}  // namespace mo2d::mechanisms
