// Coulomb friction in contacts (docs/contact.md, "Friction"): a block on two corner contacts
// sliding to a stop on the ground (v0^2 / (2 mu g) at v0 / (mu g)), on an incline (held when
// tan(alpha) < mu, else sliding at g (sin - mu cos); thrown uphill: stopping, then held or sliding
// back), a ball hitting a wall obliquely (the impact law's closed forms, sticking and sliding), a
// compliant ball sliding along a wall (tangential momentum = mu times the normal momentum); the
// energy balance closes with friction's losses in every run.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_support.hpp"

using namespace contact_test;

namespace {

std::vector<ContactEvent> friction_events(const ContactRun& r, ContactEvent::Kind k) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& e : r.events)
    if (e.kind == k) out.push_back(e);
  return out;
}

ContactLaw rough(ContactLaw l, double mu) {
  l.friction = mu;
  return l;
}

// A block of width 2 b (corner nodes A, B), its centre of mass h above their midpoint, on the line
// through the origin at the angle alpha (its corners on it), gravity (0, -g).
struct Block {
  double b = 0.2, h = 0.1, m = 2, g = 9.81, alpha = 0;
  Model model() const {
    const Vec2 u(std::cos(alpha), std::sin(alpha)), v(-u.y(), u.x());
    System s("block");
    s.add_ground_node("L", -20 * u);
    s.add_ground_node("R", 20 * u);
    s.add_body({.name = "block",
                .nodes = {{"A", -b * u}, {"B", b * u}},
                .mass = m,
                .inertia = m * (b * b + h * h) / 3,
                .com = CenterOfMass::at_point(h * v)});
    s.set_gravity({0, -g});
    return build_model(s);
  }
  std::vector<ContactDef> contacts(double mu) const {
    std::vector<ContactDef> cs;
    for (const char* c : {"A", "B"})
      cs.push_back({.name = std::string("corner") + c,
                    .point = std::string("block.") + c,
                    .target = ContactDef::Target::line,
                    .a = "ground.L",
                    .b = "ground.R",
                    .law = rough(rigid(0), mu)});
    return cs;
  }
  // the run from rest on the line with the speed v0 along it (up the slope for v0 > 0)
  ContactRun run(double mu, double v0, double t1, int samples) const {
    const Model m = model();
    ContactOptions o;
    o.forward = tight(t1, samples);
    const State st = consistent_state(m, {.positions = {},
                                          .velocities = {{"block.A.vx", v0 * std::cos(alpha)},
                                                         {"block.A.vy", v0 * std::sin(alpha)},
                                                         {"block.w", 0.0}}});
    return contact_dynamics(m, contacts(mu), st, o);
  }
  // the distance corner A moved along the line at each sample
  static Eigen::VectorXd travel(const ContactRun& r, double alpha) {
    const Trajectory& t = r.trajectory;
    const auto x = t.q0.col(t.column("block.A.x")), y = t.q0.col(t.column("block.A.y"));
    return std::cos(alpha) * (x.array() - x[0]) + std::sin(alpha) * (y.array() - y[0]);
  }
};

}  // namespace

// On level ground the block slides from v0 to rest in v0 / (mu g), over v0^2 / (2 mu g), both
// corners sticking at that instant; friction dissipates m v0^2 / 2.
TEST(ContactFriction, BlockSlidesToAStopAtTheClosedForm) {
  const Block blk;
  const double mu = 0.5, v0 = 2;
  const ContactRun r = blk.run(mu, v0, 0.6, 61);
  const double a = mu * blk.g, stop = v0 / a, dist = v0 * v0 / (2 * a);
  const std::vector<ContactEvent> stick = friction_events(r, ContactEvent::Kind::stick);
  ASSERT_EQ(stick.size(), 2U);
  for (const ContactEvent& e : stick) EXPECT_NEAR(e.t, stop, 1e-9) << e.contact;
  EXPECT_EQ(r.events.size(), 2U);
  const Eigen::VectorXd s = Block::travel(r, 0);
  const Trajectory& t = r.trajectory;
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    const double tk = std::min(t.time[k], stop);
    EXPECT_NEAR(s[k], v0 * tk - a * tk * tk / 2, 1e-9) << "t = " << t.time[k];
  }
  EXPECT_NEAR(s[s.size() - 1], dist, 1e-9);
  const Eigen::Index last = t.time.size() - 1;
  const double E = blk.m * v0 * v0 / 2;
  EXPECT_NEAR(t.dissipated[last], E, 1e-9 * E);
  EXPECT_LT(t.kinetic[last], 1e-18);
  EXPECT_LT(energy_balance_error(t), 1e-9 * E);
}

