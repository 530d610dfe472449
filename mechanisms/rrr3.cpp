// 3RRR parallel mechanism, Orsino (2016) §5.3.2, as a tree of subsystems (Figure 2.8): one RRR
// leg defined once and placed three times (rotated by 0, 120 and 240 degrees) around a
// triangular platform. Errata: the prescribed coordinates are the platform centre x, y and the
// platform angle (pi/6) sin^4(pi t / 4); the platform's centre of mass is its node C.
#include <cmath>
#include <numbers>

#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

System rrr3_leg() {
  const double r3 = std::sqrt(3.0);
  System leg("rrr_leg");
  leg.add_ground_node("O", {3.0, 0.0});
  leg.add_body({.name = "proximal",
                .nodes = {{"O", {3.0, 0.0}}, {"E", {2.0, r3}}},
                .mass = 0.5,
                .inertia = 2.0 / 3.0,
                .com = CenterOfMass::at_node("O")});
  leg.add_body({.name = "distal",
                .nodes = {{"P", {1.0, 0.0}}, {"E", {2.0, r3}}},
                .mass = 0.5,
                .inertia = 1.0 / 6.0,
                .com = CenterOfMass::between("P", "E", 0.5)});
  leg.add_revolute(
      {.name = "pivot", .node_a = "ground.O", .node_b = "proximal.O", .actuated = true});
  leg.add_revolute({.name = "elbow", .node_a = "proximal.E", .node_b = "distal.E"});
  return leg;
}

Example rrr3() {
  const double r3 = std::sqrt(3.0);
  System s("rrr3");
  s.add_body({.name = "platform",
              .nodes = {{"C", {0.0, 0.0}},
                        {"P1", {1.0, 0.0}},
                        {"P2", {-0.5, r3 / 2}},
                        {"P3", {-0.5, -r3 / 2}}},
              .mass = 1.0,
              .inertia = 0.25,
              .com = CenterOfMass::at_node("C")});
  const System leg = rrr3_leg();
  for (int k = 0; k < 3; ++k) {
    const std::string name = "leg" + std::to_string(k + 1);
    s.add_instance(name, leg, Placement{{0.0, 0.0}, 2 * std::numbers::pi * k / 3});
    s.add_revolute({.name = "attach" + std::to_string(k + 1),
                    .node_a = "platform.P" + std::to_string(k + 1),
                    .node_b = name + ".distal.P"});
  }
  s.add_coordinate({.name = "platform.angle", .rate = {{"platform.w", 1.0}}, .initial = 0.0});

  Example e{std::move(s), {}, {}};
  const double pi = std::numbers::pi;
  e.motion.push_back({"platform.C.x", [pi](Jet t) { return -sin((pi / 2) * t); }});
  e.motion.push_back({"platform.C.y", [pi](Jet t) { return sin((pi / 4) * t); }});
  e.motion.push_back(
      {"platform.angle", [pi](Jet t) { return (pi / 6) * pow(sin((pi / 4) * t), 4); }});
  e.run.t0 = 0;
  e.run.t1 = 16;
  e.run.samples = 501;
  return e;
}

}  // namespace mo2d::mechanisms
