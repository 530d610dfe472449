// Joint friction (FrictionDef) against closed forms and a second formulation:
//  - a block on an incline (forward dynamics, regularized Coulomb): sliding, the exact
//    acceleration g (sin phi - mu cos phi); from rest, the velocity excess of the regularization
//    between its two bounds; sticking (tan phi < mu), the creep rate v_s atanh(tan phi / mu) of the
//    regularized law (the exact law: 0);
//  - the block pushed along a prescribed motion (inverse dynamics, exact Coulomb): the force
//    m a + m g sin phi + mu m g cos phi sign(v), with the jump where the block reverses;
//  - the slider-crank with rail friction: inverse dynamics (fixed-point iteration on the reduced
//    model) against the Lagrange-multiplier formulation of the same problem solved here directly
//    (all joints as rows, the Coulomb law's sign cases as linear systems), the rail force equal
//    to -mu |N| sign(v) and jumping by 2 mu |N| where the slider reverses;
//  - viscous friction in a revolute joint equals a torsional damper to round-off; the energy
//    balance of a forward run with Coulomb friction closes with its dissipation counted.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;
using mechanisms::Example;

namespace {

constexpr double kG = 9.81, kMass = 2.0;

// A block (one node, 2 kg) on a prismatic joint whose ground axis rises at phi from the origin;
// rail.q is the distance up the incline. actuated: the input "rail.force" along the axis.
Model incline(double phi, double mu, double vs = 1e-3, bool actuated = false,
              Reduction reduction = Reduction::flat) {
  System s("incline");
  const Vec2 e{std::cos(phi), std::sin(phi)};
  s.add_ground_node("A", {0, 0}).add_ground_node("B", e);
  s.add_body({.name = "block", .nodes = {{"P", 0.5 * e}}, .mass = kMass});
  s.add_prismatic({.name = "rail",
                   .axis_from = "ground.A",
                   .axis_to = "ground.B",
                   .slider = "block.P",
                   .actuated = actuated});
  s.add_friction({.name = "rail_friction", .joint = "rail", .mu = mu, .regularization = vs});
  s.set_gravity({0, -kG});
  return build_model(s, {.reduction = reduction});
}

ForwardOptions bdf(double t1, int samples) {
  ForwardOptions o;
  o.t1 = t1;
  o.samples = samples;
  o.integrator = Integrator::cvode_bdf;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  return o;
}

}  // namespace

// Sliding down from v0 = -1 m/s: tanh(v / v_s) = -1 to 1e-300, so q(t) = q0 + v0 t + a t^2 / 2
// with a = -g (sin phi - mu cos phi) (the friction mu m g cos phi up the incline).
TEST(Friction, BlockSlidingDownAnInclineHasTheExactAcceleration) {
  const double phi = std::numbers::pi / 6, mu = 0.2;
  const Model m = incline(phi, mu);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"rail.v", -1.0}}});
  const Trajectory r = forward_dynamics(m, s, bdf(0.3, 31));  // stays above 1 m/s downwards
  const int iq = r.column("rail.q");
  const double a = -kG * (std::sin(phi) - mu * std::cos(phi));
  double err = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const double t = r.time[k];
    err = std::max(err, std::abs(r.q0(k, iq) - (0.5 - t + 0.5 * a * t * t)));
  }
  EXPECT_LT(err, 1e-8);
  EXPECT_LT(energy_balance_error(r), 1e-8);
  EXPECT_GT(r.dissipated[r.time.size() - 1], 0.1);
}

