// Columns added on request (mo2d/output_columns.hpp): loads' values and powers against hand
// computations from the crank's geometry, their sum against load_power, named points and centres
// of mass against the rotation of the crank, CSV columns only when asked.
#include "mo2d/output_columns.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "mo2d/mo2d.hpp"

namespace {

using namespace mo2d;

constexpr double kL = 0.3;  // crank O (ground pivot) -> A

// A crank pivoted at the origin, A at (kL, 0), under gravity with: a force at (kL, 0.1) of
// (3, -2 w); a torque 0.5 + t; a linear spring-damper from the ground (0, -0.5) to A; a spring
// given by a law (5 extension + 0.2 rate) from the ground (0.5, 0.5) to (0.2, 0) on the crank; a
// torsional spring law -2 angle at the pivot; a named point "tip" at (kL, 0.1).
Model crank() {
  System s("crank");
  s.set_gravity({0, -9.81});
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {kL, 0}}},
              .mass = 2,
              .inertia = 0.03,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O"});
  s.add_force({.name = "push",
               .body = "crank",
               .point = {kL, 0.1},
               .fx = Law::constant(3),
               .fy = Law({"crank.w"}, [](std::span<const Jet> x, Jet) { return -2.0 * x[0]; })});
  s.add_torque({.name = "drive", .body = "crank", .torque = [](double t) { return 0.5 + t; }});
  s.add_spring({.name = "lin",
                .body_a = "ground",
                .point_a = {0, -0.5},
                .body_b = "crank",
                .point_b = {kL, 0},
                .rest_length = 0.2,
                .stiffness = 10,
                .damping = 0.5});
  s.add_spring({.name = "soft",
                .body_a = "ground",
                .point_a = {0.5, 0.5},
                .body_b = "crank",
                .point_b = {0.2, 0},
                .rest_length = 0.1,
                .tension = Law({"extension", "rate"}, [](std::span<const Jet> x, Jet) {
                  return 5.0 * x[0] + 0.2 * x[1];
                })});
  s.add_torsional_spring(
      {.name = "twist", .joint = "pivot", .torque = Law({"angle"}, [](std::span<const Jet> x, Jet) {
                                            return -2.0 * x[0];
                                          })});
  s.add_point({.name = "tip", .body = "crank", .point = {kL, 0.1}});
  return build_model(s);
}

Trajectory swing(const Model& m) {
  InitialConditions ic;
  ic.velocities = {{"crank.w", 2.0}};
  ForwardOptions o;
  o.t1 = 0.5;
  o.samples = 51;
  return forward_dynamics(m, consistent_state(m, ic), o);
}

// The crank's angle and rate from the coordinates of A (written out here, not the model's).
struct Crank {
  double th, w;
  Eigen::Vector2d a, va;
};
Crank crank_at(const Model& m, const Trajectory& r, int k) {
  const Eigen::Vector2d a(r.q0(k, m.coordinate("crank.A.x")), r.q0(k, m.coordinate("crank.A.y")));
  const Eigen::Vector2d va(r.q1(k, m.rate("crank.A.vx")), r.q1(k, m.rate("crank.A.vy")));
  return {std::atan2(a.y(), a.x()), (a.x() * va.y() - a.y() * va.x()) / a.squaredNorm(), a, va};
}
// A point fixed in the crank, given at the initial configuration (crank along x).
Eigen::Vector2d rotated(const Crank& c, const Eigen::Vector2d& p) {
  return {std::cos(c.th) * p.x() - std::sin(c.th) * p.y(),
          std::sin(c.th) * p.x() + std::cos(c.th) * p.y()};
}
Eigen::Vector2d velocity(const Crank& c, const Eigen::Vector2d& p) {
  const Eigen::Vector2d r = rotated(c, p);
  return c.w * Eigen::Vector2d(-r.y(), r.x());
}

