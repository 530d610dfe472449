// The shaking force and moment (mo2d/design.hpp, frame.shaking.*) against the balance of momentum
// of the moving links, computed here from positions only: the centre of mass's acceleration and
// the rate of the angular momentum by central finite differences of the mass-weighted positions
// and body angles of the run's samples. Then metamorphic relations: turning the mechanism turns
// the shaking force with it, scaling the masses scales it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <numbers>
#include <span>

#include "mo2d/design.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace frame_loads_test {
namespace {

using namespace mo2d;
constexpr double kPi = std::numbers::pi;

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// A crank-rocker four-bar (ground 0.4, crank 0.1, coupler 0.35, rocker 0.3), turned by phi about
// the origin and moved by `shift`, masses and inertias times k, gravity turned with it.
struct FourBarCase {
  double phi = 0, k = 1;
  Vec2 shift{0, 0};
  Reduction reduction = Reduction::flat;
};
Model four_bar(const FourBarCase& c) {
  const double a = 0.1, b = 0.35, cr = 0.3, d = 0.4;
  const Eigen::Rotation2Dd R(c.phi);
  auto at = [&](Vec2 p) -> Vec2 { return R * p + c.shift; };
  const Vec2 A(0, a), B0(d, 0);
  const Vec2 AB0 = B0 - A;
  const double l = AB0.norm(), x = (b * b - cr * cr + l * l) / (2 * l);
  const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
  const Vec2 B = A + x * ex + std::sqrt(b * b - x * x) * ey;
  System s("fourbar");
  s.add_ground_node("A0", at({0, 0})).add_ground_node("B0", at(B0));
  s.add_body({.name = "crank",
              .nodes = {{"O", at({0, 0})}, {"A", at(A)}},
              .mass = 0.2 * c.k,
              .inertia = 0.2 * c.k * a * a / 12,
              .com = CenterOfMass::between("O", "A", 0.3)});
  s.add_body({.name = "coupler",
              .nodes = {{"A", at(A)}, {"B", at(B)}},
              .mass = 0.5 * c.k,
              .inertia = 0.5 * c.k * b * b / 12,
              .com = CenterOfMass::between("A", "B", 0.4, 0.2)});
  s.add_body({.name = "rocker",
              .nodes = {{"O", at(B0)}, {"B", at(B)}},
              .mass = 0.4 * c.k,
              .inertia = 0.4 * c.k * cr * cr / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  // body 1 the rocker, body 2 the ground's node: the other sign of the frame's share
  s.add_revolute({.name = "rocker_pivot", .node_a = "rocker.O", .node_b = "ground.B0"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity(R * Vec2(0, -9.81));
  return build_model(s, {.reduction = c.reduction});
}

Trajectory run(const Model& m, double theta0, int samples = 1001) {
  const std::vector<Prescribed> motion{
      {"crank.angle", [theta0](Jet t) { return theta0 + 2 * kPi * t; }}};
  InverseOptions o;
  o.t0 = 0;
  o.t1 = 1;
  o.samples = samples;
  return inverse_dynamics(m, motion, o);
}

// What the shaking force and moment about P must be by the balance of momentum of the moving
// links with gravity as their only load besides the frame: F = sum m g - d/dt sum m v_G,
// M = sum (x_G - P) x m g - dH_P/dt, H_P = sum I w + m (x_G - P) x v_G; the rates by fourth-order
// central differences of positions and body angles (valid at samples 4 .. N-5).
struct Balance {
  std::vector<Vec2> F;
  std::vector<double> M;
};
template <class T>
T rate(const std::vector<T>& x, Eigen::Index k, double h) {
  return (x[k - 2] - 8.0 * x[k - 1] + 8.0 * x[k + 1] - x[k + 2]) / (12 * h);
}
template <class T>
T second_rate(const std::vector<T>& x, Eigen::Index k, double h) {
  return (-x[k - 2] + 16.0 * x[k - 1] - 30.0 * x[k] + 16.0 * x[k + 1] - x[k + 2]) / (12 * h * h);
}
Balance momentum_balance(const Model& m, const Trajectory& r, const Vec2& P) {
  const Eigen::Index N = r.time.size();
  const double h = r.time[1] - r.time[0];
  const int nb = static_cast<int>(m.bodies.size());
  std::vector<std::vector<Vec2>> x(nb, std::vector<Vec2>(N));
  std::vector<std::vector<double>> th(nb, std::vector<double>(N));
  for (int b = 0; b < nb; ++b)
    for (Eigen::Index k = 0; k < N; ++k) {
      const Eigen::VectorXd q0 = r.q0.row(k).transpose();
      x[b][k] = com_position(m.bodies[b], q0);
      const double t = m.bodies[b].nodes.size() >= 2 ? body_angle(m.bodies[b], q0) : 0.0;
      th[b][k] = k == 0 ? t : th[b][k - 1] + std::remainder(t - th[b][k - 1], 2 * kPi);
    }
  std::vector<double> H(N, 0.0);
  Balance out{std::vector<Vec2>(N, Vec2(0, 0)), std::vector<double>(N, 0.0)};
  for (int b = 0; b < nb; ++b) {
    const Body& body = m.bodies[b];
    for (Eigen::Index k = 2; k + 2 < N; ++k) {
      H[k] += body.inertia * rate(th[b], k, h) + body.mass * cross(x[b][k] - P, rate(x[b], k, h));
      out.F[k] += body.mass * (m.gravity - second_rate(x[b], k, h));
      out.M[k] += cross(x[b][k] - P, body.mass * m.gravity);
    }
  }
  for (Eigen::Index k = 4; k + 4 < N; ++k) out.M[k] -= rate(H, k, h);
  return out;
}

// Largest difference of the frame.shaking columns from the momentum balance, relative to the
// largest shaking force (and moment).
struct Gap {
  double force = 0, moment = 0;
};
Gap gap(const Model& m, Trajectory& r, const Vec2& P) {
  add_design_columns(m, r, {.frame = true, .moment_about = P});
  const Balance bal = momentum_balance(m, r, P);
  const int fx = r.output("frame.shaking.Fx"), fy = r.output("frame.shaking.Fy"),
            mz = r.output("frame.shaking.M");
  double F_max = 0, M_max = 0;
  Gap g;
  for (Eigen::Index k = 4; k + 4 < r.time.size(); ++k) {
    const Vec2 F(r.outputs(k, fx), r.outputs(k, fy));
    F_max = std::max(F_max, F.norm());
    M_max = std::max(M_max, std::abs(r.outputs(k, mz)));
    g.force = std::max(g.force, (F - bal.F[k]).norm());
    g.moment = std::max(g.moment, std::abs(r.outputs(k, mz) - bal.M[k]));
  }
  std::cout << "  " << m.name << ": shaking force within " << g.force / F_max
            << " of the momentum balance, moment within " << g.moment / M_max << "\n";
  return {g.force / F_max, g.moment / M_max};
}

// Fourth-order central differences with h = 1e-3 s at 1 rev/s: their error, ~h^4 of the sixth
// derivatives, and rounding (~1e-16 x / h^2) are ~1e-9 of the forces (measured below); a wrong
// sign of one joint's share is of order 1.
constexpr double kFdTolerance = 1e-7;

TEST(FrameLoads, FourBarMatchesMomentumBalance) {
  for (Reduction red : {Reduction::flat, Reduction::none}) {
    const Model m = four_bar({.reduction = red});
    Trajectory r = run(m, kPi / 2);
    const Gap g = gap(m, r, Vec2(0.1, -0.05));
    EXPECT_LT(g.force, kFdTolerance) << static_cast<int>(red);
    EXPECT_LT(g.moment, kFdTolerance) << static_cast<int>(red);
  }
}

TEST(FrameLoads, SliderCrankMatchesMomentumBalance) {
  // the rail: a prismatic joint on the ground (its reaction includes no actuator here)
  const mechanisms::Example e = mechanisms::slider_crank({.omega = 2 * kPi});
  for (Reduction red : {Reduction::flat, Reduction::none}) {
    const Model m = build_model(e.system, {.reduction = red});
    InverseOptions o;
    o.t0 = 0;
    o.t1 = 1;
    o.samples = 1001;
    Trajectory r = inverse_dynamics(m, e.motion, o);
    const Gap g = gap(m, r, Vec2(-0.2, 0.3));
    EXPECT_LT(g.force, kFdTolerance);
    EXPECT_LT(g.moment, kFdTolerance);
  }
}

// A crank held by a spring-damper and a torsional spring to the ground: their shares of the frame
// load (the spring at its ground point, the torsional spring's torque on the ground).
TEST(FrameLoads, GroundSpringsMatchMomentumBalance) {
  System s("crank");
  s.set_gravity({0, -9.81});
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {0.3, 0}}},
              .mass = 2,
              .inertia = 0.03,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  s.add_spring({.name = "lin",
                .body_a = "ground",
                .point_a = {0, -0.5},
                .body_b = "crank",
                .point_b = {0.3, 0},
                .rest_length = 0.2,
                .stiffness = 100,
                .damping = 5});
  s.add_torsional_spring({.name = "twist", .joint = "pivot", .stiffness = 3, .damping = 0.1});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  const Model m = build_model(s);
  Trajectory r = run(m, 0);
  const Gap g = gap(m, r, Vec2(0.2, 0.1));
  EXPECT_LT(g.force, kFdTolerance);
  EXPECT_LT(g.moment, kFdTolerance);
}

// Turning the mechanism (and gravity) by phi about the origin turns the shaking force by phi and
// leaves the moment about the turned point unchanged; moving it leaves both unchanged about the
// moved point; scaling every mass and inertia by k scales both by k.
TEST(FrameLoads, TurnsAndScalesWithTheMechanism) {
  const Vec2 P(0.15, 0.05);
  auto shaking = [&](const FourBarCase& c, const Vec2& about) {
    const Model m = four_bar(c);
    Trajectory r = run(m, kPi / 2 + c.phi, 41);
    add_design_columns(m, r, {.frame = true, .moment_about = about});
    return Eigen::MatrixXd(r.outputs.rightCols(4));  // Fx, Fy, F, M
  };
  const Eigen::MatrixXd base = shaking({}, P);
  const double scale = base.col(2).maxCoeff();
  for (double phi : {0.7, -2.1, kPi}) {
    const Eigen::Rotation2Dd R(phi);
    const Vec2 shift(0.3, -1.2);
    const Eigen::MatrixXd turned = shaking({.phi = phi, .shift = shift}, R * P + shift);
    for (Eigen::Index k = 0; k < base.rows(); ++k) {
      const Vec2 F = R * Vec2(base(k, 0), base(k, 1));
      EXPECT_NEAR(turned(k, 0), F.x(), 1e-9 * scale) << "phi " << phi << " sample " << k;
      EXPECT_NEAR(turned(k, 1), F.y(), 1e-9 * scale) << "phi " << phi << " sample " << k;
      EXPECT_NEAR(turned(k, 3), base(k, 3), 1e-9 * scale) << "phi " << phi << " sample " << k;
    }
  }
  const Eigen::MatrixXd heavy = shaking({.k = 3.5}, P);
  EXPECT_LT((heavy - 3.5 * base).cwiseAbs().maxCoeff(), 1e-9 * scale);
}

TEST(FrameLoads, RefusesWhatItDoesNotCompute) {
  System s("geared");
  s.add_ground_node("O", {0, 0}).add_ground_node("Q", {1, 0});
  s.add_body({.name = "g1", .nodes = {{"O", {0, 0}}, {"R", {0.2, 0}}}, .mass = 1, .inertia = 0.1});
  s.add_body({.name = "g2", .nodes = {{"O", {1, 0}}, {"R", {1.4, 0}}}, .mass = 1, .inertia = 0.1});
  s.add_revolute({.name = "p1", .node_a = "ground.O", .node_b = "g1.O", .actuated = true});
  s.add_revolute({.name = "p2", .node_a = "ground.Q", .node_b = "g2.O"});
  s.add_gear({.name = "mesh", .body = "g2", .driver = "g1", .ratio = -2});
  const Model m = build_model(s);
  Trajectory r;
  r.time = Eigen::VectorXd::Zero(1);
  r.q0 = m.q0.transpose();
  r.q1 = Eigen::MatrixXd::Zero(1, m.n1);
  r.reactions = Eigen::MatrixXd::Zero(1, m.n_reactions());
  r.reaction_labels = m.reaction_labels();
  r.input_labels = m.input_labels();
  r.efforts = Eigen::MatrixXd::Zero(1, m.n_inputs());
  try {
    add_design_columns(m, r, {.frame = true});
    FAIL() << "a gear's share of the frame load was computed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gear 'mesh'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frame_loads_test
