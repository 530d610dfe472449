// Inverse dynamics with contacts (issue 35, item 3; mo2d/contact_inverse.hpp, docs/contact.md,
// "Inverse dynamics"): the shipped cam follower through the scene path (scene_inverse_model,
// inverse_dynamics, scene_inverse_contacts, as `mo2d inverse` and Python run it) against the
// closed form of its contact force, and the contacts a prescribed motion closes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

struct InverseWithContacts {
  Scene scene;
  ContactInverseModel held;
  Trajectory r;
};

InverseWithContacts inverse_of(Scene scene) {
  InverseWithContacts out{std::move(scene), {}, {}};
  out.held = scene_inverse_model(out.scene);
  const InverseOptions run = inverse_options(out.scene);
  out.r = inverse_dynamics(out.held.model, out.scene.motion, run);
  scene_inverse_contacts(out.scene, out.held.model, out.held.contacts, run, out.r);
  return out;
}

InverseWithContacts cam_follower_at(double omega) {
  char set[64];
  std::snprintf(set, sizeof set, "omega=%.17g", omega);
  const ParameterOverride o[] = {parse_override(set)};
  return inverse_of(load_scene(MO2D_MECHANISMS_DIR "/cam_follower.yaml", o));
}

// The cam follower held on its cam (mechanisms/cam_follower.yaml's header): the face at y = R + ecc
// sin(w t), so the contact force is N(t) = m g + P0 + ecc (k - m w^2) sin(w t). Below the critical
// speed (83.55 rad/s) it stays positive: no warning, its least value m g + P0 - ecc (m w^2 - k) at
// the top of the lift (w t = pi/2). Above it, it is negative from sin(w t) = (m g + P0) / (ecc
// (m w^2 - k)) on, the time the forward run's follower lifts off, and the extra force that
// prevents it is -min N = ecc (m w^2 - k) - m g - P0.
TEST(ContactInverse, CamFollowerForceFollowsTheClosedForm) {
  for (const double w : {80.0, 100.0}) {
    SCOPED_TRACE("omega = " + std::to_string(w));
    const InverseWithContacts run = cam_follower_at(w);
    const Scene& s = run.scene;
    const double m = parameter(s, "m"), g = parameter(s, "g"), P0 = parameter(s, "P0"),
                 ecc = parameter(s, "ecc"), k = parameter(s, "k");
    auto N = [&](double t) { return m * g + P0 + ecc * (k - m * w * w) * std::sin(w * t); };
    const double scale = m * g + P0 + ecc * std::abs(k - m * w * w);
    EXPECT_EQ(run.held.model.dof, 0);  // the follower's one DOF held by the contact
    ASSERT_EQ(run.held.contacts.size(), 1u);
    const InverseContact& c = run.held.contacts[0];
    EXPECT_TRUE(c.held);
    EXPECT_EQ(c.column, "cam.normal_force");
    const int col = run.r.reaction(c.column);
    ASSERT_GE(col, 0);
    ASSERT_GT(run.r.time.size(), 100);
    for (Eigen::Index i = 0; i < run.r.time.size(); ++i)
      ASSERT_NEAR(run.r.reactions(i, col), N(run.r.time[i]), 1e-9 * scale)
          << "t = " << run.r.time[i];
    const double least = m * g + P0 - ecc * (m * w * w - k);
    EXPECT_NEAR(c.min_force, least, 1e-9 * scale);
    EXPECT_NEAR(c.t_min, M_PI / 2 / w, 1e-6 / w);
    int warnings = 0;
    for (const std::string& x : run.r.stats.warnings)
      warnings += x.find("contact 'cam'") != std::string::npos;
    if (w < 83.55) {
      EXPECT_FALSE(c.pulls);
      EXPECT_TRUE(std::isnan(c.t_negative));
      EXPECT_EQ(c.preload, 0);
      EXPECT_EQ(warnings, 0);
    } else {
      const double lift = std::asin((m * g + P0) / (ecc * (m * w * w - k))) / w;
      EXPECT_TRUE(c.pulls);
      EXPECT_NEAR(c.t_negative, lift, 1e-9 * lift);
      EXPECT_NEAR(c.preload, -least, 1e-9 * scale);
      EXPECT_EQ(warnings, 1);
    }
  }
}