TEST(OutputColumns, LoadsPointsAndCentresOfMassAgainstTheCranksGeometry) {
  const Model m = crank();
  Trajectory r = swing(m);
  add_output_columns(m, r, {.loads = true, .com = true, .points = {"tip"}});
  auto col = [&](const char* l) { return r.outputs.col(r.output(l)); };
  double max_speed = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const Crank c = crank_at(m, r, k);
    max_speed = std::max(max_speed, std::abs(c.w));
    // force: F = (3, -2 w), power F . v of its point
    const Eigen::Vector2d F(3, -2 * c.w), v = velocity(c, {kL, 0.1});
    EXPECT_NEAR(col("push.fx")[k], 3, 1e-14);
    EXPECT_NEAR(col("push.fy")[k], F.y(), 1e-12);
    EXPECT_NEAR(col("push.power")[k], F.dot(v), 1e-12);
    // torque: (0.5 + t) w
    EXPECT_NEAR(col("drive.torque")[k], 0.5 + r.time[k], 1e-14);
    EXPECT_NEAR(col("drive.power")[k], (0.5 + r.time[k]) * c.w, 1e-12);
    // linear spring from (0, -0.5) to A: T = k (l - l0) + c dl/dt, power -T dl/dt
    const Eigen::Vector2d d = c.a - Eigen::Vector2d(0, -0.5);
    const double l = d.norm(), ldot = d.dot(c.va) / l, T = 10 * (l - 0.2) + 0.5 * ldot;
    EXPECT_NEAR(col("lin.length")[k], l, 1e-12);
    EXPECT_NEAR(col("lin.rate")[k], ldot, 1e-12);
    EXPECT_NEAR(col("lin.tension")[k], T, 1e-11);
    EXPECT_NEAR(col("lin.power")[k], -T * ldot, 1e-11);
    // the law spring from (0.5, 0.5) to (0.2, 0) on the crank
    const Eigen::Vector2d e = rotated(c, {0.2, 0}) - Eigen::Vector2d(0.5, 0.5);
    const double le = e.norm(), lr = e.dot(velocity(c, {0.2, 0})) / le;
    EXPECT_NEAR(col("soft.tension")[k], 5 * (le - 0.1) + 0.2 * lr, 1e-11);
    EXPECT_NEAR(col("soft.power")[k], -(5 * (le - 0.1) + 0.2 * lr) * lr, 1e-11);
    // torsional law -2 angle (relative to the initial configuration), power torque w
    EXPECT_NEAR(col("twist.torque")[k], -2 * c.th, 1e-12);
    EXPECT_NEAR(col("twist.power")[k], -2 * c.th * c.w, 1e-12);
    // named point and centre of mass
    const Eigen::Vector2d tip = rotated(c, {kL, 0.1});
    EXPECT_NEAR(col("tip.x")[k], tip.x(), 1e-13);
    EXPECT_NEAR(col("tip.y")[k], tip.y(), 1e-13);
    EXPECT_NEAR(col("tip.vx")[k], v.x(), 1e-12);
    EXPECT_NEAR(col("tip.vy")[k], v.y(), 1e-12);
    EXPECT_NEAR(col("crank.com.x")[k], 0.5 * c.a.x(), 1e-14);
    EXPECT_NEAR(col("crank.com.vy")[k], 0.5 * c.va.y(), 1e-13);
  }
  EXPECT_GT(max_speed, 1.0);  // the crank turns: the velocity terms are exercised
}

