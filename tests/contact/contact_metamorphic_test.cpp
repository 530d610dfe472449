// Metamorphic relations with contacts (issue 35, "Tests that can fail"): a generated scene with two
// rigid contacts (a pendulum rod whose end circle hits a stop line; a ball bouncing on an inclined
// floor line), run as given and in a frame that is rotated, translated, mirrored and rescaled.
// Moving the frame by p -> s Q p + d (Q a rotation, or a rotation times a reflection), with
// gravity s Q g, must move the whole run with it: the same events at the same times, speeds and
// impulses times s, energies times s^2, and every sample's positions mapped by the same map.
// A mirror turns the free side of a line to its other side: its ends are swapped with it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_support.hpp"

using namespace contact_test;

namespace {

struct FrameMap {
  Eigen::Matrix2d Q = Eigen::Matrix2d::Identity();  // rotation, or rotation times reflection
  Eigen::Vector2d d = Eigen::Vector2d::Zero();      // translation (m)
  double s = 1;                                     // scale of lengths (and of gravity)
  bool mirrored() const { return Q.determinant() < 0; }
  Vec2 point(const Eigen::Vector2d& p) const { return s * Q * p + d; }
  Vec2 vector(const Eigen::Vector2d& v) const { return s * Q * v; }
};

FrameMap frame_map(double angle, double dx, double dy, double s, bool mirror) {
  FrameMap f;
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  f.Q = mirror ? Eigen::Matrix2d(R * Eigen::Vector2d(1, -1).asDiagonal()) : R;
  f.d = {dx, dy};
  f.s = s;
  return f;
}

// One generated case: the rod (pivot at the origin, horizontal, length L, end circle r) falls onto
// the stop line x = 0 (free side x > 0); the ball (radius rb) starts above the floor through the
// point (3, -1) inclined by `slope`, moving along it.
struct ContactCase {
  double L = 1, m_rod = 1, r = 0.02, w0 = 0, e_stop = 0.6;
  double m_ball = 1, rb = 0.1, slope = 0.2, v_along = 0.5, height = 0.3, e_floor = 0.8;
};

ContactCase generated_case(std::mt19937_64& rng) {
  auto u = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  ContactCase c;
  c.L = u(0.3, 1.5);
  c.m_rod = u(0.5, 3);
  c.r = u(0, 0.05);
  c.w0 = u(-1, 1);
  c.e_stop = u(0.2, 0.9);
  c.m_ball = u(0.2, 2);
  c.rb = u(0.02, 0.2);
  c.slope = u(-0.4, 0.4);
  c.v_along = u(-1, 1);
  c.height = u(0.1, 0.8);
  c.e_floor = u(0.3, 0.9);
  return c;
}

struct MappedScene {
  Model model;
  std::vector<ContactDef> contacts;
  State initial;
};

MappedScene mapped_scene(const ContactCase& c, const FrameMap& f) {
  const Eigen::Vector2d along(std::cos(c.slope), std::sin(c.slope));
  const Eigen::Vector2d normal(-along.y(), along.x()), foot(3, -1);
  System s("contact_metamorphic");
  s.add_ground_node("O", f.point({0, 0}));
  s.add_ground_node("S1", f.point({0, 1}));
  s.add_ground_node("S2", f.point({0, -2}));
  s.add_ground_node("F1", f.point(foot - 5 * along));
  s.add_ground_node("F2", f.point(foot + 5 * along));
  const double L = f.s * c.L;
  s.add_body({.name = "rod",
              .nodes = {{"O", f.point({0, 0})}, {"B", f.point({c.L, 0})}},
              .mass = c.m_rod,
              .inertia = c.m_rod * L * L / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "rod.O"});
  s.add_body({.name = "ball",
              .nodes = {{"C", f.point(foot + (c.rb + c.height) * normal)}},
              .mass = c.m_ball});
  s.set_gravity(f.vector({0, -9.81}));
  MappedScene out{build_model(s), {}, {}};
  // a mirror swaps the ends of each line, so that its free side stays the mapped free side
  const bool swap = f.mirrored();
  auto line = [&](const char* name, const char* point, double radius, const char* a, const char* b,
                  double e) {
    out.contacts.push_back({.name = name,
                            .point = point,
                            .radius = f.s * radius,
                            .target = ContactDef::Target::line,
                            .a = swap ? b : a,
                            .b = swap ? a : b,
                            .law = rigid(e)});
  };
  line("stop", "rod.B", c.r, "ground.S1", "ground.S2", c.e_stop);
  line("floor", "ball.C", c.rb, "ground.F1", "ground.F2", c.e_floor);
  const Vec2 v = f.vector(c.v_along * along);
  const double w = swap ? -c.w0 : c.w0;  // an angular rate changes sign in a mirror
  out.initial = consistent_state(
      out.model,
      {.positions = {}, .velocities = {{"rod.w", w}, {"ball.C.vx", v.x()}, {"ball.C.vy", v.y()}}});
  return out;
}

ContactRun run_case(const MappedScene& sc) {
  ContactOptions o;
  o.forward = tight(1.2, 25);
  return contact_dynamics(sc.model, sc.contacts, sc.initial, o);
}

Eigen::Vector2d node_at(const Model& m, const Trajectory& r, Eigen::Index k, const std::string& n) {
  return {r.q0(k, m.coordinate(n + ".x")), r.q0(k, m.coordinate(n + ".y"))};
}

// The mapped run against the run as given: events, energies and positions follow the map.
void expect_mapped(const MappedScene& a, const ContactRun& ra, const MappedScene& b,
                   const ContactRun& rb, const FrameMap& f) {
  ASSERT_EQ(ra.events.size(), rb.events.size());
  for (std::size_t k = 0; k < ra.events.size(); ++k) {
    const ContactEvent &x = ra.events[k], &y = rb.events[k];
    SCOPED_TRACE("event " + std::to_string(k) + " of " + x.contact +
                 " at t = " + std::to_string(x.t));
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.contact, y.contact);
    EXPECT_NEAR(y.t, x.t, 1e-9);
    EXPECT_NEAR(y.speed, f.s * x.speed, 1e-8 * f.s * (1 + x.speed));
    EXPECT_NEAR(y.speed_after, f.s * x.speed_after, 1e-8 * f.s * (1 + x.speed));
    EXPECT_NEAR(y.impulse, f.s * x.impulse, 1e-8 * f.s * (1 + std::abs(x.impulse)));
    const double s2 = f.s * f.s;
    EXPECT_NEAR(y.energy_lost, s2 * x.energy_lost, 1e-8 * s2 * (1 + x.energy_lost));
  }
  const Trajectory &ta = ra.trajectory, &tb = rb.trajectory;
  ASSERT_EQ(ta.time.size(), tb.time.size());
  for (Eigen::Index k = 0; k < ta.time.size(); ++k)
    for (const char* n : {"rod.B", "ball.C"}) {
      const Eigen::Vector2d want = f.point(node_at(a.model, ta, k, n));
      EXPECT_LT((node_at(b.model, tb, k, n) - want).norm(), 1e-8 * f.s)
          << n << " at t = " << ta.time[k];
    }
  const double s2 = f.s * f.s, scale = 1 + ta.kinetic.cwiseAbs().maxCoeff();
  EXPECT_LT((tb.kinetic - s2 * ta.kinetic).cwiseAbs().maxCoeff(), 1e-8 * s2 * scale);
}

}  // namespace

// 8 generated cases, each in 4 frames: rotated and translated; mirrored; rescaled by 0.37 (with
// gravity: the same times); all three at once.
TEST(ContactMetamorphic, RunsFollowRotationTranslationMirrorAndScale) {
  std::mt19937_64 rng(35);
  const std::vector<FrameMap> frames = {
      frame_map(0.7, 2.5, -1.3, 1, false), frame_map(0, 0, 0, 1, true),
      frame_map(0, 0, 0, 0.37, false), frame_map(-2.1, -4, 7, 3.2, true)};
  int impacts = 0;
  for (int n = 0; n < 8; ++n) {
    const ContactCase c = generated_case(rng);
    const MappedScene given = mapped_scene(c, {});
    const ContactRun r = run_case(given);
    for (const ContactEvent& e : r.events) impacts += e.kind == ContactEvent::Kind::impact;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      SCOPED_TRACE("case " + std::to_string(n) + ", frame " + std::to_string(k));
      const MappedScene mapped = mapped_scene(c, frames[k]);
      expect_mapped(given, r, mapped, run_case(mapped), frames[k]);
    }
  }
  EXPECT_GT(impacts, 16);  // the cases hit something: the relations are not about free flight
}