// On an incline of 20 degrees (tan = 0.364): with mu = 0.5 or 0.4 the block stays put; with mu =
// 0.2 it slides down at g (sin - mu cos), friction dissipating mu m g cos times the distance.
TEST(ContactFriction, BlockOnAnInclineStaysOrSlides) {
  Block blk;
  blk.alpha = 20 * M_PI / 180;
  const double sa = std::sin(blk.alpha), ca = std::cos(blk.alpha);
  // mu = 0.4, just above tan(alpha): held only as a whole (the upper corner carries less normal
  // force, 0.384 m g against 0.555 m g, and half the friction would be outside its own cone)
  for (const double mu : {0.5, 0.4}) {
    const ContactRun held = blk.run(mu, 0, 0.5, 11);
    EXPECT_TRUE(held.events.empty()) << "mu = " << mu;
    EXPECT_LT(Block::travel(held, blk.alpha).cwiseAbs().maxCoeff(), 1e-12) << "mu = " << mu;
  }
  const double mu = 0.2, a = blk.g * (sa - mu * ca);
  const ContactRun slid = blk.run(mu, 0, 0.5, 11);
  EXPECT_TRUE(slid.events.empty());
  const Eigen::VectorXd s = Block::travel(slid, blk.alpha);
  const Trajectory& t = slid.trajectory;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    EXPECT_NEAR(s[k], -a * t.time[k] * t.time[k] / 2, 1e-9) << "t = " << t.time[k];
  const Eigen::Index last = t.time.size() - 1;
  EXPECT_NEAR(t.dissipated[last], mu * blk.m * blk.g * ca * (-s[last]), 1e-9);
  EXPECT_LT(energy_balance_error(t), 1e-9 * blk.m * blk.g * std::abs(s[last]));
}

// Thrown up the incline at v0 it decelerates at g (sin + mu cos) and stops at v0 / that; then with
// mu = 0.5 it sticks there, with mu = 0.2 it slides back down at g (sin - mu cos).
TEST(ContactFriction, BlockThrownUpAnInclineStopsThenSticksOrSlidesBack) {
  Block blk;
  blk.alpha = 20 * M_PI / 180;
  const double sa = std::sin(blk.alpha), ca = std::cos(blk.alpha), v0 = 1.5;
  for (const double mu : {0.5, 0.2}) {
    const double up = blk.g * (sa + mu * ca), down = blk.g * (sa - mu * ca), stop = v0 / up;
    const ContactRun r = blk.run(mu, v0, 0.8, 41);
    const bool sticks = mu > std::tan(blk.alpha);
    const std::vector<ContactEvent> ev =
        friction_events(r, sticks ? ContactEvent::Kind::stick : ContactEvent::Kind::slip);
    ASSERT_EQ(ev.size(), 2U) << "mu = " << mu;
    EXPECT_EQ(r.events.size(), 2U) << "mu = " << mu;
    for (const ContactEvent& e : ev) EXPECT_NEAR(e.t, stop, 1e-9) << e.contact;
    const Eigen::VectorXd s = Block::travel(r, blk.alpha);
    const Trajectory& t = r.trajectory;
    for (Eigen::Index k = 0; k < s.size(); ++k) {
      const double tk = t.time[k], top = v0 * stop / 2;
      const double want = tk <= stop ? v0 * tk - up * tk * tk / 2
                          : sticks   ? top
                                     : top - down * (tk - stop) * (tk - stop) / 2;
      EXPECT_NEAR(s[k], want, 1e-9) << "mu = " << mu << ", t = " << tk;
    }
    EXPECT_LT(energy_balance_error(t), 1e-9 * blk.m * v0 * v0);
  }
}

