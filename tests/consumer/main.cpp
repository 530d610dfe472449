// A pendulum built with the mo2d API: a link pivoted at the ground with a 1 kg point mass at its
// tip, an actuated pivot, and the inverse dynamics for a prescribed angle theta(t).
#include <cmath>
#include <cstdio>
#include <mo2d/mo2d.hpp>
#include <vector>

int main() {
  using namespace mo2d;
  const double L = 1.0, mass = 1.0, g = 9.81;

  System s("pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {L, 0}}},
              .mass = mass,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O", .actuated = true});
  s.add_coordinate({.name = "link.angle", .rate = {{"link.w", 1.0}}});
  s.set_gravity({0, -g});

  const Model model = build_model(s);
  std::printf("%s: %d coordinates, %d quasi-velocities, DOF %d\n", model.name.c_str(), model.n0,
              model.n1, model.dof);

  // theta(t) evaluated on a Jet gives theta, theta' and theta'' exactly.
  const std::vector<Prescribed> motion = {{"link.angle", [](Jet t) { return 0.5 * sin(3.0 * t); }}};
  InverseOptions run;
  run.t0 = 0;
  run.t1 = 2;
  run.samples = 201;
  const Trajectory r = inverse_dynamics(model, motion, run);

  // Compare the pivot torque with the closed form m L^2 theta'' + m g L cos(theta).
  const int u = r.effort("pivot.torque");
  double max_error = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const double t = r.time[k];
    const double th = 0.5 * std::sin(3 * t), th_dd = -4.5 * std::sin(3 * t);
    const double expected = mass * L * L * th_dd + mass * g * L * std::cos(th);
    max_error = std::fmax(max_error, std::abs(r.efforts(k, u) - expected));
  }
  std::printf("pivot.torque: %d samples, max |error| vs closed form = %.3g N m\n",
              static_cast<int>(r.time.size()), max_error);
  return model.dof == 1 && max_error < 1e-9 ? 0 : 1;
}
