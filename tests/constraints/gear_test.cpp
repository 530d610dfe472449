// Gear pairs and racks (src/constraints/gear.hpp) against closed forms.
//  - Two flywheels on ground-fixed axes, geared omega_2 = rho omega_1, a torque T on wheel 1:
//    alpha_1 = T / (I1 + rho^2 I2) (the equivalent inertia), the mesh torque on wheel 2 I2 rho
//    alpha_1, energy conserved (the mesh does no work).
//  - A housing c pinned to the ground with two shafts k and j on its own axes, geared
//    omega_j - omega_c = rho (omega_k - omega_c). With phi = theta_k - theta_c,
//      T = 1/2 J w_c^2 + 1/2 I_k (w_c + phi')^2 + 1/2 I_j (w_c + rho phi')^2,
//      J = I_c + m_k a^2 + m_j b^2 (a, b: the shafts' axes from the pivot),
//    a torque T_k on k from the ground gives the generalized forces (T_k, T_k) on (theta_c, phi):
//    constant accelerations from the 2 x 2 mass matrix. Held still (inverse dynamics, the
//    housing's pivot actuated, a motor between the housing and k): the motor torque
//    (I_k + rho^2 I_j) phi'', the holding torque (I_k + rho I_j) phi'', the mesh torques
//    rho I_j phi'' on j and -(1 - rho) rho I_j phi'' on the housing.
//  - A rack on a slide and a pinion on the ground: q'' = r alpha, the mass m on the rack and the
//    pinion inertia I: alpha = T / (I + m r^2), the rack force m r alpha.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "constraints/constraints.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

constexpr double I1 = 0.02, I2 = 0.05, rho = -0.6, T1 = 0.7;

BodyDef wheel(const std::string& name, Vec2 c, double mass, double inertia) {
  return {.name = name,
          .nodes = {{"C", c}, {"R", c + Vec2(0.1, 0.02)}},
          .mass = mass,
          .inertia = inertia};
}

System flywheels() {
  System s("flywheels");
  s.add_ground_node("O1", {0, 0});
  s.add_ground_node("O2", {0.3, 0});
  s.add_body(wheel("w1", {0, 0}, 1, I1));
  s.add_body(wheel("w2", {0.3, 0}, 1, I2));
  s.add_revolute({.name = "p1", .node_a = "ground.O1", .node_b = "w1.C"});
  s.add_revolute({.name = "p2", .node_a = "ground.O2", .node_b = "w2.C"});
  s.add_gear({.name = "mesh", .body = "w2", .driver = "w1", .ratio = rho});
  s.add_torque({.name = "drive", .body = "w1", .torque = [](double) { return T1; }});
  return s;
}

TEST(Gear, FlywheelsTurnWithTheEquivalentInertia) {
  const Model m = build_model(flywheels());
  EXPECT_EQ(m.dof, 1);
  const State s0 = consistent_state(m, {.positions = {}, .velocities = {{"w1.w", 1.0}}});
  EXPECT_NEAR(s0.q1[m.rate("w2.w")], rho, 1e-12);
  const Trajectory r =
      forward_dynamics(m, s0, {.t1 = 2, .samples = 21, .rtol = 1e-11, .atol = 1e-13});
  const double alpha = T1 / (I1 + rho * rho * I2);
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    EXPECT_NEAR(r.q1(i, m.rate("w1.w")), 1 + alpha * t, 1e-7) << t;
    EXPECT_NEAR(r.q1(i, m.rate("w2.w")), rho * (1 + alpha * t), 1e-7) << t;
    EXPECT_NEAR(r.reactions(i, r.reaction("mesh.torque")), I2 * rho * alpha, 1e-7) << t;
    EXPECT_NEAR(r.reactions(i, r.reaction("mesh.carrier_torque")), -(1 - rho) * I2 * rho * alpha,
                1e-7)
        << t;
    // phi is the unwrapped angle of w1 (it keeps growing past pi): equal to the nodes' angle to
    // the solver's tolerance, and to the closed form to the integration error of the positions
    // (a phase error that accumulates over the six turns)
    const double phi = r.q0(i, m.coordinate("mesh.phi"));
    const double theta =
        std::atan2(r.q0(i, m.coordinate("w1.R.y")), r.q0(i, m.coordinate("w1.R.x")));
    EXPECT_NEAR(std::remainder(phi - theta, 2 * std::numbers::pi), 0, 1e-12) << t;
    EXPECT_NEAR(phi, std::atan2(0.02, 0.1) + t + alpha * t * t / 2, 1e-6) << t;
  }
  EXPECT_GT(r.q0(r.time.size() - 1, m.coordinate("mesh.phi")), 4.0);
  EXPECT_LT(energy_balance_error(r), 1e-7);
  EXPECT_LT(r.residuals.col(0).maxCoeff(), 1e-9);
}

