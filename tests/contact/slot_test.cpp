// A pin in a slot (src/contact/slot.hpp): the three parts' gaps (walls, closed end; outside, the
// lips) against central differences and closed forms, and runs of a free pin against the times
// of the closed forms: entering through the mouth, hitting the closed end and a wall, leaving; a
// pin hitting a lip from outside; a pin reaching the slot through its wall (refused).
#include <gtest/gtest.h>

#include <random>

#include "contact/contact_set.hpp"
#include "contact/contact_support.hpp"
#include "mo2d/error.hpp"

using namespace contact_test;

namespace {

// a free bar bar.A -> bar.B with the named point "mouth" on it, a ball ball.C
Model slot_gap_scene() {
  System s("slot_gaps");
  s.add_body({.name = "bar",
              .nodes = {{"A", {0, 1}}, {"B", {1, 1.3}}},
              .mass = 1,
              .inertia = 0.1,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "ball", .nodes = {{"C", {0.6, 1.25}}}, .mass = 1, .inertia = 0.01});
  s.add_point({.name = "mouth", .body = "bar", .point = {1.4, 1.5}});
  return build_model(s);
}

ContactDef bar_slot() {
  return {.name = "slot",
          .point = "ball.C",
          .radius = 0.1,
          .target = ContactDef::Target::slot,
          .a = "bar.A",
          .b = "mouth",
          .width = 0.3,
          .law = rigid(0.5)};
}

// the slot's part `part` (0 left, 1 right, 2 end) with the pin inside or outside
GapValue part_gap(const Model& m, const ContactDef& d, int part, bool inside,
                  const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  std::vector<detail::CompiledContact> cs;
  detail::compile_contacts(m, d, cs);
  EXPECT_EQ(cs.size(), 3U);
  detail::CompiledContact& c = cs[static_cast<size_t>(part)];
  c.inside = inside;
  GapValue g;
  g.J = Eigen::VectorXd::Zero(m.n1);
  detail::gap_into(m, c, q0, q1, g);
  EXPECT_NEAR(detail::gap_only(m, c, q0), g.g, 1e-14);
  return g;
}

}  // namespace

TEST(SlotGap, GradientRateAndCurvatureMatchFiniteDifferences) {
  const Model m = slot_gap_scene();
  const ContactDef d = bar_slot();
  std::mt19937_64 rng(3535);
  std::normal_distribution<double> n01(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q0 = m.q0, q1(m.n1);
    for (int i = 0; i < m.n0; ++i) q0[i] += 0.2 * n01(rng);
    for (int i = 0; i < m.n1; ++i) q1[i] = n01(rng);
    for (int part = 0; part < 3; ++part)
      for (const bool inside : {true, false}) {
        if (part == 2 && !inside) continue;  // a constant
        const GapValue g = part_gap(m, d, part, inside, q0, q1);
        const double h = 1e-6;
        for (int i = 0; i < m.n0; ++i) {
          Eigen::VectorXd qp = q0, qm = q0;
          qp[i] += h;
          qm[i] -= h;
          const double fd =
              (part_gap(m, d, part, inside, qp, q1).g - part_gap(m, d, part, inside, qm, q1).g) /
              (2 * h);
          EXPECT_NEAR(g.J[i], fd, 1e-8 * (1 + std::abs(fd)))
              << "part " << part << " inside " << inside << " coordinate " << i;
        }
        EXPECT_NEAR(g.rate, g.J.dot(q1), 1e-12 * (1 + std::abs(g.rate)));
        const Eigen::VectorXd qp = q0 + h * q1.head(m.n0), qm = q0 - h * q1.head(m.n0);
        const double fd2 = (part_gap(m, d, part, inside, qp, q1).rate -
                            part_gap(m, d, part, inside, qm, q1).rate) /
                           (2 * h);
        EXPECT_NEAR(g.curvature, fd2, 1e-6 * (1 + std::abs(fd2)))
            << "part " << part << " inside " << inside;
        ++checked;
      }
  }
  EXPECT_EQ(checked, 100);
}

// The closed forms on a ground slot along x from (0, 0) to (1, 0), width 0.3, pin radius 0.1.
TEST(SlotGap, ValuesMatchClosedForms) {
  System s("slot_values");
  s.add_ground_node("A", {0, 0});
  s.add_ground_node("B", {1, 0});
  s.add_body({.name = "ball", .nodes = {{"C", {0.5, 0.02}}}, .mass = 1});
  const Model m = build_model(s);
  ContactDef d = bar_slot();
  d.a = "ground.A";
  d.b = "ground.B";
  const Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
  EXPECT_NEAR(part_gap(m, d, 0, true, m.q0, q1).g, 0.05 - 0.02, 1e-15);  // h - l, h = w/2 - r
  EXPECT_NEAR(part_gap(m, d, 1, true, m.q0, q1).g, 0.05 + 0.02, 1e-15);
  EXPECT_NEAR(part_gap(m, d, 2, true, m.q0, q1).g, 0.5 - 0.1, 1e-15);
  Eigen::VectorXd q0 = m.q0;  // outside: the lips at (1, +-0.15)
  q0[m.coordinate("ball.C.x")] = 1.2;
  q0[m.coordinate("ball.C.y")] = 0.1;
  EXPECT_NEAR(part_gap(m, d, 0, false, q0, q1).g, std::hypot(0.2, 0.05) - 0.1, 1e-15);
  EXPECT_NEAR(part_gap(m, d, 1, false, q0, q1).g, std::hypot(0.2, 0.25) - 0.1, 1e-15);
  EXPECT_NEAR(part_gap(m, d, 2, false, q0, q1).g, 0.3, 0);
}