// From rest above tan phi = mu: the regularized law lets the block accelerate a little faster
// while |v| < ~v_s. With w = -v, dw/dt = g sin phi - mu g cos phi tanh(w / v_s) and
// |a| t <= w <= g sin phi t, the velocity excess over the exact |a| t tends to
//   mu g cos phi * integral (1 - tanh(w / v_s)) dt  in  [ln 2 v_s / (g sin phi), ln 2 v_s / |a|]
// times mu g cos phi (integral of 1 - tanh(k t) = ln 2 / k).
TEST(Friction, BlockSlidingFromRestLeadsTheExactMotionByTheRegularizationBound) {
  const double phi = std::numbers::pi / 6, mu = 0.2, vs = 1e-3;
  const Model m = incline(phi, mu, vs);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"rail.v", 0.0}}});
  const Trajectory r = forward_dynamics(m, s, bdf(0.5, 11));
  const double a = kG * (std::sin(phi) - mu * std::cos(phi));
  const double excess = -r.q1(r.time.size() - 1, r.rate_column("rail.v")) - a * 0.5;
  const double nf = mu * kG * std::cos(phi) * std::log(2.0) * vs;
  std::printf("from rest: velocity excess %.6e m/s, bounds [%.6e, %.6e]\n", excess,
              nf / (kG * std::sin(phi)), nf / a);
  EXPECT_GE(excess, nf / (kG * std::sin(phi)) * (1 - 1e-6));
  EXPECT_LE(excess, nf / a * (1 + 1e-6));
  EXPECT_LT(energy_balance_error(r), 1e-8);
}

// Below tan phi = mu the exact block sticks. The regularized one creeps at the speed where
// mu g cos phi tanh(w / v_s) = g sin phi: w* = v_s atanh(tan phi / mu), reached within a few
// v_s / (mu g cos phi); the distance crept, w* t, is the regularization's error.
TEST(Friction, BlockOnAShallowInclineSticksUpToTheRegularizationCreep) {
  const double phi = 10 * std::numbers::pi / 180, mu = 0.3;
  for (double vs : {1e-3, 1e-4}) {
    const Model m = incline(phi, mu, vs);
    const State s = consistent_state(m, {.positions = {}, .velocities = {{"rail.v", 0.0}}});
    const Trajectory r = forward_dynamics(m, s, bdf(1.0, 11));
    const double creep = vs * std::atanh(std::tan(phi) / mu);
    const int last = static_cast<int>(r.time.size()) - 1;
    const double v = r.q1(last, r.rate_column("rail.v"));
    const double crept = 0.5 - r.q0(last, r.column("rail.q"));
    std::printf("stick, v_s = %g: creep %.6e m/s (closed form %.6e), crept %.6e m in 1 s\n", vs, -v,
                creep, crept);
    EXPECT_NEAR(-v, creep, 1e-6 * creep);
    EXPECT_NEAR(crept, creep * 1.0, 0.01 * creep);  // less the short start
    EXPECT_LT(energy_balance_error(r), 1e-9);
  }
}

// Inverse dynamics, exact Coulomb: rail.q = 0.5 + 0.1 sin(2 t) prescribed; the force along the
// axis is m q'' + m g sin phi + mu m g cos phi sign(q'), on both formulations of the model; it
// jumps by 2 mu m g cos phi where the block reverses (t = pi/4), and is 0 friction at v = 0.
TEST(Friction, InverseDynamicsOfThePushedBlockIsTheClosedForm) {
  const double phi = std::numbers::pi / 6, mu = 0.25;
  for (Reduction red : {Reduction::flat, Reduction::none}) {
    const Model m = incline(phi, mu, 1e-3, true, red);
    const std::vector<Prescribed> p = {{"rail.q", [](Jet t) { return 0.5 + 0.1 * sin(2.0 * t); }}};
    InverseOptions o;
    o.t0 = 0;
    o.t1 = std::numbers::pi / 2;
    o.samples = 9;  // t = k pi / 16: sample 4 is the reversal
    const Trajectory r = inverse_dynamics(m, p, o);
    double err = 0;
    for (int k = 0; k < r.time.size(); ++k) {
      const double t = r.time[k], v = 0.2 * std::cos(2 * t), acc = -0.4 * std::sin(2 * t);
      auto exact = [&](double sgn) {
        return kMass * (acc + kG * std::sin(phi) + mu * kG * std::cos(phi) * sgn);
      };
      if (k == 4) {  // the reversal: v is rounding (1e-17), the friction one of its limits
        const double e =
            std::min({std::abs(r.efforts(k, 0) - exact(1)), std::abs(r.efforts(k, 0) - exact(0)),
                      std::abs(r.efforts(k, 0) - exact(-1))});
        err = std::max(err, e);
        continue;
      }
      err = std::max(err, std::abs(r.efforts(k, 0) - exact((v > 0) - (v < 0))));
    }
    EXPECT_LT(err, 1e-12 * kMass * kG);
    // t = 3 pi / 16 and 5 pi / 16: the same acceleration, opposite velocities
    EXPECT_NEAR(r.efforts(3, 0) - r.efforts(5, 0), 2 * mu * kMass * kG * std::cos(phi), 1e-12);
  }
}

