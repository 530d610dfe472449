// Applied loads (point forces, forces between nodes, torques) in inverse dynamics, against a
// closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

// Loads: a point mass pendulum with a time-dependent force at the tip and a torque on the link.
// Closed form: tau = m L^2 th'' + m g L cos(th) - (r x F) - T.
TEST(Loads, ForceAtAPointAndTorqueOnABody) {
  const double L = 0.9, mass = 1.7, g = 9.81;
  auto ex = mechanisms::pendulum({.L = L, .m = mass, .g = g, .theta0 = 0.4});
  System s = ex.system;
  auto fx = [](double t) { return 2.0 * std::cos(t); };
  auto fy = [](double t) { return -1.0 + 0.5 * t; };
  auto T = [](double t) { return 0.3 * std::sin(3 * t); };
  s.add_force({.name = "push",
               .body = "link",
               .point = {L * std::cos(0.4), L * std::sin(0.4)},
               .fx = fx,
               .fy = fy});
  s.add_torque({.name = "twist", .body = "link", .torque = T});
  const Model model = build_model(s);
  const Trajectory res = inverse_dynamics(model, ex.motion, ex.run);
  for (int i = 0; i < res.time.size(); ++i) {
    const double t = res.time[i];
    const Jet th = ex.motion[0].motion(Jet(t, 1, 0));
    const double rx = L * std::cos(th.v), ry = L * std::sin(th.v);
    const double moment = rx * fy(t) - ry * fx(t);
    const double tau = mass * L * L * th.dd + mass * g * L * std::cos(th.v) - moment - T(t);
    EXPECT_NEAR(res.efforts(i, 0), tau, 1e-10) << "t = " << t;
  }
}

// A force at a point between the nodes of a bar (given as a point, converted to gamma/rho):
// a bar pivoted at one end, force F(t) perpendicular at 60 % of its length, no gravity.
TEST(Loads, ForceBetweenNodesAndCentreOfMassAsPoint) {
  const double L = 2.0, mass = 3.0;
  System s("bar");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"E", {L, 0}}},
              .mass = mass,
              .inertia = mass * L * L / 12,
              .com = CenterOfMass::at_point({L / 2, 0})});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O", .actuated = true});
  s.add_coordinate({.name = "angle", .rate = {{"bar.w", 1}}});
  s.add_force({.name = "f",
               .body = "bar",
               .point = {0.6 * L, 0.1},
               .fx = [](double) { return 0.0; },
               .fy = [](double t) { return 1.0 + t; }});
  const Model model = build_model(s);
  auto th = [](Jet t) { return 0.5 * t * t; };  // angle'' = 1
  const Trajectory res = inverse_dynamics(model, std::vector<Prescribed>{{"angle", th}},
                                          {.t0 = 0, .t1 = 1, .samples = 11});
  for (int i = 0; i < res.time.size(); ++i) {
    const double t = res.time[i], a = 0.5 * t * t;
    // point (0.6 L, 0.1) in the body frame rotated by a
    const double px = 0.6 * L * std::cos(a) - 0.1 * std::sin(a);
    const double moment = px * (1.0 + t);  // r x F with F = (0, 1 + t)
    EXPECT_NEAR(res.efforts(i, 0), mass * L * L / 3 * 1.0 - moment, 1e-11) << "t = " << t;
  }
}
