// Rigid contact with Newton's restitution (src/contact/impact.hpp, contact_events.cpp): the
// bouncing ball's impact times and speeds against their closed forms, its Zeno accumulation time,
// a pendulum hitting a stop, two balls colliding (momentum), a rod landing flat on two stops at
// once (the complementarity problem of two contacts), and the LCP solver on random problems.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact/contact_support.hpp"
#include "contact/impact.hpp"

using namespace contact_test;

namespace {

std::vector<ContactEvent> of_kind(const ContactRun& r, ContactEvent::Kind k) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& e : r.events)
    if (e.kind == k) out.push_back(e);
  return out;
}

}  // namespace

// Dropped from h: the first impact at t1 = sqrt(2 h / g) at v1 = g t1; the k-th after it at
// v1 e^k, the flight after it 2 v1 e^(k+1) / g long; the energy lost at the k-th is (1 - e^2) m (v1
// e^k)^2 / 2 (its rebound height e^(2k) h).
TEST(RigidContact, BouncingBallTimesSpeedsAndLosses) {
  const double m = 0.3, r = 0.02, h = 1.2, g = 9.81, e = 0.8;
  const Model model = build_model(ball_scene(m, 0, r + h, g));
  ContactOptions o;
  o.forward = tight(4, 41);
  const ContactRun run =
      contact_dynamics(model, {ground_contact(r, rigid(e))}, state_of(model, {}), o);
  const std::vector<ContactEvent> hits = of_kind(run, ContactEvent::Kind::impact);
  ASSERT_GE(hits.size(), 10U);
  const double t1 = std::sqrt(2 * h / g), v1 = g * t1;
  double t = t1;
  for (size_t k = 0; k < 10; ++k) {
    const double v = v1 * std::pow(e, static_cast<double>(k));
    EXPECT_NEAR(hits[k].t, t, 1e-9) << "impact " << k;
    EXPECT_NEAR(hits[k].speed, v, 1e-9 * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].energy_lost, 0.5 * m * v * v * (1 - e * e), 1e-9 * m * v1 * v1);
    t += 2 * e * v / g;
  }
  // the penetration never exceeds the event tolerance at the samples
  const int iy = run.trajectory.column("ball.C.y");
  EXPECT_GT(run.trajectory.q0.col(iy).minCoeff(), r - 1e-9);
  EXPECT_LT(energy_balance_error(run.trajectory), 1e-9 * m * g * h);
}

// e = 0.5: the impacts accumulate at t_inf = t1 (1 + e) / (1 - e); the run predicts it from the
// interval ratios, holds the ball on the ground from then on (a persistent contact whose
// multiplier is m g) and reports the accumulation.
TEST(RigidContact, ZenoAccumulationBecomesPersistentContact) {
  const double m = 1.5, r = 0.1, h = 0.5, g = 9.81, e = 0.5;
  const Model model = build_model(ball_scene(m, 0, r + h, g));
  ContactOptions o;
  o.forward = tight(3, 31);
  const ContactRun run =
      contact_dynamics(model, {ground_contact(r, rigid(e))}, state_of(model, {}), o);
  const std::vector<ContactEvent> z = of_kind(run, ContactEvent::Kind::zeno);
  ASSERT_EQ(z.size(), 1U);
  const double t1 = std::sqrt(2 * h / g), t_inf = t1 * (1 + e) / (1 - e);
  EXPECT_NEAR(z[0].predicted_t, t_inf, 1e-9);
  EXPECT_LE(t_inf - z[0].t, 1e-5 * 3);  // the default zeno_time, 1e-5 of the run
  EXPECT_EQ(of_kind(run, ContactEvent::Kind::lift_off).size(), 0U);
  const Trajectory& t = run.trajectory;
  const int iy = t.column("ball.C.y"), ivy = t.rate_column("ball.C.vy");
  for (Eigen::Index k = 0; k < t.time.size(); ++k) {
    if (t.time[k] < t_inf) continue;
    EXPECT_NEAR(t.q0(k, iy), r, 1e-9) << "t = " << t.time[k];
    EXPECT_NEAR(t.q1(k, ivy), 0, 1e-9) << "t = " << t.time[k];
    EXPECT_NEAR(t.a1(k, ivy), 0, 1e-8) << "t = " << t.time[k];
  }
  // all the energy is lost: at rest on the ground
  const Eigen::Index last = t.time.size() - 1;
  EXPECT_NEAR(t.dissipated[last], m * g * h, 1e-8 * m * g * h);
}

