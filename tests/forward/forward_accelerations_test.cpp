// forward_accelerations (mo2d/forward_data.hpp): the accelerations at one given state, against the
// closed form of a pendulum and against the rates forward_dynamics records along its own run.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "mo2d/forward_data.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

VectorXd row(const MatrixXd& x, int k) {
  return x.row(k).transpose();
}

}  // namespace

// Point mass m on a massless link of length L at angle theta from +x, rate w, pivot torque u,
// gravity -g y: m L^2 theta'' = u - m g L cos(theta), and the tip P = L (cos, sin) accelerates by
// L theta'' (-sin, cos) - L w^2 (cos, sin). Every formulation, at states in four quadrants.
TEST(ForwardAccelerations, PendulumClosedForm) {
  const double L = 0.7, mass = 2.0, g = 9.81;
  const Model m = build_model(mechanisms::pendulum({.L = L, .m = mass, .g = g}).system);
  const int iw = m.rate("link.w"), ix = m.coordinate("link.P.x"), iy = m.coordinate("link.P.y");
  for (Formulation f :
       {Formulation::augmented_lagrangian, Formulation::lagrange, Formulation::null_space}) {
    ForwardOptions o;
    o.formulation = f;
    ForwardData data(m, o);
    for (const auto& [theta, w, u] : {std::tuple{0.3, 0.0, 0.0}, std::tuple{1.2, -2.5, 4.0},
                                      std::tuple{-2.0, 1.5, -3.0}, std::tuple{2.8, 0.7, 25.0}}) {
      const State s = consistent_state(
          m, {.positions = {{"link.angle", theta}}, .velocities = {{"link.w", w}}});
      const VectorXd efforts = VectorXd::Constant(1, u);
      const VectorXd& a = forward_accelerations(m, data, 0.0, s.q0, s.q1, efforts);
      EXPECT_EQ(&a, &data.a);
      const double th_dd = (u - mass * g * L * std::cos(theta)) / (mass * L * L);
      const double ax = -L * th_dd * std::sin(theta) - L * w * w * std::cos(theta);
      const double ay = L * th_dd * std::cos(theta) - L * w * w * std::sin(theta);
      const double tol = 1e-9 * (1 + std::abs(th_dd) + w * w);
      EXPECT_NEAR(a[iw], th_dd, tol) << to_string(f) << " theta " << theta;
      EXPECT_NEAR(a[ix], ax, tol) << to_string(f) << " theta " << theta;
      EXPECT_NEAR(a[iy], ay, tol) << to_string(f) << " theta " << theta;
      EXPECT_DOUBLE_EQ(data.u[0], u);
    }
  }
}

// At every output time of a run, the accelerations of the recorded state and efforts are the
// rates the run recorded (the right-hand side the integrator evaluates): the double four-bar
// (passive, M positive definite: the Schur solve) away from its singular positions, and the
// pendulum driven by a torque (M singular: the KKT solve) on rk4.
TEST(ForwardAccelerations, MatchesTheRatesOfARun) {
  {
    const Model m = build_model(mechanisms::double_fourbar());
    const State s0 = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
    ForwardOptions o;
    o.t1 = 0.3;
    o.samples = 7;
    const Trajectory r = forward_dynamics(m, s0, o);
    ForwardData data(m, o);
    for (int k = 0; k < r.time.size(); ++k) {
      const VectorXd& a =
          forward_accelerations(m, data, r.time[k], row(r.q0, k), row(r.q1, k), VectorXd::Zero(0));
      const VectorXd expected = row(r.a1, k);
      EXPECT_LE((a - expected).lpNorm<Eigen::Infinity>(),
                1e-12 * (1 + expected.lpNorm<Eigen::Infinity>()))
          << "double four-bar, t = " << r.time[k];
    }
  }
  {
    const Model m = build_model(mechanisms::pendulum({.theta0 = -1.0}).system);
    const State s0 = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.5}}});
    ForwardOptions o;
    o.integrator = Integrator::rk4;
    o.t1 = 1;
    o.samples = 11;
    o.efforts = {[](double t) { return 3.0 * std::sin(2 * t); }};
    const Trajectory r = forward_dynamics(m, s0, o);
    ForwardData data(m, o);
    for (int k = 0; k < r.time.size(); ++k) {
      const VectorXd& a =
          forward_accelerations(m, data, r.time[k], row(r.q0, k), row(r.q1, k), row(r.efforts, k));
      const VectorXd expected = row(r.a1, k);
      EXPECT_LE((a - expected).lpNorm<Eigen::Infinity>(),
                1e-12 * (1 + expected.lpNorm<Eigen::Infinity>()))
          << "pendulum, t = " << r.time[k];
    }
  }
}

// A workspace of another model, or a state or efforts of the wrong size, are refused by name.
TEST(ForwardAccelerations, RefusesAMismatch) {
  const Model m = build_model(mechanisms::pendulum().system);
  const Model other = build_model(mechanisms::pendulum().system);
  ForwardData data(m);
  const VectorXd u = VectorXd::Zero(1), bad_u = VectorXd::Zero(2);
  EXPECT_THROW(forward_accelerations(other, data, 0, m.q0, VectorXd::Zero(m.n1), u), Error);
  EXPECT_THROW(forward_accelerations(m, data, 0, m.q0, VectorXd::Zero(m.n1), bad_u), Error);
  EXPECT_THROW(forward_accelerations(m, data, 0, m.q0, VectorXd::Zero(m.n1 + 1), u), Error);
  EXPECT_NO_THROW(forward_accelerations(m, data, 0, m.q0, VectorXd::Zero(m.n1), u));
  const VectorXd nan_u = VectorXd::Constant(1, NAN);
  EXPECT_THROW(forward_accelerations(m, data, 0, m.q0, VectorXd::Zero(m.n1), nan_u), Error);
}
