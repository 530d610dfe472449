// IFToMM benchmark double four-bar: five uniform bars of 1 m and 1 kg (three cranks pivoted on the
// ground at x = 0, 1, 2, two couplers), cranks vertical and couplers horizontal at t = 0, gravity
// 9.81 m/s^2 downward, crank tips moving at 1 m/s in +x (crank rate -1 rad/s). Whenever the bars
// lie horizontal all joints are collinear and the constraint Jacobian loses rank.
#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

System double_fourbar() {
  System s("double_fourbar");
  const double m = 1.0, L = 1.0, I = m * L * L / 12;
  for (int k = 0; k < 3; ++k) {
    const std::string c = "crank" + std::to_string(k);
    s.add_ground_node("O" + std::to_string(k), {double(k), 0.0});
    s.add_body({.name = c, .nodes = {{"O", {double(k), 0.0}}, {"B", {double(k), L}}}, .mass = m,
                .inertia = I, .com = CenterOfMass::between("O", "B", 0.5)});
    s.add_revolute({.name = c + "_pivot", .node_a = "ground.O" + std::to_string(k),
                    .node_b = c + ".O"});
  }
  for (int k = 0; k < 2; ++k) {
    const std::string c = "coupler" + std::to_string(k + 1);
    s.add_body({.name = c, .nodes = {{"A", {double(k), L}}, {"B", {double(k + 1), L}}}, .mass = m,
                .inertia = I, .com = CenterOfMass::between("A", "B", 0.5)});
    s.add_revolute({.name = c + "_left", .node_a = "crank" + std::to_string(k) + ".B",
                    .node_b = c + ".A"});
    s.add_revolute({.name = c + "_right", .node_a = "crank" + std::to_string(k + 1) + ".B",
                    .node_b = c + ".B"});
  }
  s.set_gravity({0, -9.81});
  return s;
}

}  // namespace mo2d::mechanisms
