#include <cmath>
#include <cstdio>
#include <mo2d/mo2d.hpp>
int main() {
  using namespace mo2d;
  System s("pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {1, 0}}},
              .mass = 1,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O", .actuated = true});
  s.add_coordinate({.name = "link.angle", .rate = {{"link.w", 1.0}}});
  s.set_gravity({0, -9.81});
  const Model model = build_model(s);
  const std::vector<Prescribed> motion = {{"link.angle", [](Jet t) { return 0.5 * sin(3.0 * t); }}};
  const Trajectory r = inverse_dynamics(model, motion, InverseOptions{});  // t in [0, 1] s
  double error = 0;  // against the closed form m L^2 theta'' + m g L cos(theta)
  for (int k = 0; k < r.time.size(); ++k) {
    const double theta = 0.5 * std::sin(3 * r.time[k]),
                 expected = -9 * theta + 9.81 * std::cos(theta);
    error = std::fmax(error, std::abs(r.efforts(k, r.effort("pivot.torque")) - expected));
  }
  std::printf("%s: DOF %d, pivot torque within %.1e N m of the closed form\n", model.name.c_str(),
              model.dof, error);
  return error < 1e-9 ? 0 : 1;
}
