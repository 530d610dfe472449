// The tangents of the contact kinds (src/contact/tangent.hpp): the sliding rate v_t = J_t q1
// against the central difference of the relative displacement, along t, of the two bodies'
// material points at the contact point under rigid motions (each body turned by its rotation rate
// about one of its nodes); the bias dv_t/dt - J_t a against the central difference of v_t along
// q1; at random configurations of the four kinds (a ball's circle on a bar's line, a bar point on
// an inclined ground line, the ball outside a circle around the bar point, the ball in a hole
// around bar.B).
#include <gtest/gtest.h>

#include <random>

#include "contact/contact_support.hpp"
#include "mo2d/error.hpp"

using namespace contact_test;

namespace {

Model tangent_scene() {
  System s("tangents");
  s.add_ground_node("O", {0, 0});
  s.add_ground_node("X", {1, 0.2});
  s.add_body({.name = "bar",
              .nodes = {{"A", {0, 1}}, {"B", {1, 1.3}}},
              .mass = 1,
              .inertia = 0.1,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "ball", .nodes = {{"C", {0.4, 2}}}, .mass = 1, .inertia = 0.01});
  s.add_point({.name = "tip", .body = "bar", .point = {0.7, 1.6}});
  return build_model(s);
}

ContactDef rough_contact(std::string name, std::string point, double r, ContactDef::Target target,
                         std::string a, std::string b, double R) {
  ContactLaw l = rigid(0.5);
  l.friction = 0.4;
  return {.name = std::move(name),
          .point = std::move(point),
          .radius = r,
          .target = target,
          .a = std::move(a),
          .b = std::move(b),
          .target_radius = R,
          .law = l};
}

Vec2 turned(const Vec2& v, double angle) {
  return {std::cos(angle) * v.x() - std::sin(angle) * v.y(),
          std::sin(angle) * v.x() + std::cos(angle) * v.y()};
}

Vec2 cross_z(const Vec2& v) {  // z x v
  return {-v.y(), v.x()};
}

}  // namespace

TEST(ContactTangent, SlidingRateAndBiasMatchFiniteDifferences) {
  const Model m = tangent_scene();
  using T = ContactDef::Target;
  const std::vector<ContactDef> cs = {
      rough_contact("ball_bar", "ball.C", 0.1, T::line, "bar.A", "bar.B", 0),
      rough_contact("tip_ground", "tip", 0, T::line, "ground.O", "ground.X", 0),
      rough_contact("ball_circle", "ball.C", 0.1, T::circle, "tip", "", 0.3),
      rough_contact("ball_hole", "ball.C", 0.1, T::hole, "bar.B", "", 2.5)};
  // the tip's coefficients on bar.A -> bar.B (Example 2.6 (b)) at the initial geometry
  const Vec2 d0(1, 0.3), w0(0.7, 0.6);
  const double gamma = w0.dot(d0) / d0.squaredNorm(),
               rho = (d0.x() * w0.y() - d0.y() * w0.x()) / d0.squaredNorm();
  std::mt19937_64 rng(3535);
  std::normal_distribution<double> n01(0.0, 1.0);
  auto at = [&](const Eigen::VectorXd& q, const std::string& node) {
    return Vec2(q[m.coordinate(node + ".x")], q[m.coordinate(node + ".y")]);
  };
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q0 = m.q0;
    for (int i = 0; i < m.n0; ++i) q0[i] += 0.2 * n01(rng);
    const Vec2 A = at(q0, "bar.A"), B = at(q0, "bar.B"), C = at(q0, "ball.C");
    const Vec2 tip = (1 - gamma) * A + gamma * B + rho * cross_z(B - A);
    // rigid velocities: the bar turning at wb about A moving at vA, the ball at wc
    const Vec2 vA(n01(rng), n01(rng)), vC(n01(rng), n01(rng));
    const double wb = n01(rng), wc = n01(rng);
    Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
    auto set = [&](const std::string& node, const Vec2& v) {
      q1[m.rate(node + ".vx")] = v.x();
      q1[m.rate(node + ".vy")] = v.y();
    };
    set("bar.A", vA);
    set("bar.B", vA + wb * cross_z(B - A));
    set("ball.C", vC);
    q1[m.rate("bar.w")] = wb;
    q1[m.rate("ball.w")] = wc;
    for (const ContactDef& c : cs) {
      // the contact point Q and the tangent t (tangent.hpp's definitions)
      const Vec2 P = c.point == "tip" ? tip : C;
      Vec2 t, n;
      if (c.target == T::line) {
        const Vec2 a = c.a == "bar.A" ? A : Vec2(0, 0), b = c.a == "bar.A" ? B : Vec2(1, 0.2);
        t = (b - a).normalized();
        n = cross_z(t);
      } else {
        const Vec2 centre = c.a == "tip" ? tip : B;
        n = (c.target == T::circle ? 1.0 : -1.0) * (P - centre).normalized();
        t = {n.y(), -n.x()};
      }
      const Vec2 Q = P - c.radius * n;
      // the material points at Q of the point's body and of the target's body after a time s
      auto body1 = [&](double s) -> Vec2 {
        return c.point == "tip" ? A + s * vA + turned(Q - A, wb * s)
                                : C + s * vC + turned(Q - C, wc * s);
      };
      auto body2 = [&](double s) -> Vec2 {
        return c.a == "ground.O" ? Q : Vec2(A + s * vA + turned(Q - A, wb * s));
      };
      const double h = 1e-5;
      const double fd = t.dot(body1(h) - body2(h) - body1(-h) + body2(-h)) / (2 * h);
      const TangentValue v = contact_tangent(m, c, q0, q1);
      EXPECT_NEAR(v.rate, fd, 1e-8 * (1 + std::abs(fd))) << c.name << " trial " << trial;
      EXPECT_NEAR(v.rate, v.J.dot(q1), 1e-12 * (1 + std::abs(v.rate))) << c.name;
      // the bias along any velocities
      Eigen::VectorXd u(m.n1);
      for (int i = 0; i < m.n1; ++i) u[i] = n01(rng);
      const TangentValue vu = contact_tangent(m, c, q0, u);
      const Eigen::VectorXd qp = q0 + h * u.head(m.n0), qm = q0 - h * u.head(m.n0);
      const double fd2 =
          (contact_tangent(m, c, qp, u).rate - contact_tangent(m, c, qm, u).rate) / (2 * h);
      EXPECT_NEAR(vu.curvature, fd2, 1e-7 * (1 + std::abs(fd2))) << c.name;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 80);
}

// A line with friction must belong to one body: its points on two bodies are refused.
TEST(ContactTangent, RoughLineOnTwoBodiesIsRefused) {
  const Model m = tangent_scene();
  ContactDef c =
      rough_contact("split", "ball.C", 0.1, ContactDef::Target::line, "bar.A", "ground.X", 0);
  try {
    (void)contact_tangent(m, c, m.q0, Eigen::VectorXd::Zero(m.n1));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("split"), std::string::npos) << e.what();
  }
  c.law.friction = -1;
  c.b = "bar.B";
  EXPECT_THROW((void)contact_tangent(m, c, m.q0, Eigen::VectorXd::Zero(m.n1)), Error);
}
