// IFToMM benchmark double four-bar: five uniform bars of 1 m and 1 kg (three cranks pivoted on the
// ground at x = 0, 1, 2, two couplers), cranks vertical and couplers horizontal at t = 0, gravity
// 9.81 m/s^2 downward, crank tips moving at 1 m/s in +x (crank rate -1 rad/s). Whenever the bars
// lie horizontal all joints are collinear and the constraint Jacobian loses rank.
#include "mo2d/mechanisms.hpp"

namespace mo2d::mechanisms {

System double_fourbar() {
  System s("double_fourbar");
  const double m = 1.0, L = 1.0, I = m * L * L / 12;
  const std::string crank[3] = {"crank0", "crank1", "crank2"};
  const std::string pivot[3] = {"O0", "O1", "O2"};
  for (int k = 0; k < 3; ++k) {
    s.add_ground_node(pivot[k], {double(k), 0.0});
    s.add_body({.name = crank[k],
                .nodes = {{"O", {double(k), 0.0}}, {"B", {double(k), L}}},
                .mass = m,
                .inertia = I,
                .com = CenterOfMass::between("O", "B", 0.5)});
    s.add_revolute(
        {.name = crank[k] + "_pivot", .node_a = "ground." + pivot[k], .node_b = crank[k] + ".O"});
  }
  const std::string coupler[2] = {"coupler1", "coupler2"};
  for (int k = 0; k < 2; ++k) {
    s.add_body({.name = coupler[k],
                .nodes = {{"A", {double(k), L}}, {"B", {double(k + 1), L}}},
                .mass = m,
                .inertia = I,
                .com = CenterOfMass::between("A", "B", 0.5)});
    s.add_revolute(
        {.name = coupler[k] + "_left", .node_a = crank[k] + ".B", .node_b = coupler[k] + ".A"});
    s.add_revolute({.name = coupler[k] + "_right",
                    .node_a = crank[k + 1] + ".B",
                    .node_b = coupler[k] + ".B"});
  }
  s.set_gravity({0, -9.81});
  return s;
}

}  // namespace mo2d::mechanisms
