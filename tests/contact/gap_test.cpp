// The gaps of the contact kinds (src/contact/point_line.hpp, circle_circle.hpp): their gradient J
// against central differences of g in every node coordinate, g' = J q1, and J' q1 against the
// central difference of J q1 along q1, at random configurations (not assembled: the gap is a
// function of the coordinates alone).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_support.hpp"
#include "mo2d/error.hpp"

using namespace contact_test;

namespace {

// a free bar bar.A -> bar.B, a ball ball.C, a bar point "tip" and ground nodes
Model gap_scene() {
  System s("gaps");
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

std::vector<ContactDef> gap_contacts() {
  using T = ContactDef::Target;
  const ContactLaw l = rigid(0.5);
  return {{.name = "ball_bar",
           .point = "ball.C",
           .radius = 0.1,
           .target = T::line,
           .a = "bar.A",
           .b = "bar.B",
           .law = l},
          {.name = "tip_ground",
           .point = "tip",
           .radius = 0,
           .target = T::line,
           .a = "ground.O",
           .b = "ground.X",
           .law = l},
          {.name = "ball_circle",
           .point = "ball.C",
           .radius = 0.1,
           .target = T::circle,
           .a = "tip",
           .target_radius = 0.3,
           .law = l},
          {.name = "ball_hole",
           .point = "ball.C",
           .radius = 0.1,
           .target = T::hole,
           .a = "bar.B",
           .target_radius = 2.5,
           .law = l}};
}

}  // namespace

TEST(ContactGap, GradientRateAndCurvatureMatchFiniteDifferences) {
  const Model m = gap_scene();
  std::mt19937_64 rng(35);
  std::normal_distribution<double> n01(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q0 = m.q0, q1(m.n1);
    for (int i = 0; i < m.n0; ++i) q0[i] += 0.2 * n01(rng);
    for (int i = 0; i < m.n1; ++i) q1[i] = n01(rng);
    for (const ContactDef& c : gap_contacts()) {
      const GapValue g = contact_gap(m, c, q0, q1);
      const double h = 1e-6;
      for (int i = 0; i < m.n0; ++i) {  // node coordinates: the same index in q0 and q1
        Eigen::VectorXd qp = q0, qm = q0;
        qp[i] += h;
        qm[i] -= h;
        const double fd = (contact_gap(m, c, qp, q1).g - contact_gap(m, c, qm, q1).g) / (2 * h);
        EXPECT_NEAR(g.J[i], fd, 1e-8 * (1 + std::abs(fd))) << c.name << " coordinate " << i;
      }
      EXPECT_NEAR(g.rate, g.J.dot(q1), 1e-12 * (1 + std::abs(g.rate))) << c.name;
      const Eigen::VectorXd qp = q0 + h * q1.head(m.n0), qm = q0 - h * q1.head(m.n0);
      const double fd2 =
          (contact_gap(m, c, qp, q1).rate - contact_gap(m, c, qm, q1).rate) / (2 * h);
      EXPECT_NEAR(g.curvature, fd2, 1e-6 * (1 + std::abs(fd2))) << c.name;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 80);
}

// The closed forms at one configuration: the ball 0.7 above the ground line O -> X of slope
// 0.2, its circle of radius 0.1 around it (g = distance - r), in a hole of radius 2.5 around bar.B.
TEST(ContactGap, ValuesMatchClosedForms) {
  const Model m = gap_scene();
  const std::vector<ContactDef> cs = gap_contacts();
  const Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
  ContactDef ground = cs[0];
  ground.a = "ground.O";
  ground.b = "ground.X";
  const double d = (2 - 0.2 * 0.4) / std::sqrt(1 + 0.04);  // (C - O) . z x (X - O) / |X - O|
  EXPECT_NEAR(contact_gap(m, ground, m.q0, q1).g, d - 0.1, 1e-14);
  const double D = std::hypot(0.4 - 1, 2 - 1.3);
  EXPECT_NEAR(contact_gap(m, cs[3], m.q0, q1).g, 2.5 - 0.1 - D, 1e-14);
}

TEST(ContactGap, BadDefinitionsNameTheContact) {
  const Model m = gap_scene();
  ContactDef c = gap_contacts()[0];
  c.point = "ball.Q";
  try {
    (void)contact_gap(m, c, m.q0, Eigen::VectorXd::Zero(m.n1));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ball_bar"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ball.Q"), std::string::npos) << e.what();
  }
  c = gap_contacts()[3];
  c.target_radius = 0.05;
  EXPECT_THROW((void)contact_gap(m, c, m.q0, Eigen::VectorXd::Zero(m.n1)), Error);
  c = gap_contacts()[0];
  c.b = "bar.A";
  EXPECT_THROW((void)contact_gap(m, c, m.q0, Eigen::VectorXd::Zero(m.n1)), Error);
}