// The powers of the loads given by a law (forces, torques, law springs) sum to load_power, what
// the energy balance integrates as work.loads; the linear spring's power is minus the rate of its
// potential less its damper's dissipation.
TEST(OutputColumns, PowersSumToWhatTheEnergyBalanceIntegrates) {
  const Model m = crank();
  Trajectory r = swing(m);
  add_output_columns(m, r, {.loads = true});
  for (int k = 0; k < r.time.size(); ++k) {
    const Eigen::VectorXd q0 = r.q0.row(k).transpose(), q1 = r.q1.row(k).transpose();
    double sum = 0;
    for (const char* l : {"push.power", "drive.power", "soft.power", "twist.power"})
      sum += r.outputs(k, r.output(l));
    EXPECT_NEAR(sum, load_power(m, q0, q1, r.time[k]), 1e-12) << "t = " << r.time[k];
    const double l = r.outputs(k, r.output("lin.length")),
                 ldot = r.outputs(k, r.output("lin.rate"));
    EXPECT_NEAR(r.outputs(k, r.output("lin.power")) + damping_power(m, q0, q1),
                -10 * (l - 0.2) * ldot, 1e-11);
  }
  // the integrated work: trapezoids of the CSV's powers against the run's work.loads
  double work = 0, scale = 0;
  for (int k = 1; k < r.time.size(); ++k) {
    double p0 = 0, p1 = 0;
    for (const char* l : {"push.power", "drive.power", "soft.power", "twist.power"}) {
      p0 += r.outputs(k - 1, r.output(l));
      p1 += r.outputs(k, r.output(l));
    }
    work += 0.5 * (p0 + p1) * (r.time[k] - r.time[k - 1]);
    scale = std::max(scale, std::abs(work));
  }
  // trapezoids over 50 intervals of 10 ms: error ~ dt^2 / 12 of the power's second derivative
  EXPECT_NEAR(work, r.load_work[r.time.size() - 1], 1e-3 * scale);
}

// A second formulation: the power of every load (the linear spring's too) plus that of gravity is
// the rate of the kinetic energy q1^T M a1 along the run (the pivot does no work; a1 from the
// run's accelerations, not from the loads' powers).
TEST(OutputColumns, EveryLoadsPowerPlusGravitysIsTheRateOfKineticEnergy) {
  const Model m = crank();
  Trajectory r = swing(m);
  add_output_columns(m, r, {.loads = true, .com = true});
  const Eigen::MatrixXd M = mass_matrix(m);
  double worst = 0, scale = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const Eigen::VectorXd q1 = r.q1.row(k).transpose(), a1 = r.a1.row(k).transpose();
    double p = 0;
    for (const char* l : {"push.power", "drive.power", "lin.power", "soft.power", "twist.power"})
      p += r.outputs(k, r.output(l));
    p += 2 * -9.81 * r.outputs(k, r.output("crank.com.vy"));  // m g . v of the centre of mass
    const double dK = q1.dot(M * a1);
    worst = std::max(worst, std::abs(p - dK));
    scale = std::max(scale, std::abs(dK));
  }
  EXPECT_GT(scale, 1.0);
  EXPECT_LT(worst, 1e-9 * scale) << "scale " << scale;
}

TEST(OutputColumns, CsvHasTheColumnsOnlyWhenAsked) {
  const Model m = crank();
  Trajectory r = swing(m);
  const std::string before = trajectory_csv(r);
  add_output_columns(m, r, {});
  EXPECT_EQ(trajectory_csv(r), before);
  EXPECT_EQ(before.find("push.power"), std::string::npos);
  add_output_columns(m, r, {.all_points = true});
  const std::string with = trajectory_csv(r);
  const std::string header = with.substr(0, with.find('\n'));
  EXPECT_NE(header.find(",tip.x,tip.y,tip.vx,tip.vy"), std::string::npos) << header;
  EXPECT_EQ(header.find("push"), std::string::npos);
  EXPECT_EQ(header.find("com"), std::string::npos);
  EXPECT_THROW(add_output_columns(m, r, {.all_points = true}), Error);  // twice the same columns
}

TEST(OutputColumns, UnknownPointIsNamedWithASuggestion) {
  const Model m = crank();
  Trajectory r = swing(m);
  try {
    add_output_columns(m, r, {.points = {"tpi"}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'tpi'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'tip'"), std::string::npos) << e.what();
  }
}

}  // namespace