// A disc (radius r, inertia m r^2 / 2, no gravity) hits the wall x = 1 obliquely: Newton's
// restitution e in the normal direction (P_n = m (1 + e) v_x); the tangential impulse stops the
// contact point's sliding v_t = v_y + r w if that needs at most mu P_n (stick), else it is
// -mu P_n sign(v_t) (slip). After: v_x = -e v_x, v_y += P_t / m, w += r P_t / I.
TEST(ContactFriction, DiscHitsAWallObliquely) {
  const double m = 0.3, r = 0.05, I = m * r * r / 2, e = 0.6, vx = 2, vy = 1.2, w0 = -5;
  for (const double mu : {0.05, 0.8}) {  // sticking needs mu >= 0.099
    System s("disc");
    s.add_ground_node("D", {1, -10});
    s.add_ground_node("U", {1, 10});
    s.add_body({.name = "disc", .nodes = {{"C", {1 - r - 0.1, 0}}}, .mass = m, .inertia = I});
    const Model model = build_model(s);
    ContactOptions o;
    o.forward = tight(0.2, 3);
    const ContactDef wall = {.name = "wall",
                             .point = "disc.C",
                             .radius = r,
                             .target = ContactDef::Target::line,
                             .a = "ground.D",
                             .b = "ground.U",
                             .law = rough(rigid(e), mu)};
    const ContactRun run = contact_dynamics(
        model, {wall}, state_of(model, {{"disc.C.vx", vx}, {"disc.C.vy", vy}, {"disc.w", w0}}), o);
    const double Pn = m * (1 + e) * vx, vt = vy + r * w0, k = 1 / m + r * r / I;
    const double stick = -vt / k;
    const double Pt = std::abs(stick) <= mu * Pn ? stick : -mu * Pn * std::copysign(1.0, vt);
    const std::vector<ContactEvent> hits = friction_events(run, ContactEvent::Kind::impact);
    ASSERT_EQ(hits.size(), 1U) << "mu = " << mu;
    EXPECT_NEAR(hits[0].t, 0.1 / vx, 1e-12);
    EXPECT_NEAR(hits[0].impulse, Pn, 1e-12);
    const double vy1 = vy + Pt / m, w1 = w0 + r * Pt / I;
    const double lost =
        m * (vx * vx * (1 - e * e) + vy * vy - vy1 * vy1) / 2 + I * (w0 * w0 - w1 * w1) / 2;
    EXPECT_NEAR(hits[0].energy_lost, lost, 1e-12);
    EXPECT_GT(lost, 0);
    const Trajectory& t = run.trajectory;
    EXPECT_NEAR(t.q1(2, t.rate_column("disc.C.vx")), -e * vx, 1e-12);
    EXPECT_NEAR(t.q1(2, t.rate_column("disc.C.vy")), vy1, 1e-12) << "mu = " << mu;
    EXPECT_NEAR(t.q1(2, t.rate_column("disc.w")), w1, 1e-10) << "mu = " << mu;
    if (mu > 0.5)
      EXPECT_NEAR(vy1 + r * w1, 0, 1e-12);  // stuck: leaves rolling on the wall
    else
      EXPECT_GT(vy1 + r * w1, 0.01);  // still sliding forward: the impulse is -mu P_n
    EXPECT_LT(energy_balance_error(t), 1e-12);
  }
}

// The same disc against a compliant wall (Lankarani-Nikravesh) sliding all through the contact:
// the tangential impulse is -mu times the normal one, whatever the law's force history:
// m dv_y = -mu m (v_x- - v_x+), I dw = r m dv_y. With little sliding it sticks during the contact
// (a stick event); the energy balance closes in both.
TEST(ContactFriction, CompliantDiscSlidesAlongAWall) {
  const double m = 0.3, r = 0.05, I = m * r * r / 2, vx = 2;
  for (const double vy : {3.0, 0.05}) {
    const double mu = 0.1;
    System s("disc");
    s.add_ground_node("D", {1, -10});
    s.add_ground_node("U", {1, 10});
    s.add_body({.name = "disc", .nodes = {{"C", {1 - r - 0.1, 0}}}, .mass = m, .inertia = I});
    const Model model = build_model(s);
    ContactOptions o;
    o.forward = tight(0.1, 3);
    const ContactDef wall = {.name = "wall",
                             .point = "disc.C",
                             .radius = r,
                             .target = ContactDef::Target::line,
                             .a = "ground.D",
                             .b = "ground.U",
                             .law = rough(compliant(1e7, 1.5, 0.8), mu)};
    const ContactRun run =
        contact_dynamics(model, {wall}, state_of(model, {{"disc.C.vx", vx}, {"disc.C.vy", vy}}), o);
    const Trajectory& t = run.trajectory;
    const double vx1 = t.q1(2, t.rate_column("disc.C.vx"));
    const double dvy = t.q1(2, t.rate_column("disc.C.vy")) - vy,
                 dw = t.q1(2, t.rate_column("disc.w"));
    EXPECT_LT(vx1, -0.5 * vx);
    if (vy > 1) {
      EXPECT_TRUE(friction_events(run, ContactEvent::Kind::stick).empty());
      EXPECT_NEAR(dvy, -mu * (vx - vx1), 1e-9);
      EXPECT_NEAR(dw, r * m * dvy / I, 1e-7);
    } else {
      EXPECT_FALSE(friction_events(run, ContactEvent::Kind::stick).empty());
    }
    EXPECT_LT(energy_balance_error(t), 1e-9 * m * (vx * vx + vy * vy));
  }
}
