// Offset slider-crank: crank O-A (actuated at O), rod A-B, slider B on the line y = e.
#include <cmath>

#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

Example slider_crank(const SliderCrankParams& p) {
  System s("slider_crank");
  const double xb = p.r + std::sqrt(p.L * p.L - p.e * p.e);  // crank along +x at t = 0
  s.add_ground_node("O", {0, 0}).add_ground_node("R1", {0, p.e}).add_ground_node("R2", {1, p.e});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {p.r, 0}}},
              .mass = p.m_crank,
              .inertia = p.m_crank * p.r * p.r / 12,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "rod",
              .nodes = {{"A", {p.r, 0}}, {"B", {xb, p.e}}},
              .mass = p.m_rod,
              .inertia = p.m_rod * p.L * p.L / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "slider", .nodes = {{"B", {xb, p.e}}}, .mass = p.m_slider});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "rod.A"});
  s.add_revolute({.name = "wrist_pin", .node_a = "rod.B", .node_b = "slider.B"});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "slider.B"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity({0, -p.gravity});

  Example e{std::move(s), {}, {}};
  const double w = p.omega;
  e.motion.push_back({"crank.angle", [w](Jet t) { return w * t; }});
  e.run.t0 = 0;
  e.run.t1 = 1;
  e.run.samples = 201;
  return e;
}

}  // namespace mo2d::mechanisms