// A uniform rod pinned at O, released horizontal, hits a stop at its tip when vertical: the tip
// arrives at sqrt(3 g L), the impact takes (1 - e^2) m g L / 2 (the pivot's impulse does no work),
// and the rod comes back to hit again at e times the speed.
TEST(RigidContact, PendulumHitsAStop) {
  const double L = 0.8, m = 2, g = 9.81, e = 0.6;
  const Model model = stop_pendulum(L, m, g);
  const State st = consistent_state(model, {.positions = {}, .velocities = {{"rod.w", 0.0}}});
  ContactOptions o;
  o.forward = tight(1.5, 16);
  // the stop: the line S1 -> S2 (x = 0), free side x > 0
  const ContactDef stop{.name = "stop",
                        .point = "rod.B",
                        .target = ContactDef::Target::line,
                        .a = "ground.S1",
                        .b = "ground.S2",
                        .law = rigid(e)};
  const ContactRun run = contact_dynamics(model, {stop}, st, o);
  const std::vector<ContactEvent> hits = of_kind(run, ContactEvent::Kind::impact);
  ASSERT_GE(hits.size(), 2U);
  const double v = std::sqrt(3 * g * L);
  EXPECT_NEAR(hits[0].speed, v, 1e-8 * v);
  EXPECT_NEAR(hits[0].energy_lost, (1 - e * e) * m * g * L / 2, 1e-8 * m * g * L);
  EXPECT_NEAR(hits[1].speed, e * v, 1e-8 * v);
  EXPECT_LT(run.trajectory.residuals.maxCoeff(), 1e-10);
}

// Two balls on a line, no gravity, ball a's circle against ball b's: the velocities after follow
// the closed form of a central impact and the momentum is the same at every sample.
TEST(RigidContact, TwoBallsConserveMomentum) {
  const double m1 = 1, m2 = 3, v1 = 1, v2 = -0.5, e = 0.7, r1 = 0.1, r2 = 0.2;
  System s("two");
  s.add_body({.name = "a", .nodes = {{"C", {0, 0}}}, .mass = m1});
  s.add_body({.name = "b", .nodes = {{"C", {1, 0}}}, .mass = m2});
  const Model model = build_model(s);
  const ContactDef c{.name = "ab",
                     .point = "a.C",
                     .radius = r1,
                     .target = ContactDef::Target::circle,
                     .a = "b.C",
                     .target_radius = r2,
                     .law = rigid(e)};
  ContactOptions o;
  o.forward = tight(2, 21);
  const ContactRun run =
      contact_dynamics(model, {c}, state_of(model, {{"a.C.vx", v1}, {"b.C.vx", v2}}), o);
  ASSERT_EQ(of_kind(run, ContactEvent::Kind::impact).size(), 1U);
  const double t_hit = (1 - r1 - r2) / (v1 - v2);
  EXPECT_NEAR(run.events[0].t, t_hit, 1e-10);
  const Trajectory& t = run.trajectory;
  const int a = t.rate_column("a.C.vx"), b = t.rate_column("b.C.vx");
  const double p = m1 * v1 + m2 * v2;
  const double a_after = (p - m2 * e * (v1 - v2)) / (m1 + m2);
  const double b_after = (p + m1 * e * (v1 - v2)) / (m1 + m2);
  const Eigen::Index last = t.time.size() - 1;
  EXPECT_NEAR(t.q1(last, a), a_after, 1e-12);
  EXPECT_NEAR(t.q1(last, b), b_after, 1e-12);
  for (Eigen::Index k = 0; k < t.time.size(); ++k)
    EXPECT_NEAR(m1 * t.q1(k, a) + m2 * t.q1(k, b), p, 1e-12);
}