// The housing: pivot at O, input shaft k at (a, 0), output shaft j at (b, 0).
constexpr double Ic = 0.3, mc = 2, a = 0.4, b = -0.25, mk = 1.5, mj = 0.8, Ik = I1, Ij = I2;

System housing(bool held) {
  System s("housing");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "case",
              .nodes = {{"O", {0, 0}}, {"A", {a, 0}}, {"B", {b, 0}}},
              .mass = mc,
              .inertia = Ic});
  s.add_body(wheel("k", {a, 0}, mk, Ik));
  s.add_body(wheel("j", {b, 0}, mj, Ij));
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "case.O", .actuated = held});
  s.add_revolute({.name = "bk", .node_a = "case.A", .node_b = "k.C", .actuated = held});
  s.add_revolute({.name = "bj", .node_a = "case.B", .node_b = "j.C"});
  s.add_gear({.name = "mesh", .body = "j", .driver = "k", .carrier = "case", .ratio = rho});
  if (!held) s.add_torque({.name = "drive", .body = "k", .torque = [](double) { return T1; }});
  if (held) s.add_coordinate({.name = "case.angle", .rate = {{"case.w", 1.0}}});
  return s;
}

TEST(Gear, HousingFreeToTurnFollowsTheTwoByTwoMassMatrix) {
  const Model m = build_model(housing(false));
  EXPECT_EQ(m.dof, 2);
  const double J = Ic + mk * a * a + mj * b * b;
  Eigen::Matrix2d M;
  M << J + Ik + Ij, Ik + rho * Ij, Ik + rho * Ij, Ik + rho * rho * Ij;
  const Eigen::Vector2d acc = M.lu().solve(Eigen::Vector2d(T1, T1));  // (alpha_c, phi'')
  const State s0 =
      consistent_state(m, {.positions = {}, .velocities = {{"case.w", 0.0}, {"k.w", 0.0}}});
  const Trajectory r = forward_dynamics(m, s0, {.t1 = 1, .samples = 11});
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const double wc = acc[0] * t, wk = wc + acc[1] * t, wj = wc + rho * acc[1] * t;
    EXPECT_NEAR(r.q1(i, m.rate("case.w")), wc, 1e-7) << t;
    EXPECT_NEAR(r.q1(i, m.rate("k.w")), wk, 1e-7) << t;
    EXPECT_NEAR(r.q1(i, m.rate("j.w")), wj, 1e-7) << t;
    const double tau = Ij * (acc[0] + rho * acc[1]);  // the only torque on j
    EXPECT_NEAR(r.reactions(i, r.reaction("mesh.torque")), tau, 1e-7) << t;
    EXPECT_NEAR(r.reactions(i, r.reaction("mesh.carrier_torque")), -(1 - rho) * tau, 1e-7) << t;
  }
  EXPECT_LT(energy_balance_error(r), 1e-7);
}

TEST(Gear, HeldHousingCarriesTheReactionTorque) {
  const Model m = build_model(housing(true));
  const Model m_none = build_model(housing(true), {.reduction = Reduction::none});
  const double phidd = 1.3;
  const std::vector<Prescribed> p = {
      {"case.angle", [](Jet) { return Jet(0.0); }},
      {"mesh.phi", [&](Jet t) { return 0.2 + 0.5 * phidd * t * t; }}};
  for (const bool lagrange : {false, true}) {
    const Trajectory r = lagrange ? inverse_dynamics_lagrange(m_none, p, {.t1 = 1, .samples = 5})
                                  : inverse_dynamics(m, p, {.t1 = 1, .samples = 5});
    for (int i = 0; i < r.time.size(); ++i) {
      EXPECT_NEAR(r.efforts(i, r.effort("bk.torque")), (Ik + rho * rho * Ij) * phidd, 1e-9);
      EXPECT_NEAR(r.efforts(i, r.effort("pivot.torque")), (Ik + rho * Ij) * phidd, 1e-9);
      EXPECT_NEAR(r.reactions(i, r.reaction("mesh.torque")), rho * Ij * phidd, 1e-9);
      EXPECT_NEAR(r.reactions(i, r.reaction("mesh.carrier_torque")), -(1 - rho) * rho * Ij * phidd,
                  1e-9);
    }
  }
}

