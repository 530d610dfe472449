// Whitworth quick-return mechanism, Orsino (2016) §5.3.1 (errata: the fourth ground node is
// (0.001, 0.8), so the slide line is y = 0.8). Mo2DPack bodies: 0 ground, 1 slider, 2 rod,
// 3 slotted lever, 4 crank. The crank (actuated at ground node O2) drives a pin that slides in
// the lever's slot; the lever drives the rod, the rod drives the slider along y = 0.8.
#include <numbers>

#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

Example whitworth() {
  System s("whitworth");
  s.add_ground_node("O1", {0.0, 0.0})        // lever pivot
      .add_ground_node("O2", {0.0, 0.3})     // crank pivot
      .add_ground_node("S1", {0.0, 0.8})     // slide axis from S1 ...
      .add_ground_node("S2", {0.001, 0.8});  // ... towards S2

  s.add_body({.name = "slider", .nodes = {{"P", {0.8, 0.8}}}, .mass = 1.0, .inertia = 0.0});
  s.add_body({.name = "rod",
              .nodes = {{"A", {0.8, 0.8}}, {"B", {0.15, 0.6}}},
              .mass = 0.2,
              .inertia = 0.2 * 0.1 * 0.1 / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "lever",
              .nodes = {{"O", {0.0, 0.0}}, {"B", {0.15, 0.6}}},
              .mass = 0.4,
              .inertia = 0.2 * 0.5 * 0.5 / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0.0, 0.3}}, {"A", {0.1, 0.4}}},
              .mass = 0.2,
              .inertia = 0.2 * 0.1 * 0.1 / 3,
              .com = CenterOfMass::at_node("O")});

  s.add_prismatic(
      {.name = "slide", .axis_from = "ground.S1", .axis_to = "ground.S2", .slider = "slider.P"});
  s.add_revolute({.name = "rod_slider", .node_a = "slider.P", .node_b = "rod.A"});
  s.add_revolute({.name = "rod_lever", .node_a = "rod.B", .node_b = "lever.B"});
  s.add_revolute({.name = "lever_pivot", .node_a = "ground.O1", .node_b = "lever.O"});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.O2", .node_b = "crank.O", .actuated = true});
  s.add_pin_in_slot(
      {.name = "crank_pin", .axis_from = "lever.O", .axis_to = "lever.B", .pin = "crank.A"});
  // Mo2DPack's AddCoordinate: d/dt crank.angle = crank.w, starting at 0
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}, .initial = 0.0});

  Example e{std::move(s), {}, {}};
  e.motion.push_back({"crank.angle", [](Jet t) { return (std::numbers::pi / 2) * t; }});
  e.run.t0 = 0;
  e.run.t1 = 16;
  e.run.samples = 501;
  return e;
}

}  // namespace mo2d::mechanisms