// The same lift-off time as the forward run's (its closed form to 1e-9 of the time:
// docs/contact.md): the inverse run's first negative force is where a free follower leaves the cam.
TEST(ContactInverse, FirstNegativeForceIsTheForwardRunsLiftOff) {
  const InverseWithContacts inv = cam_follower_at(100);
  const Scene& scene = inv.scene;
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  const SceneRun fwd = scene_forward(scene, model, initial_state(scene, model), o);
  ASSERT_FALSE(fwd.events.empty());
  EXPECT_EQ(fwd.events[0].kind, ContactEvent::Kind::lift_off);
  EXPECT_NEAR(inv.held.contacts[0].t_negative, fwd.events[0].t, 1e-9 * fwd.events[0].t);
}

// A bar of length L pivoted at one end, its tip (a circle of radius r) on the floor: held by the
// floor, N = m g / 2 (moments about the pivot). The same bar above the floor, turned by its
// pivot, actuated: turned up, the contact open at the start stays open and out of the run; turned
// down through the floor, the motion closes it: refused at the located time, sin(t) = (y0 - r) / L.
std::string bar(double y0, bool actuated) {
  char text[1024];
  std::snprintf(text, sizeof text, R"(name: bar
parameters: {y0: %.17g, L: 1, r: 0.05, m: 2}
ground: {O: [0, y0], F1: [-1, 0], F2: [3, 0]}
bodies:
  bar:
    nodes: {O: [0, y0], T: [L, y0]}
    mass: m
    inertia: m * L^2 / 12
    com: {between: [O, T], gamma: 0.5}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: bar.O, actuated: %s}
coordinates:
  bar.angle: {rate: {bar.w: 1}}
loads: {gravity: [0, -9.81]}
contacts:
  floor: {point: bar.T, radius: r, line: [ground.F1, ground.F2], law: rigid, restitution: 0.5}
run: {solve: inverse, duration: 1, samples: 11}
)",
                y0, actuated ? "true" : "false");
  return text;
}

TEST(ContactInverse, ContactsHeldAndContactsClosedByTheMotion) {
  {
    const InverseWithContacts run = inverse_of(parse_scene(bar(0.05, false)));
    ASSERT_TRUE(run.held.contacts[0].held);
    EXPECT_EQ(run.held.model.dof, 0);
    const int col = run.r.reaction("floor.normal_force");
    ASSERT_GE(col, 0);
    for (Eigen::Index i = 0; i < run.r.time.size(); ++i)
      EXPECT_NEAR(run.r.reactions(i, col), 2 * 9.81 / 2, 1e-12);
    EXPECT_FALSE(run.held.contacts[0].pulls);
  }
  {  // turned up: the contact open at the start stays open, left out (its least gap: at t = 0)
    const InverseWithContacts run =
        inverse_of(parse_scene(bar(0.5, true) + "motion: {bar.angle: t}\n"));
    ASSERT_FALSE(run.held.contacts[0].held);
    EXPECT_EQ(run.held.model.dof, 1);
    EXPECT_NEAR(run.held.contacts[0].min_gap, 0.45, 1e-12);
    EXPECT_EQ(run.held.contacts[0].t_min_gap, 0);
  }
  try {
    (void)inverse_of(parse_scene(bar(0.5, true) + "motion: {bar.angle: -t}\n"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "floor");
    EXPECT_NEAR(e.time(), std::asin(0.45), 1e-12);
    EXPECT_NE(std::string(e.what()).find("closes it at t = 0.4667653"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mo2d
