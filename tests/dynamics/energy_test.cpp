// Energy balance of forward runs with every load (issue 10, item 6): the work of point forces,
// torques and inputs, the damper dissipation and the work of time-dependent constraints are
// integrated along the run, so K + V - W + D stays at its initial value to integration accuracy.
// Closed forms: a constant force on a slider (W = F dx), a torque on a rotor (W = tau dtheta), a
// moving constraint (W = dK); the engine of the issue across integrators; and a balance with a
// term left out must show a large error.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

const Integrator kAll[] = {Integrator::rk4,  Integrator::dopri5,    Integrator::erk6,
                           Integrator::erk8, Integrator::cvode_bdf, Integrator::baumgarte};

ForwardOptions run(Integrator integ, double t1, int samples = 41) {
  ForwardOptions o;
  o.t1 = t1;
  o.samples = samples;
  o.integrator = integ;
  o.rtol = 1e-11;
  o.atol = 1e-12;
  o.step = 1e-3;
  return o;
}

// A 2 kg block on a horizontal rail, a constant push fx and a sideways fy (no work: the rail
// holds it), optionally a spring-damper to the ground.
Model block_on_rail(double fx, double fy, double k = 0, double c = 0, Signal f = {}) {
  System s("block");
  s.add_ground_node("L", {0, 0}).add_ground_node("R", {1, 0});
  s.add_body({.name = "block", .nodes = {{"P", {0.8, 0}}}, .mass = 2.0});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.L", .axis_to = "ground.R", .slider = "block.P"});
  if (!f) f = [fx](double) { return fx; };
  s.add_force({.name = "push", .body = "block", .point = {0.8, 0}, .fx = f, .fy = [fy](double) {
                 return fy;
               }});
  if (k > 0 || c > 0)
    s.add_spring({.name = "spring",
                  .body_a = "ground",
                  .point_a = {0, 0},
                  .body_b = "block",
                  .point_b = {0.8, 0},
                  .rest_length = 0.5,
                  .stiffness = k,
                  .damping = c});
  return build_model(s);
}

}  // namespace

// x(t) = x0 + v0 t + F t^2 / (2 m): the load's work is F (x - x0), the kinetic energy gains it.
TEST(EnergyBalance, ConstantForceOnASlider) {
  const double F = 3.0, m = 2.0, v0 = 0.4;
  const Model model = block_on_rail(F, 5.0);
  const State s = consistent_state(model, {.positions = {}, .velocities = {{"rail.v", v0}}});
  for (Integrator integ : kAll) {
    const Trajectory r = forward_dynamics(model, s, run(integ, 1.0));
    const int ix = r.column("block.P.x");
    for (int i = 0; i < r.time.size(); ++i) {
      const double t = r.time[i], dx = v0 * t + F * t * t / (2 * m);
      EXPECT_NEAR(r.q0(i, ix) - 0.8, dx, 1e-9) << to_string(integ) << " t = " << t;
      EXPECT_NEAR(r.load_work[i], F * dx, 1e-9) << to_string(integ) << " t = " << t;
    }
    EXPECT_LE(energy_balance_error(r), 1e-9) << to_string(integ);
    EXPECT_EQ(r.input_work.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(r.constraint_work.cwiseAbs().maxCoeff(), 0.0);
  }
}

// A disc pivoted at its centre (ground point (1, 0.5), away from the origin) under a constant
// torque: theta = theta0 + w0 t + tau t^2 / (2 I), W = tau (theta - theta0) = K - K0.
TEST(EnergyBalance, TorqueOnARotor) {
  const double tau = 0.7, I = 0.05, w0 = -1.5;
  System s("rotor");
  s.add_ground_node("O", {1, 0.5});
  s.add_body(
      {.name = "disc", .nodes = {{"O", {1, 0.5}}, {"E", {1.2, 0.5}}}, .mass = 3.0, .inertia = I});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "disc.O"});
  s.add_coordinate({.name = "disc.angle", .rate = {{"disc.w", 1.0}}, .initial = 0.0});
  s.add_torque({.name = "drive", .body = "disc", .torque = [tau](double) { return tau; }});
  s.set_gravity({0, -9.81});  // no work: the centre of mass is at the pivot
  const Model model = build_model(s);
  const State st = consistent_state(model, {.positions = {}, .velocities = {{"disc.w", w0}}});
  for (Integrator integ : kAll) {
    const Trajectory r = forward_dynamics(model, st, run(integ, 1.0));
    const int ia = r.column("disc.angle");
    for (int i = 0; i < r.time.size(); ++i) {
      const double t = r.time[i], dth = w0 * t + tau * t * t / (2 * I);
      EXPECT_NEAR(r.q0(i, ia), dth, 1e-8) << to_string(integ) << " t = " << t;
      EXPECT_NEAR(r.load_work[i], tau * dth, 1e-8) << to_string(integ) << " t = " << t;
      EXPECT_NEAR(r.kinetic[i] - r.kinetic[0], tau * dth, 1e-8) << to_string(integ);
    }
    EXPECT_LE(energy_balance_error(r), 1e-8) << to_string(integ);
  }
}