TEST(SlotGap, BadSlotsNameTheContact) {
  const Model m = slot_gap_scene();
  auto message = [&](const ContactDef& d) -> std::string {
    try {
      std::vector<detail::CompiledContact> cs;
      detail::compile_contacts(m, d, cs);
    } catch (const Error& e) {
      EXPECT_EQ(e.element(), "slot");
      return e.what();
    }
    return "";
  };
  ContactDef d = bar_slot();
  d.width = 0.2;
  EXPECT_NE(message(d).find("width must be more than the pin's diameter"), std::string::npos);
  d = bar_slot();
  d.b = "bar.A";
  EXPECT_NE(message(d).find("the slot's ends a and b are the same point"), std::string::npos);
  d = bar_slot();
  d.b = "ball.C";
  d.point = "bar.B";
  EXPECT_NE(message(d).find("are not on one body"), std::string::npos);
  d = bar_slot();
  d.point = "bar.B";
  EXPECT_NE(message(d).find("on the same body"), std::string::npos);
  d = bar_slot();
  d.radius = 1.5;
  d.width = 4;
  EXPECT_NE(message(d).find("not longer than the pin's radius"), std::string::npos);
  EXPECT_EQ(message(bar_slot()), "");
  try {  // one gap asked of a slot
    (void)contact_gap(m, bar_slot(), m.q0, Eigen::VectorXd::Zero(m.n1));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a slot has three gaps"), std::string::npos);
  }
}

namespace {

// A free pin (radius 0.1, no gravity) at (x, y) moving at (vx, vy) by the ground slot from (0, 0)
// (closed end) to (1, 0) (mouth), width 0.3, restitution 0.5; its events over [0, t1].
std::vector<ContactEvent> pin_run(double x, double y, double vx, double vy, double t1) {
  System s("pin_slot");
  s.add_ground_node("A", {0, 0});
  s.add_ground_node("B", {1, 0});
  s.add_body({.name = "ball", .nodes = {{"C", {x, y}}}, .mass = 2});
  const Model m = build_model(s);
  ContactDef d = bar_slot();
  d.a = "ground.A";
  d.b = "ground.B";
  ContactOptions o;
  o.forward = tight(t1, 11);
  return contact_dynamics(m, {d}, state_of(m, {{"ball.C.vx", vx}, {"ball.C.vy", vy}}), o).events;
}

}  // namespace

// In through the mouth at t = 0.5, on the closed end (s = r) at 1.4, back at half the speed, out
// at 1.4 + 0.9 / 0.5 = 3.2.
TEST(SlotRun, PinEntersHitsTheEndAndLeaves) {
  const std::vector<ContactEvent> ev = pin_run(1.5, 0.01, -1, 0, 3.5);
  ASSERT_EQ(ev.size(), 3U);
  EXPECT_EQ(ev[0].kind, ContactEvent::Kind::enter);
  EXPECT_EQ(ev[0].contact, "slot");
  EXPECT_NEAR(ev[0].t, 0.5, 1e-10);
  EXPECT_EQ(ev[1].kind, ContactEvent::Kind::impact);
  EXPECT_EQ(ev[1].contact, "slot.end");
  EXPECT_NEAR(ev[1].t, 1.4, 1e-10);
  EXPECT_NEAR(ev[1].speed, 1, 1e-10);
  EXPECT_NEAR(ev[1].speed_after, 0.5, 1e-10);
  EXPECT_NEAR(ev[1].impulse, 2 * 1.5, 1e-9);
  EXPECT_EQ(ev[2].kind, ContactEvent::Kind::leave);
  EXPECT_NEAR(ev[2].t, 3.2, 1e-10);
}

// Across the slot: the left wall (l = h = 0.05) at 0.05, the right at 0.05 + 0.1 / 0.5, the left
// again 0.1 / 0.25 later.
TEST(SlotRun, PinRattlesBetweenTheWalls) {
  const std::vector<ContactEvent> ev = pin_run(0.5, 0, 0, 1, 0.7);
  ASSERT_EQ(ev.size(), 3U);
  const char* names[] = {"slot.left", "slot.right", "slot.left"};
  const double t[] = {0.05, 0.25, 0.65}, v[] = {1, 0.5, 0.25};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(ev[k].kind, ContactEvent::Kind::impact);
    EXPECT_EQ(ev[k].contact, names[k]);
    EXPECT_NEAR(ev[k].t, t[k], 1e-10);
    EXPECT_NEAR(ev[k].speed, v[k], 1e-10);
  }
}

// Off the band at the mouth: the pin (l = 0.21) aimed at the left lip's corner (1, 0.15) at unit
// speed meets it head-on at t = |(0.5, 0.06)| - r, at the speed 1, and leaves at e = 0.5.
TEST(SlotRun, PinHitsALipFromOutside) {
  const double d = std::hypot(0.5, 0.06);
  const std::vector<ContactEvent> ev = pin_run(1.5, 0.21, -0.5 / d, -0.06 / d, 0.6);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, ContactEvent::Kind::impact);
  EXPECT_EQ(ev[0].contact, "slot.left");
  EXPECT_NEAR(ev[0].t, d - 0.1, 1e-10);
  EXPECT_NEAR(ev[0].speed, 1, 1e-10);
  EXPECT_NEAR(ev[0].speed_after, 0.5, 1e-10);
}

// From outside through a wall (l = w/2 at t = 0.35): not modelled, refused with the time.
TEST(SlotRun, PinThroughAWallIsRefused) {
  try {
    (void)pin_run(0.5, 0.5, 0, -1, 0.5);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("enters its slot through a wall at t = 0.35"), std::string::npos) << w;
    EXPECT_EQ(e.element(), "slot");
    EXPECT_NEAR(e.time(), 0.35, 1e-9);
  }
}