// A free rod falls flat onto the ground: both tips close at once (one impact of two contacts);
// it leaves without rotation at e times its speed.
TEST(RigidContact, RodLandsFlatOnTwoContacts) {
  const double L = 1, m = 1, g = 9.81, h = 0.3, e = 0.6;
  System s("rod");
  s.add_ground_node("L", {-10, 0});
  s.add_ground_node("R", {10, 0});
  s.add_body({.name = "rod",
              .nodes = {{"A", {0, h}}, {"B", {L, h}}},
              .mass = m,
              .inertia = m * L * L / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.set_gravity({0, -g});
  const Model model = build_model(s);
  std::vector<ContactDef> cs;
  for (const char* tip : {"rod.A", "rod.B"})
    cs.push_back({.name = std::string("tip") + tip[4],
                  .point = tip,
                  .target = ContactDef::Target::line,
                  .a = "ground.L",
                  .b = "ground.R",
                  .law = rigid(e)});
  ContactOptions o;
  o.forward = tight(0.3, 4);
  const State st = consistent_state(
      model,
      {.positions = {}, .velocities = {{"rod.A.vx", 0.0}, {"rod.A.vy", 0.0}, {"rod.w", 0.0}}});
  const ContactRun run = contact_dynamics(model, cs, st, o);
  const std::vector<ContactEvent> hits = of_kind(run, ContactEvent::Kind::impact);
  ASSERT_EQ(hits.size(), 2U);
  EXPECT_EQ(hits[0].t, hits[1].t);
  const double v = std::sqrt(2 * g * h);
  EXPECT_NEAR(hits[0].speed, v, 1e-9);
  EXPECT_NEAR(hits[0].energy_lost, 0.5 * m * v * v * (1 - e * e), 1e-9);
  // after: rising at e v (the samples after the impact: free flight from e v)
  const Trajectory& t = run.trajectory;
  const int ya = t.rate_column("rod.A.vy"), yb = t.rate_column("rod.B.vy");
  const Eigen::Index last = t.time.size() - 1;
  EXPECT_NEAR(t.q1(last, ya), t.q1(last, yb), 1e-10);
  EXPECT_NEAR(t.q1(last, ya), e * v - g * (t.time[last] - hits[0].t), 1e-9);
}

// The LCP solver on random positive definite problems: w = W P + q >= 0, P >= 0, w . P = 0.
TEST(RigidContact, LcpEnumerationSolvesRandomProblems) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int k = 1 + trial % 6;
    Eigen::MatrixXd B(k, k + 2);
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k + 2; ++j) B(i, j) = n01(rng);
    const Eigen::MatrixXd W = B * B.transpose();
    Eigen::VectorXd q(k), P;
    for (int i = 0; i < k; ++i) q[i] = n01(rng);
    ASSERT_TRUE(mo2d::detail::solve_lcp_enumerate(W, q, P)) << "trial " << trial;
    const Eigen::VectorXd w = W * P + q;
    EXPECT_GE(P.minCoeff(), 0);
    EXPECT_GE(w.minCoeff(), -1e-9);
    EXPECT_LT(std::abs(w.dot(P)), 1e-9 * (1 + P.norm()));
  }
}

// A pin in a hole of the ground (clearance c = R - r), no gravity, starting at the centre at v:
// it hits the wall at c / v, crosses the hole (2 c) at e v and hits the opposite wall at
// c / v + 2 c / (e v), then again after 2 c / (e^2 v).
TEST(RigidContact, PinRattlesInAHole) {
  const double R = 0.01, r = 0.009, v = 0.3, e = 0.7, c = R - r;
  System s("pin");
  s.add_ground_node("H", {0, 0});
  s.add_body({.name = "pin", .nodes = {{"C", {0, 0}}}, .mass = 0.1});
  const Model model = build_model(s);
  const ContactDef hole{.name = "clearance",
                        .point = "pin.C",
                        .radius = r,
                        .target = ContactDef::Target::hole,
                        .a = "ground.H",
                        .target_radius = R,
                        .law = rigid(e)};
  ContactOptions o;
  o.forward = tight(0.1, 11);
  const ContactRun run = contact_dynamics(model, {hole}, state_of(model, {{"pin.C.vx", v}}), o);
  const std::vector<ContactEvent> hits = of_kind(run, ContactEvent::Kind::impact);
  ASSERT_GE(hits.size(), 3U);
  EXPECT_NEAR(hits[0].t, c / v, 1e-12);
  EXPECT_NEAR(hits[1].t, c / v + 2 * c / (e * v), 1e-12);
  EXPECT_NEAR(hits[2].t, c / v + 2 * c / (e * v) + 2 * c / (e * e * v), 1e-12);
  EXPECT_NEAR(hits[2].speed, e * e * v, 1e-12);
}