namespace {

// The slider-crank of mechanisms/slider_crank with friction mu in its rail.
Model slider_crank_with_friction(double mu, Reduction red) {
  Example ex = mechanisms::slider_crank();
  ex.system.add_friction({.name = "rail_friction", .joint = "rail", .mu = mu});
  return build_model(ex.system, {.reduction = red});
}

// The Lagrange-multiplier formulation with the rail friction, solved directly at one sample:
// every joint is rows (Reduction::none), M a - f - F e_q = B u - A^T lambda with the rail force
// F = -mu |R_y| sign(v) (the rail is horizontal: N = |R_y|, R_y = -lambda_y); for each sign s of
// R_y the system is linear; the consistent one (s R_y >= 0) is the solution. Returns u.
double lagrange_effort(const Model& m, const Trajectory& r, int k, double mu) {
  const VectorXd q0 = r.q0.row(k).transpose(), q1 = r.q1.row(k).transpose(),
                 a1 = r.a1.row(k).transpose();
  const double t = r.time[k];
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1), f(m.n1);
  velocity_jacobian(m, q0, t, A, b);
  applied_forces(m, q0, q1, t, f);
  const MatrixXd M = mass_matrix(m), B = input_matrix(m);
  const int q = m.rate("rail.v");
  int ry = -1;
  for (const auto& re : m.reactions)
    if (re.label == "rail.Fy") ry = re.row;
  const double v = q1[q], sgn = (v > 0) - (v < 0);
  for (double s : {1.0, -1.0}) {
    // F = -mu sgn s R_y = mu sgn s lambda_y:  A^T lambda - F e_q - B u = f - M a
    MatrixXd L(m.n1, m.m1 + 1);
    L.leftCols(m.m1) = A.transpose();
    L(q, ry) -= mu * sgn * s;
    L.col(m.m1) = -B.col(0);
    const VectorXd x = L.partialPivLu().solve(f - M * a1);
    if (-s * x[ry] >= 0) return x[m.m1];
  }
  ADD_FAILURE() << "no consistent sign at t = " << t;
  return 0;
}

}  // namespace

TEST(Friction, SliderCrankInverseDynamicsMatchesTheLagrangeFormulation) {
  const double mu = 0.2;
  const Example ex = mechanisms::slider_crank();
  InverseOptions o = ex.run;
  o.samples = 101;
  const Trajectory flat =
      inverse_dynamics(slider_crank_with_friction(mu, Reduction::flat), ex.motion, o);
  const Model none = slider_crank_with_friction(mu, Reduction::none);
  const Trajectory rows = inverse_dynamics(none, ex.motion, o);
  const Trajectory dry =
      inverse_dynamics(build_model(ex.system), ex.motion, o);  // without friction
  double err = 0, err_rows = 0, effect = 0;
  for (int k = 0; k < flat.time.size(); ++k) {
    const double u = lagrange_effort(none, rows, k, mu);
    err = std::max(err, std::abs(flat.efforts(k, 0) - u));
    err_rows = std::max(err_rows, std::abs(rows.efforts(k, 0) - u));
    effect = std::max(effect, std::abs(flat.efforts(k, 0) - dry.efforts(k, 0)));
  }
  std::printf(
      "slider-crank, mu = %g: torque vs Lagrange %.3e (rows %.3e) N m; friction's "
      "effect up to %.4f N m\n",
      mu, err, err_rows, effect);
  EXPECT_LT(err, 1e-11);
  EXPECT_LT(err_rows, 1e-11);
  EXPECT_GT(effect, 0.05);  // the friction is not negligible: the comparison can fail
}

