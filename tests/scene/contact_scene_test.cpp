// Contacts in scene files (issue 35; docs/scene-format.md, "Contacts"): the shipped bouncing ball
// run through the scene path (parse_scene, scene_forward, as `mo2d forward` and Python run it)
// against the closed forms, with the same events as the C++ core's contact_dynamics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double scene_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

std::vector<ContactEvent> scene_events_of_kind(const SceneRun& r, ContactEvent::Kind k) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& e : r.events)
    if (e.kind == k) out.push_back(e);
  return out;
}

// mechanisms/bouncing_ball.yaml: dropped with its centre at h, radius r, restitution e. Impact k
// (k = 0, 1, ...) at t1 + 2 v1 (e + ... + e^k) / g, t1 = sqrt(2 (h - r) / g), v1 = g t1, at the
// approach speed v1 e^k and the separation speed v1 e^(k+1); the flight after it rises to the
// rebound height (h - r) e^(2(k+1)) above the floor, read from every sample inside that flight as
// y - r + vy^2 / (2 g) (ballistic). The impulse is m (1 + e) v1 e^k, the loss (1 - e^2) m (v1
// e^k)^2 / 2.
TEST(ContactScene, BouncingBallFollowsTheClosedForms) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/bouncing_ball.yaml");
  ASSERT_EQ(scene.contacts.size(), 1U);
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  check_scene_options(scene, model, o);
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  const double h = scene_parameter(scene, "h"), r = scene_parameter(scene, "r");
  const double m = scene_parameter(scene, "m"), e = scene_parameter(scene, "e");
  const double g = scene_parameter(scene, "g");
  const std::vector<ContactEvent> hits = scene_events_of_kind(run, ContactEvent::Kind::impact);
  ASSERT_GE(hits.size(), 20U);
  const double t1 = std::sqrt(2 * (h - r) / g), v1 = g * t1;
  const Trajectory& tr = run.trajectory;
  const int iy = tr.column("ball.C.y"), ivy = tr.rate_column("ball.C.vy");
  double t = t1;
  int flights_checked = 0;
  for (size_t k = 0; k < 20; ++k) {
    const double v = v1 * std::pow(e, static_cast<double>(k));
    EXPECT_NEAR(hits[k].t, t, 1e-9) << "impact " << k;
    EXPECT_EQ(hits[k].contact, "floor");
    EXPECT_NEAR(hits[k].speed, v, 1e-9 * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].speed_after, e * v, 1e-9 * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].impulse, m * (1 + e) * v, 1e-9 * m * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].energy_lost, 0.5 * m * v * v * (1 - e * e), 1e-9 * m * v1 * v1);
    const double next = t + 2 * e * v / g;
    const double height = (h - r) * std::pow(e, 2.0 * static_cast<double>(k + 1));
    for (Eigen::Index s = 0; s < tr.time.size(); ++s) {
      if (!(tr.time[s] > t + 1e-6 && tr.time[s] < next - 1e-6)) continue;
      const double vy = tr.q1(s, ivy);
      EXPECT_NEAR(tr.q0(s, iy) - r + vy * vy / (2 * g), height, 1e-9 * (h - r))
          << "flight after impact " << k << ", t = " << tr.time[s];
      ++flights_checked;
    }
    t = next;
  }
  EXPECT_GT(flights_checked, 200);
  // the accumulation at t_inf = t1 (1 + e) / (1 - e), then at rest on the floor
  const std::vector<ContactEvent> z = scene_events_of_kind(run, ContactEvent::Kind::zeno);
  ASSERT_EQ(z.size(), 1U);
  EXPECT_NEAR(z[0].predicted_t, t1 * (1 + e) / (1 - e), 1e-9);
  EXPECT_NEAR(tr.dissipated[tr.time.size() - 1], m * g * (h - r), 1e-9 * m * g * h);
}

// The scene path runs exactly the core's contact run: the same events as contact_dynamics with
// the scene's contacts and the method scene_forward reports.
TEST(ContactScene, SceneRunIsTheCoreContactRun) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/bouncing_ball.yaml");
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  const State initial = initial_state(scene, model);
  const SceneRun run = scene_forward(scene, model, initial, o);
  ContactOptions co = scene.contact;
  co.forward = o;
  const ContactRun core = contact_dynamics(model, scene.contacts, initial, co);
  ASSERT_EQ(run.events.size(), core.events.size());
  for (size_t k = 0; k < core.events.size(); ++k) {
    EXPECT_EQ(run.events[k].t, core.events[k].t) << k;
    EXPECT_EQ(run.events[k].speed, core.events[k].speed) << k;
  }
  EXPECT_NE(run.trajectory.stats.method.find("with contacts"), std::string::npos);
}

