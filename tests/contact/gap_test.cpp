// The gaps of the contact kinds (src/contact/point_line.hpp, circle_circle.hpp): their gradient J
// against central differences of g in every node coordinate, g' = J q1, and J' q1 against the
// central difference of J q1 along q1, at random configurations (not assembled: the gap is a
// function of the coordinates alone).
#include <gtest/gtest.h>

#include <random>

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