// The rail's force along the axis on the slider is the friction itself: -mu |N| sign(v) at every
// sample, so it jumps by 2 mu |N| where the slider reverses (between two samples).
TEST(Friction, SliderCrankRailForceIsCoulombAndJumpsWhereTheSliderReverses) {
  const double mu = 0.2;
  const Example ex = mechanisms::slider_crank();
  const Model m = slider_crank_with_friction(mu, Reduction::flat);
  InverseOptions o = ex.run;
  o.samples = 400;  // no sample exactly at a reversal
  const Trajectory r = inverse_dynamics(m, ex.motion, o);
  const int fx = r.reaction("rail.Fx"), fy = r.reaction("rail.Fy");
  const int v = r.rate_column("rail.v");
  int reversals = 0;
  // the reaction's sign convention (Model::reactions): its axis part times sign(v) keeps one sign
  const double side = r.reactions(1, fx) * r.q1(1, v) > 0 ? 1.0 : -1.0;
  for (int k = 0; k < r.time.size(); ++k) {
    const double sgn = (r.q1(k, v) > 0) - (r.q1(k, v) < 0);
    // equal to the iteration's tolerance: 1e-12 of mu times the largest reaction (friction.hpp)
    const double tol = 1e-12 * mu * r.reactions.row(k).cwiseAbs().maxCoeff() + 1e-14;
    EXPECT_NEAR(r.reactions(k, fx), side * mu * std::abs(r.reactions(k, fy)) * sgn, tol);
    if (k > 0 && r.q1(k, v) * r.q1(k - 1, v) < 0) {
      ++reversals;
      const double jump = std::abs(r.reactions(k, fx) - r.reactions(k - 1, fx));
      const double n = 0.5 * (std::abs(r.reactions(k, fy)) + std::abs(r.reactions(k - 1, fy)));
      EXPECT_NEAR(jump, 2 * mu * n, 0.02 * 2 * mu * n) << "t = " << r.time[k];
    }
  }
  EXPECT_EQ(reversals, 4);  // two turns of the crank in 1 s
}

namespace {

// A disc (2 kg, I = 0.01 kg m^2, centre of mass at its pivot O) on an actuated revolute joint to
// the ground, with friction in the pin (radius r) and optionally viscous friction.
Model disc_on_pin(double mu, double radius, double viscous, Reduction red = Reduction::flat) {
  System s("disc");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "disc",
              .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}},
              .mass = kMass,
              .inertia = 0.01,
              .com = CenterOfMass::at_node("O")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "disc.O", .actuated = true});
  s.add_coordinate({.name = "disc.angle", .rate = {{"disc.w", 1.0}}});
  s.add_friction({.name = "pin", .joint = "pivot", .viscous = viscous, .mu = mu, .radius = radius});
  s.set_gravity({0, -kG});
  return build_model(s, {.reduction = red});
}

}  // namespace

// The pin carries the weight: |R| = m g, so the torque is I theta'' + c theta' + mu r m g
// sign(theta'), theta = sin(t) prescribed; on the reduced model (the reaction from the split at
// the eliminated joint) and with the joint as rows.
TEST(Friction, PinFrictionTorqueOfADiscIsTheClosedForm) {
  const double mu = 0.3, radius = 0.02, c = 0.05;
  for (Reduction red : {Reduction::flat, Reduction::none}) {
    const Model m = disc_on_pin(mu, radius, c, red);
    const std::vector<Prescribed> p = {{"disc.angle", [](Jet t) { return sin(t); }}};
    InverseOptions o;
    o.t1 = 3;
    o.samples = 31;
    const Trajectory r = inverse_dynamics(m, p, o);
    double err = 0;
    for (int k = 0; k < r.time.size(); ++k) {
      const double t = r.time[k], w = std::cos(t);
      const double exact =
          -0.01 * std::sin(t) + c * w + mu * radius * kMass * kG * ((w > 0) - (w < 0));
      err = std::max(err, std::abs(r.efforts(k, 0) - exact));
    }
    EXPECT_LT(err, 1e-13);
  }
}

