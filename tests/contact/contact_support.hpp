#pragma once
// Scenes of the contact tests: a ball over the ground, a pendulum rod, two balls, a free rod.
#include <Eigen/Core>
#include <string>

#include "mo2d/contact.hpp"
#include "mo2d/mo2d.hpp"

namespace contact_test {

using namespace mo2d;

// A ball (one node "ball.C", mass m, no rotation) at (x, y) over the ground line y = 0 from
// ground.L (-100, 0) to ground.R (100, 0) (free side y > 0), gravity (0, -g).
inline System ball_scene(double m, double x, double y, double g) {
  System s("ball");
  s.add_ground_node("L", {-100, 0});
  s.add_ground_node("R", {100, 0});
  s.add_body({.name = "ball", .nodes = {{"C", {x, y}}}, .mass = m});
  s.set_gravity({0, -g});
  return s;
}

// A uniform rod (length L, mass m) pinned at the ground origin O, lying along +x, with the ground
// points S1 (0, 1) and S2 (0, -2) of a stop line x = 0, gravity (0, -g): released, its tip B hits
// the stop when vertical.
inline Model stop_pendulum(double L, double m, double g) {
  System s("stop");
  s.add_ground_node("O", {0, 0});
  s.add_ground_node("S1", {0, 1});
  s.add_ground_node("S2", {0, -2});
  s.add_body({.name = "rod",
              .nodes = {{"O", {0, 0}}, {"B", {L, 0}}},
              .mass = m,
              .inertia = m * L * L / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "rod.O"});
  s.set_gravity({0, -g});
  return build_model(s);
}

// The ground contact of the ball: a circle of radius r around ball.C against the line L -> R.
inline ContactDef ground_contact(double r, ContactLaw law) {
  return {.name = "floor",
          .point = "ball.C",
          .radius = r,
          .target = ContactDef::Target::line,
          .a = "ground.L",
          .b = "ground.R",
          .law = law};
}

// A state of m from its initial positions and the rates given by label (others 0).
inline State state_of(const Model& m, std::initializer_list<std::pair<std::string, double>> rates) {
  State s;
  s.q0 = m.q0;
  s.q1 = Eigen::VectorXd::Zero(m.n1);
  for (const auto& [label, v] : rates) s.q1[m.rate(label)] = v;
  return s;
}

inline ContactLaw compliant(double K, double n, double e) {
  ContactLaw l;
  l.kind = ContactLaw::Kind::compliant;
  l.stiffness = K;
  l.exponent = n;
  l.restitution = e;
  return l;
}

// dopri5 at rtol 1e-12, atol 1e-14 over [0, t1]: the contact tests' tight runs.
inline ForwardOptions tight(double t1, int samples) {
  return {.t0 = 0,
          .t1 = t1,
          .samples = samples,
          .integrator = Integrator::dopri5,
          .rtol = 1e-12,
          .atol = 1e-14};
}

inline ContactLaw rigid(double e) {
  ContactLaw l;
  l.kind = ContactLaw::Kind::rigid;
  l.restitution = e;
  return l;
}

}  // namespace contact_test