// mechanisms/cam_follower.yaml at omega: one turn of the cam through the scene path.
SceneRun cam_follower_at(double omega, Scene& scene) {
  char set[64];
  std::snprintf(set, sizeof set, "omega=%.17g", omega);
  const ParameterOverride o[] = {parse_override(set)};
  scene = load_scene(MO2D_MECHANISMS_DIR "/cam_follower.yaml", o);
  const Model model = build_scene_model(scene);
  const ForwardOptions run = forward_options(scene, model);
  check_scene_options(scene, model, run);
  return scene_forward(scene, model, initial_state(scene, model), run);
}

// The cam follower (see the scene's header): the contact force N = m g + P0 + ecc (k - m w^2)
// sin(w t) reaches 0 at the top of the lift at the critical speed w_c = sqrt((P0 + k ecc + m g) /
// (m ecc)), where the spring force and the weight equal the follower's mass times the cam's
// demanded acceleration ecc w^2. Below it: no event in a turn, the follower's face on the cam at
// y = R + ecc sin(w t) at every sample; above it: one lift-off in the turn, where sin(w t) = (m g +
// P0) / (ecc (m w^2 - k)), and each landing on the driven cam dissipates (1 - e^2) m v^2 / 2 (the
// cam's speed is imposed: the follower's mass alone) and leaves at e v.
TEST(ContactScene, CamFollowerLiftsOffAboveTheCriticalSpeed) {
  Scene scene;
  (void)cam_follower_at(100, scene);
  const double ecc = scene_parameter(scene, "ecc"), R = scene_parameter(scene, "R");
  const double m = scene_parameter(scene, "m"), k = scene_parameter(scene, "k");
  const double P0 = scene_parameter(scene, "P0"), g = scene_parameter(scene, "g");
  const double e = scene_parameter(scene, "e");
  const double wc = std::sqrt((P0 + k * ecc + m * g) / (m * ecc));
  for (const double ratio : {0.5, 0.9, 0.995, 1.005, 1.1, 1.5, 2.0}) {
    const double w = ratio * wc;
    const SceneRun run = cam_follower_at(w, scene);
    const std::vector<ContactEvent> off = scene_events_of_kind(run, ContactEvent::Kind::lift_off);
    const Trajectory& tr = run.trajectory;
    EXPECT_LT(std::abs(energy_balance_error(tr)), 1e-9) << "w / w_c = " << ratio;
    if (ratio < 1) {
      EXPECT_TRUE(run.events.empty()) << "w / w_c = " << ratio << ": " << run.events.size();
      const int iy = tr.column("follower.P.y");
      for (Eigen::Index s = 0; s < tr.time.size(); ++s)
        EXPECT_NEAR(tr.q0(s, iy), R + ecc * std::sin(w * tr.time[s]), 1e-9 * ecc)
            << "w / w_c = " << ratio << ", t = " << tr.time[s];
      continue;
    }
    ASSERT_EQ(off.size(), 1U) << "w / w_c = " << ratio;
    const double t_off = std::asin((m * g + P0) / (ecc * (m * w * w - k))) / w;
    EXPECT_NEAR(off[0].t, t_off, 1e-10) << "w / w_c = " << ratio;
    for (const ContactEvent& hit : scene_events_of_kind(run, ContactEvent::Kind::impact)) {
      const double v = hit.speed;
      EXPECT_GT(hit.t, off[0].t);
      // the Zeno accumulation's last impact is perfectly inelastic (e = 0, nothing after)
      const double ek = hit.speed_after == 0 ? 0 : e;
      EXPECT_NEAR(hit.energy_lost, (1 - ek * ek) * m * v * v / 2, 1e-9 * m * v * v + 1e-15)
          << "w / w_c = " << ratio << ", t = " << hit.t;
      EXPECT_NEAR(hit.speed_after, ek * v, 1e-9 * v) << "w / w_c = " << ratio << ", t = " << hit.t;
    }
  }
}

// A scene without contacts runs forward_dynamics as before: no events.
TEST(ContactScene, SceneWithoutContactsHasNoEvents) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/mass_spring_mass.yaml");
  ASSERT_TRUE(scene.contacts.empty());
  const Model model = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, model);
  o.t1 = o.t0 + 0.1;
  o.samples = 3;
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  EXPECT_TRUE(run.events.empty());
  EXPECT_EQ(run.trajectory.time.size(), 3);
}

}  // namespace
}  // namespace mo2d