// Rack of mass m on a horizontal slide along x, pinion (inertia I) on a ground axis above it.
constexpr double rack_m = 3, pinion_I = 0.01, radius = -0.05;

System rack_and_pinion() {
  System s("rack");
  s.add_ground_node("O", {0, 0.05});
  s.add_ground_node("X0", {-1, 0});
  s.add_ground_node("X1", {1, 0});
  s.add_body({.name = "rack", .nodes = {{"P", {0.1, 0}}}, .mass = rack_m});
  s.add_body(wheel("pinion", {0, 0.05}, 1, pinion_I));
  s.add_prismatic(
      {.name = "slide", .axis_from = "ground.X0", .axis_to = "ground.X1", .slider = "rack.P"});
  s.add_revolute({.name = "axle", .node_a = "ground.O", .node_b = "pinion.C"});
  s.add_rack({.name = "teeth", .slide = "slide", .pinion = "pinion", .radius = radius});
  s.add_torque({.name = "drive", .body = "pinion", .torque = [](double) { return T1; }});
  return s;
}

TEST(Gear, RackFollowsThePinion) {
  const Model m = build_model(rack_and_pinion());
  EXPECT_EQ(m.dof, 1);
  const State s0 = consistent_state(m, {.positions = {}, .velocities = {{"pinion.w", 0.0}}});
  const Trajectory r = forward_dynamics(m, s0, {.t1 = 1, .samples = 11});
  const double alpha = T1 / (pinion_I + rack_m * radius * radius);
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    EXPECT_NEAR(r.q1(i, m.rate("pinion.w")), alpha * t, 1e-7);
    EXPECT_NEAR(r.q0(i, m.coordinate("slide.q")), 1.1 + radius * alpha * t * t / 2, 1e-8);
    EXPECT_NEAR(r.reactions(i, r.reaction("teeth.force")), rack_m * radius * alpha, 1e-7);
  }
  EXPECT_LT(energy_balance_error(r), 1e-7);
}

// d psi / d q0 of the gear rows against central differences (a moving carrier).
TEST(Gear, PositionJacobianMatchesFiniteDifferences) {
  const Model m = build_model(housing(false));
  Eigen::VectorXd q = m.q0;
  for (int k = 0; k < q.size(); ++k) q[k] += 0.01 * std::sin(3.0 * k + 1);
  for (const Constraint& c : m.constraints) {
    if (c.kind() != ConstraintKind::gear) continue;
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m.m0, m.n0);
    Eigen::VectorXd res(m.m0);
    detail::DenseSink sink{J};
    detail::position_rows(m, c, q, 0.0, res, sink);
    for (int k = 0; k < m.n0; ++k) {
      Eigen::VectorXd qp = q, qm = q, rp(m.m0), rm(m.m0);
      const double h = 1e-6;
      qp[k] += h;
      qm[k] -= h;
      detail::NullSink null;
      detail::position_rows(m, c, qp, 0.0, rp, null);
      detail::position_rows(m, c, qm, 0.0, rm, null);
      EXPECT_NEAR(J(c.row0, k), (rp[c.row0] - rm[c.row0]) / (2 * h), 1e-7) << k;
    }
  }
}

TEST(Gear, BadInputNamesTheGear) {
  System s = flywheels();
  s.add_gear({.name = "bad", .body = "w2", .driver = "w1", .ratio = 0});
  EXPECT_THROW(
      {
        try {
          build_model(s);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("gear 'bad'"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  System s2 = flywheels();
  s2.add_gear({.name = "self", .body = "w1", .driver = "w1", .ratio = 2});
  EXPECT_THROW(build_model(s2), Error);
}

}  // namespace