// The cam profile contact (src/contact/profile.hpp): its gap against a brute-force distance to the
// curve, its gradient J against central differences in every node coordinate, g' = J q1, and
// J' q1 against the central difference of J q1 along q1, at random configurations of a free cam
// (its nodes perturbed off the rigid shape: the gap is a function of the coordinates alone) and a
// follower point or roller near every part of a profile that is convex and concave; and the
// refusals: a table that is not periodic, a radius <= 0, a roller larger than a concave part's
// radius of curvature (an undercut), friction.

namespace {

constexpr double kPi = std::numbers::pi;

// r(phi) = R0 + a cos(3 phi) sampled every 5 deg: convex near phi = 0, concave near phi = 60 deg
// (radius of curvature 0.032 m there with R0 = 0.05, a = 0.01).
std::shared_ptr<const LookupTable> trefoil(double R0 = 0.05, double a = 0.01, int n = 72,
                                           Extrapolation ext = Extrapolation::periodic) {
  std::vector<double> x, y;
  for (int i = 0; i <= n; ++i) {
    const double phi = 2 * kPi * i / n;
    x.push_back(phi);
    y.push_back(R0 + a * std::cos(3 * phi));
  }
  return std::make_shared<const LookupTable>("trefoil", x, y,
                                             TableOptions{Interpolation::cubic, ext});
}

// a free cam (nodes O, A: the profile's centre and axis) and a ball (one node C)
Model profile_scene() {
  System s("profile");
  s.add_ground_node("G", {0, 0});
  s.add_body({.name = "cam",
              .nodes = {{"O", {0.1, 0.2}}, {"A", {0.13, 0.22}}},
              .mass = 1,
              .inertia = 0.01,
              .com = CenterOfMass::between("O", "A", 0)});
  s.add_body({.name = "ball", .nodes = {{"C", {0.1, 0.3}}}, .mass = 1, .inertia = 1e-4});
  return build_model(s);
}

ContactDef profile_contact(double radius, std::shared_ptr<const LookupTable> table) {
  return {.name = "cam_ball",
          .point = "ball.C",
          .radius = radius,
          .target = ContactDef::Target::profile,
          .a = "cam.O",
          .b = "cam.A",
          .profile = std::move(table),
          .law = rigid(0.5)};
}

int node_var(const Model& m, const std::string& body, int local) {
  for (const Body& b : m.bodies)
    if (b.name == body) return b.nodes[static_cast<size_t>(local)].var;
  ADD_FAILURE() << "no body " << body;
  return 0;
}

// The profile's point at phi in the world with the frame O -> A of q0.
Eigen::Vector2d world_point(const LookupTable& r, const Eigen::Vector2d& O,
                            const Eigen::Vector2d& A, double phi) {
  const Eigen::Vector2d e1 = (A - O).normalized(), e2(-e1.y(), e1.x());
  return O + r(phi) * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

// The distance from P to the curve by brute force: a grid of 20000 angles, then golden-section
// refinement around the best one (independent of the Newton of profile.cpp).
double brute_distance(const LookupTable& r, const Eigen::Vector2d& O, const Eigen::Vector2d& A,
                      const Eigen::Vector2d& P) {
  auto dist = [&](double phi) { return (P - world_point(r, O, A, phi)).norm(); };
  const int n = 20000;
  double best = 1e300, at = 0;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * kPi * i / n, d = dist(phi);
    if (d < best) {
      best = d;
      at = phi;
    }
  }
  double lo = at - 2 * kPi / n, hi = at + 2 * kPi / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 80; ++i) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    (dist(a) < dist(b) ? hi : lo) = dist(a) < dist(b) ? b : a;
  }
  return dist(0.5 * (lo + hi));
}

}  // namespace

