// Four-bar measures (mo2d/design.hpp): Grashof's classes; the run's transmission angle against the
// cosine law; the run's velocity ratio against the rate of its output angle; limit positions
// (closed form) where the run's output stops and reaches its extremes; dead positions of a
// triple-rocker from the loop's geometry; coupler points on the other branch against a model
// assembled on that branch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/design.hpp"
#include "mo2d/mo2d.hpp"

namespace four_bar_test {
namespace {

using namespace mo2d;
constexpr double kPi = std::numbers::pi;

// A four-bar with input pivot A0 at the origin, B0 = (d, 0), input at theta0, B on the branch of
// FourBarPositions (the clockwise side of B0 -> A; `other`: the mirror side), a named point "P" on
// the coupler at (along, across) of A -> B.
Model loop(const FourBarLengths& l, double theta0, bool other = false, double along = 0.4,
           double across = 0.3) {
  const double a = l.input, b = l.coupler, c = l.output, d = l.ground;
  const Vec2 A0(0, 0), B0(d, 0), A(a * std::cos(theta0), a * std::sin(theta0));
  const Vec2 AB0 = B0 - A;
  const double z = AB0.norm(), x = (b * b - c * c + z * z) / (2 * z);
  const Vec2 ex = AB0 / z, ey(-ex.y(), ex.x());
  const Vec2 B = A + x * ex + (other ? -1 : 1) * std::sqrt(b * b - x * x) * ey;
  const Vec2 u = B - A, P = A + along * u + across * Vec2(-u.y(), u.x());
  System s("loop");
  s.add_ground_node("A0", A0).add_ground_node("B0", B0);
  s.add_body({.name = "crank", .nodes = {{"O", A0}, {"A", A}}, .mass = 0.2, .inertia = 1e-3});
  s.add_body({.name = "coupler", .nodes = {{"A", A}, {"B", B}}, .mass = 0.5, .inertia = 5e-3});
  s.add_body({.name = "rocker", .nodes = {{"O", B0}, {"B", B}}, .mass = 0.4, .inertia = 3e-3});
  s.add_revolute({.name = "pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "pin_a", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "pin_b", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "pivot_b", .node_a = "ground.B0", .node_b = "rocker.O"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.add_point({.name = "P", .body = "coupler", .point = P});
  return build_model(s);
}

const FourBarDef kLoop{"L", "ground.A0", "coupler.A", "coupler.B", "ground.B0", {"P"}};
const FourBarLengths kCrankRocker{0.4, 0.1, 0.35, 0.3};

// The crank from theta0 to theta1 in [0, 1] s; the design columns of the loop.
Trajectory turn(const Model& m, double theta0, double theta1, int samples) {
  const std::vector<Prescribed> motion{
      {"crank.angle", [=](Jet t) { return theta0 + (theta1 - theta0) * t; }}};
  InverseOptions o;
  o.t0 = 0;
  o.t1 = 1;
  o.samples = samples;
  Trajectory r = inverse_dynamics(m, motion, o);
  add_output_columns(m, r, OutputRequest{.all_points = true});
  add_design_columns(m, r, {.four_bars = {kLoop}});
  return r;
}

TEST(FourBar, GrashofClasses) {
  struct Case {
    FourBarLengths l;
    GrashofClass want;
  };
  const Case cases[] = {
      {{0.4, 0.1, 0.35, 0.3}, GrashofClass::crank_rocker},
      {{0.1, 0.4, 0.35, 0.3}, GrashofClass::double_crank},
      {{0.4, 0.3, 0.35, 0.1}, GrashofClass::rocker_crank},
      {{0.4, 0.3, 0.1, 0.35}, GrashofClass::double_rocker},
      {{0.4, 0.2, 0.4, 0.2}, GrashofClass::change_point},
      {{0.4, 0.3, 0.35, 0.32}, GrashofClass::triple_rocker},
  };
  for (const Case& c : cases) EXPECT_EQ(grashof_class(c.l), c.want) << to_string(c.want);
  EXPECT_THROW(grashof_class({1.0, 0.1, 0.2, 0.3}), Error);  // cannot close
  EXPECT_THROW(grashof_class({0.4, 0.0, 0.35, 0.3}), Error);
  EXPECT_THROW(grashof_class({0.4, std::nan(""), 0.35, 0.3}), Error);
}

// Over a turn of the crank: the transmission angle of the run's positions is the cosine law's at
// the run's input angle; the velocity ratio is d(output angle)/d(input angle) of the run's
// positions (central differences, error ~ (2 pi / 2000)^2).
TEST(FourBar, TransmissionAngleAndVelocityRatioMatchTheRun) {
  const Model m = loop(kCrankRocker, kPi / 2);
  const Trajectory r = turn(m, kPi / 2, kPi / 2 + 2 * kPi, 2001);
  const int in = r.output("L.input_angle"), out = r.output("L.output_angle"),
            mu = r.output("L.transmission_angle"), ratio = r.output("L.velocity_ratio");
  double worst_mu = 0, worst_ratio = 0;
  for (Eigen::Index k = 1; k + 1 < r.time.size(); ++k) {
    worst_mu = std::max(
        worst_mu, std::abs(r.outputs(k, mu) - transmission_angle(kCrankRocker, r.outputs(k, in))));
    const double dpsi = std::remainder(r.outputs(k + 1, out) - r.outputs(k - 1, out), 2 * kPi);
    const double dth = std::remainder(r.outputs(k + 1, in) - r.outputs(k - 1, in), 2 * kPi);
    worst_ratio = std::max(worst_ratio, std::abs(r.outputs(k, ratio) - dpsi / dth));
  }
  EXPECT_LT(worst_mu, 1e-10);
  EXPECT_LT(worst_ratio, 1e-5);
  // the run's extremes of mu are the closed forms' (at theta = 0 and pi, both sampled)
  const FourBarPositions p = four_bar_positions(kCrankRocker);
  EXPECT_NEAR(r.outputs.col(mu).minCoeff(), p.min_transmission, 1e-10);
  EXPECT_NEAR(r.outputs.col(mu).maxCoeff(), p.max_transmission, 1e-10);
}

// At the closed form's limit positions the run's output stops (velocity ratio 0) at the closed
// form's output angle, and over a turn the output's extremes are those angles.
TEST(FourBar, LimitPositionsStopTheOutput) {
  const FourBarPositions p = four_bar_positions(kCrankRocker);
  ASSERT_TRUE(p.input_rotates);
  const Model m = loop(kCrankRocker, kPi / 2);
  for (const auto& [theta, psi] :
       {std::pair{p.limit_extended, p.output_extended}, {p.limit_folded, p.output_folded}}) {
    const double to = kPi / 2 + std::remainder(theta - kPi / 2, 2 * kPi);
    const Trajectory r = turn(m, kPi / 2, to, 51);
    const Eigen::Index last = r.time.size() - 1;
    EXPECT_NEAR(r.outputs(last, r.output("L.velocity_ratio")), 0, 1e-9) << theta;
    EXPECT_NEAR(r.outputs(last, r.output("L.output_angle")), psi, 1e-9) << theta;
  }
  const Trajectory r = turn(m, kPi / 2, kPi / 2 + 2 * kPi, 721);
  const Eigen::VectorXd psi = r.outputs.col(r.output("L.output_angle"));
  EXPECT_NEAR(psi.maxCoeff(), std::max(p.output_extended, p.output_folded), 1e-5);
  EXPECT_NEAR(psi.minCoeff(), std::min(p.output_extended, p.output_folded), 1e-5);
}

// A triple-rocker's input rocks between dead positions where coupler and output are in line:
// there |A - B0| = b + c (or |b - c|), from the positions.
TEST(FourBar, DeadPositionsOfATripleRocker) {
  const FourBarLengths l{0.4, 0.3, 0.35, 0.32};
  const FourBarPositions p = four_bar_positions(l);
  ASSERT_FALSE(p.input_rotates);
  const Vec2 B0(l.ground, 0);
  for (double theta : {p.input_min, p.input_max}) {
    const double z = (l.input * Vec2(std::cos(theta), std::sin(theta)) - B0).norm();
    const double in_line = std::min(std::abs(z - (l.coupler + l.output)),
                                    std::abs(z - std::abs(l.coupler - l.output)));
    EXPECT_LT(in_line, 1e-12) << theta;
  }
  EXPECT_GT(p.input_max, p.input_min);
  // inside the range the loop closes, beyond it not
  EXPECT_TRUE(std::isfinite(transmission_angle(l, p.input_max - 1e-6)));
  EXPECT_TRUE(std::isnan(transmission_angle(l, p.input_max + 1e-6)));
  EXPECT_TRUE(std::isfinite(transmission_angle(l, p.input_min + 1e-6)));
  EXPECT_TRUE(std::isnan(transmission_angle(l, p.input_min - 1e-6)));
  // extremes of mu over the range: those of a scan of the cosine law
  double lo = kPi, hi = 0;
  for (int k = 0; k <= 20000; ++k) {
    const double mu = transmission_angle(l, p.input_min + (p.input_max - p.input_min) * k / 20000);
    lo = std::min(lo, mu);
    hi = std::max(hi, mu);
  }
  EXPECT_NEAR(p.min_transmission, lo, 1e-6);
  EXPECT_NEAR(p.max_transmission, hi, 1e-6);
}

// The coupler point on the other branch (L.other.P) is the point P of the same loop assembled on
// that branch, run through the same input angles.
TEST(FourBar, CouplerPointOnTheOtherBranch) {
  const Model m = loop(kCrankRocker, kPi / 2), mirror = loop(kCrankRocker, kPi / 2, true);
  const Trajectory r = turn(m, kPi / 2, kPi / 2 + 2 * kPi, 37);
  const Trajectory s = turn(mirror, kPi / 2, kPi / 2 + 2 * kPi, 37);
  double worst = 0;
  for (Eigen::Index k = 0; k < r.time.size(); ++k)
    worst = std::max(
        worst, (Vec2(r.outputs(k, r.output("L.other.P.x")), r.outputs(k, r.output("L.other.P.y"))) -
                Vec2(s.outputs(k, s.output("P.x")), s.outputs(k, s.output("P.y"))))
                   .norm());
  EXPECT_LT(worst, 1e-12);
  // and the mirror branch's transmission angle is the same (the cosine law holds on both)
  EXPECT_LT((r.outputs.col(r.output("L.transmission_angle")) -
             s.outputs.col(s.output("L.transmission_angle")))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

}  // namespace
}  // namespace four_bar_test