// Viscous friction in the crank pivot of the slider-crank (no input, gravity, a spin) is the
// torsional damper of the same coefficient: the same forward run to round-off.
TEST(Friction, ViscousFrictionInARevoluteJointIsATorsionalDamper) {
  const double c = 0.02;
  Example a = mechanisms::slider_crank(), b = mechanisms::slider_crank();
  a.system.add_friction({.name = "pivot_friction", .joint = "crank_pivot", .viscous = c});
  b.system.add_torsional_spring({.name = "damper", .joint = "crank_pivot", .damping = c});
  const Model ma = build_model(a.system), mb = build_model(b.system);
  ForwardOptions o;
  o.t1 = 1;
  o.samples = 21;
  o.integrator = Integrator::rk4;
  o.step = 1e-3;
  const InitialConditions ic{.positions = {}, .velocities = {{"crank.w", 8.0}}};
  const Trajectory ra = forward_dynamics(ma, consistent_state(ma, ic), o);
  const Trajectory rb = forward_dynamics(mb, consistent_state(mb, ic), o);
  const double diff = (ra.q0 - rb.q0).cwiseAbs().maxCoeff();
  std::printf("viscous friction vs torsional damper: max |dq0| = %.3e\n", diff);
  EXPECT_LT(diff, 1e-12);
  EXPECT_NEAR(ra.dissipated[20], rb.dissipated[20], 1e-10);
  EXPECT_GT(rb.dissipated[20], 0.1);
}

// Forward runs of the slider-crank with Coulomb friction in the rail and in the crank pin (its
// reaction from the split at the eliminated joint): the friction's dissipation closes the energy
// balance to integration accuracy; without it the balance would miss the whole dissipation.
TEST(Friction, EnergyBalanceWithCoulombFrictionCloses) {
  Example ex = mechanisms::slider_crank();
  ex.system.add_friction({.name = "rail_friction", .joint = "rail", .mu = 0.2});
  ex.system.add_friction({.name = "pin_friction", .joint = "crank_pin", .mu = 0.2, .radius = 0.01});
  const Model m = build_model(ex.system);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank.w", 12.0}}});
  const Trajectory r = forward_dynamics(m, s, bdf(1.0, 41));
  const double dissipated = r.dissipated[40];
  std::printf("slider-crank with Coulomb friction: dissipated %.6f J, balance error %.3e J\n",
              dissipated, energy_balance_error(r));
  EXPECT_GT(dissipated, 0.5);
  EXPECT_LT(energy_balance_error(r), 1e-6 * dissipated);
}

TEST(Friction, BadDefinitionsAreErrorsNamingTheFriction) {
  auto build = [](FrictionDef f) {
    Example ex = mechanisms::slider_crank();
    ex.system.add_friction(std::move(f));
    return build_model(ex.system);
  };
  auto message = [&](FrictionDef f) {
    try {
      build(std::move(f));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({.name = "f", .joint = "rial", .mu = 0.1}).find("did you mean 'rail'"),
            std::string::npos);
  EXPECT_NE(message({.name = "f", .joint = "crank_pin", .mu = 0.1}).find("pin radius"),
            std::string::npos);
  EXPECT_NE(message({.name = "f", .joint = "rail", .mu = -0.1}).find("mu must be"),
            std::string::npos);
  EXPECT_NE(message({.name = "f", .joint = "rail", .mu = 0.1, .radius = 0.1}).find("radius"),
            std::string::npos);
  EXPECT_NE(message({.name = "f", .joint = "rail", .regularization = 0}).find("regularization"),
            std::string::npos);
}

// The validation formulation has no friction stage: it refuses a model with friction rather than
// return the frictionless answer.
TEST(Friction, InverseLagrangeFormulationRefusesFriction) {
  const Model m = incline(0.5, 0.2, 1e-3, true, Reduction::none);
  const std::vector<Prescribed> p = {{"rail.q", [](Jet t) { return 0.5 + 0.1 * t; }}};
  EXPECT_THROW(inverse_dynamics_lagrange(m, p, {}), Error);
}