TEST(ProfileGap, MatchesBruteForceAndFiniteDifferences) {
  const Model m = profile_scene();
  const std::shared_ptr<const LookupTable> table = trefoil();
  const int o = node_var(m, "cam", 0), a = node_var(m, "cam", 1), c = node_var(m, "ball", 0);
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double radius = trial % 2 == 0 ? 0.0 : 0.02;  // a knife edge, a roller
    const ContactDef def = profile_contact(radius, table);
    Eigen::VectorXd q0 = m.q0, q1(m.n1);
    for (int i : {o, o + 1, a, a + 1}) q0[i] += 0.01 * u(rng);
    const Eigen::Vector2d O(q0[o], q0[o + 1]), A(q0[a], q0[a + 1]);
    // the ball's centre off the curve along its normal by radius + a few mm (either side)
    const double phi = kPi * u(rng), h0 = 1e-6;
    const Eigen::Vector2d Q = world_point(*table, O, A, phi);
    const Eigen::Vector2d T =
        world_point(*table, O, A, phi + h0) - world_point(*table, O, A, phi - h0);
    const Eigen::Vector2d nrm = Eigen::Vector2d(T.y(), -T.x()).normalized();
    const Eigen::Vector2d P = Q + (radius + 0.004 * u(rng)) * nrm;
    q0[c] = P.x();
    q0[c + 1] = P.y();
    for (int i = 0; i < m.n1; ++i) q1[i] = n01(rng);
    const GapValue g = contact_gap(m, def, q0, q1);
    EXPECT_NEAR(
        g.g + radius,
        (P - Q).dot(nrm) > 0 ? brute_distance(*table, O, A, P) : -brute_distance(*table, O, A, P),
        1e-10)
        << "trial " << trial;
    // fourth-order central differences (the cam's nodes are 0.036 m apart: g's higher
    // derivatives in their coordinates scale as 1/0.036^k, too large for a second-order one)
    const double h = 1e-5;
    auto diff = [&](auto f) { return (-f(2 * h) + 8 * f(h) - 8 * f(-h) + f(-2 * h)) / (12 * h); };
    for (int i = 0; i < m.n0; ++i) {
      const double fd = diff([&](double s) {
        Eigen::VectorXd q = q0;
        q[i] += s;
        return contact_gap(m, def, q, q1).g;
      });
      EXPECT_NEAR(g.J[i], fd, 1e-8 * (1 + std::abs(fd))) << "trial " << trial << " coord " << i;
    }
    EXPECT_NEAR(g.rate, g.J.dot(q1), 1e-12 * (1 + std::abs(g.rate)));
    auto rate_at = [&](double s) {
      const Eigen::VectorXd q = q0 + s * q1.head(m.n0);
      return contact_gap(m, def, q, q1).rate;
    };
    // J' q1 has large higher derivatives where the point is near a concave part's centre of
    // curvature (1 + kappa D small), and g' is only C^1 where the closest point crosses a knot
    // (the spline's third derivative jumps): the tolerance adds twice the difference's own
    // error, estimated from the same difference at h and h / 2
    const double fd2 = diff(rate_at),
                 fd2_half = (-rate_at(h) + 8 * rate_at(h / 2) - 8 * rate_at(-h / 2) + rate_at(-h)) /
                            (6 * h);
    EXPECT_NEAR(g.curvature, fd2_half, 1e-6 * (1 + std::abs(fd2)) + 2 * std::abs(fd2 - fd2_half))
        << "trial " << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 40);
}

TEST(ProfileGap, RefusesUnfitTables) {
  const Model m = profile_scene();
  const Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
  auto message = [&](const ContactDef& c) -> std::string {
    try {
      (void)contact_gap(m, c, m.q0, q1);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  auto has = [](const std::string& s, const char* what) {
    return s.find(what) != std::string::npos;
  };
  // not periodic
  std::string s = message(profile_contact(0, trefoil(0.05, 0.01, 72, Extrapolation::clamp)));
  EXPECT_TRUE(has(s, "cam_ball") && has(s, "not periodic")) << s;
  // r <= 0 somewhere: R0 = 0.005 < a (at phi = 60 deg)
  s = message(profile_contact(0, trefoil(0.005, 0.01)));
  EXPECT_TRUE(has(s, "cam_ball") && has(s, "<= 0 at phi = 60 deg")) << s;
  // an undercut: the concave parts' radius of curvature 0.032 m at 60, 180, 300 deg
  s = message(profile_contact(0.04, trefoil()));
  EXPECT_TRUE(has(s, "cam_ball") && has(s, "undercut") && has(s, "0.0316736 m at phi = ") &&
              (has(s, "= 60 deg") || has(s, "= 180 deg") || has(s, "= 300 deg")))
      << s;
  EXPECT_EQ(message(profile_contact(0.03, trefoil())), "no error");
  // friction
  ContactDef rough = profile_contact(0, trefoil());
  rough.law.friction = 0.2;
  s = message(rough);
  EXPECT_TRUE(has(s, "cam_ball") && has(s, "friction")) << s;
  // no table
  s = message(profile_contact(0, nullptr));
  EXPECT_TRUE(has(s, "cam_ball") && has(s, "table")) << s;
}