// A damped spring with a periodic push: the spring's energy is potential, its damper dissipates,
// the push does work; K + V - W + D stays constant, and each term is really there.
TEST(EnergyBalance, DampedSpringWithAPeriodicForce) {
  const Model model = block_on_rail(0, 0, 50.0, 1.5, [](double t) { return 4 * std::sin(7 * t); });
  const State s = consistent_state(model, {.positions = {}, .velocities = {{"rail.v", 0.4}}});
  for (Integrator integ : kAll) {
    const Trajectory r = forward_dynamics(model, s, run(integ, 3.0, 61));
    const Eigen::Index last = r.time.size() - 1;
    EXPECT_GT(r.dissipated[last], 0.3) << to_string(integ);
    EXPECT_GT(r.load_work.cwiseAbs().maxCoeff(), 0.1) << to_string(integ);
    EXPECT_LE(energy_balance_error(r), 1e-8) << to_string(integ);
  }
}

// A time-dependent constraint drives the block: x = 0.8 + 0.1 sin(3 t). It is the only load, so
// its work is the kinetic energy gained: W = 1/2 m (v^2 - v0^2), v = 0.3 cos(3 t).
TEST(EnergyBalance, WorkOfAMovingConstraint) {
  System s("driven");
  s.add_ground_node("L", {0, 0}).add_ground_node("R", {1, 0});
  s.add_body({.name = "block", .nodes = {{"P", {0.8, 0}}}, .mass = 2.0});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.L", .axis_to = "ground.R", .slider = "block.P"});
  s.add_constraint(PositionConstraintDef{
      .name = "drive", .args = {"block.P.x"}, .psi = [](std::span<const Jet> x, Jet t) {
        return x[0] - 0.8 - 0.1 * sin(3.0 * t);
      }});
  const Model model = build_model(s);
  ASSERT_EQ(model.dof, 0);
  const State st = consistent_state(model, {});
  for (Integrator integ : {Integrator::rk4, Integrator::dopri5, Integrator::cvode_bdf}) {
    const Trajectory r = forward_dynamics(model, st, run(integ, 1.0));
    for (int i = 0; i < r.time.size(); ++i) {
      const double v = 0.3 * std::cos(3 * r.time[i]);
      EXPECT_NEAR(r.constraint_work[i], 0.5 * 2.0 * (v * v - 0.09), 1e-8) << to_string(integ);
    }
    EXPECT_LE(energy_balance_error(r), 1e-8) << to_string(integ);
  }
}

// The engine of the issue: a gas force on the piston, a viscous load at the crank and gravity.
// The balance error was 2.45e3 J (the gas force's work left out); now it is at the integration
// error (measured: see the report), for every integrator.
TEST(EnergyBalance, EngineBalancesForEveryIntegrator) {
  const Scene scene = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/engine.yaml");
  const Model model = build_scene_model(scene);
  const State s0 = initial_state(scene, model);
  for (Integrator integ : kAll) {
    ForwardOptions o = forward_options(scene, model);
    o.integrator = integ;
    o.t1 = 0.2;  // five revolutions, two firings
    o.samples = 401;
    o.step = 2e-5;  // rk4, baumgarte: 157 rad/s and a pressure pulse of a few ms
    // BDF's global error at the scene's rtol 1e-8 is of the bound's own order (measured: 4.3e-4 J
    // with the exact Newton matrix, 3.5e-4 J with difference quotients, bound 4.1e-4 J): the
    // bound is checked at a tenth of that tolerance, where the error is far below it
    if (integ == Integrator::cvode_bdf) o.rtol = 1e-9;
    const Trajectory r = forward_dynamics(model, s0, o);
    std::printf("%s: balance error %.3g J\n", to_string(integ), energy_balance_error(r));

    const double scale = r.load_work.cwiseAbs().maxCoeff() + r.kinetic.maxCoeff();
    EXPECT_GT(r.load_work.cwiseAbs().maxCoeff(), 100.0) << to_string(integ);  // the gas force
    EXPECT_GT(r.dissipated[r.time.size() - 1], 1.0) << to_string(integ);      // the load
    EXPECT_LE(energy_balance_error(r), 1e-7 * scale) << to_string(integ);
  }
}

// The balance has teeth: the same run with one term left out shows an error of that term's size.
TEST(EnergyBalance, AMissingTermGivesALargeError) {
  const Scene scene = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/engine.yaml");
  const Model model = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, model);
  o.t1 = 0.2;
  o.samples = 101;
  Trajectory r = forward_dynamics(model, initial_state(scene, model), o);
  const double ok = energy_balance_error(r), work = r.load_work.cwiseAbs().maxCoeff();
  EXPECT_LE(ok, 1e-6 * work);
  Trajectory no_load = r;
  no_load.load_work.setZero();
  EXPECT_GE(energy_balance_error(no_load), 0.9 * work);
  Trajectory no_damper = r;
  no_damper.dissipated.setZero();
  EXPECT_GE(energy_balance_error(no_damper), 0.9 * r.dissipated[r.time.size() - 1]);
  Trajectory wrong_potential = r;
  wrong_potential.potential.array() += 1e-3 * r.time.array();  // a potential that drifts 1 mJ/s
  EXPECT_GE(energy_balance_error(wrong_potential), 0.9 * 1e-3 * 0.2 - ok);
}
