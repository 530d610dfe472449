// Loads that depend on the state (mo2d/law.hpp), against independent references: a law written as
// the built-in linear element gives the same run to round-off (a torque -k angle - c w is the
// torsional spring-damper, a tension k extension + c rate the linear spring); unilateral springs
// (a rope, a bump stop) against the free flight and the elastic bounce they must give; the
// quantities a law reads against hand computations; energy balances with every law counted; the
// errors (unknown label, a law beside a stiffness, a non-finite value naming its arguments).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

// A 1 m, 2 kg bar pivoted at O, gravity: the base of the equivalence tests.
System bar_pendulum() {
  System s("bar");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"E", {1, 0}}},
              .mass = 2.0,
              .inertia = 2.0 / 12,
              .com = CenterOfMass::between("O", "E", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  s.set_gravity({0, -9.81});
  return s;
}

ForwardOptions rk4(double t1, int samples = 101) {
  ForwardOptions o;
  o.t1 = t1;
  o.samples = samples;
  o.integrator = Integrator::rk4;
  o.step = 1e-3;
  return o;
}

Trajectory swing(const System& s, const ForwardOptions& o, double w0 = 2.0) {
  const Model m = build_model(s);
  return forward_dynamics(m, consistent_state(m, {.positions = {}, .velocities = {{"bar.w", w0}}}),
                          o);
}

double max_abs_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace

// -k angle - c w as a torque law is the torsional spring-damper: the same accelerations at every
// evaluation, so a fixed-step run gives the same states to the last bit; only the bookkeeping of
// the energy differs (potential and dissipation for the element, load work for the law).
TEST(Laws, TorqueLawEqualsTheTorsionalSpringDamper) {
  const double k = 3.0, c = 0.4;
  System a = bar_pendulum();
  a.add_torsional_spring({.name = "d", .joint = "pivot", .stiffness = k, .damping = c});
  System b = bar_pendulum();
  b.add_torque({.name = "d",
                .body = "bar",
                .torque = Law({"pivot.angle", "bar.w"},
                              [=](std::span<const Jet> x, Jet) { return -k * x[0] - c * x[1]; })});
  const Trajectory ra = swing(a, rk4(3.0)), rb = swing(b, rk4(3.0));
  EXPECT_EQ(max_abs_diff(ra.q0, rb.q0), 0.0);
  EXPECT_EQ(max_abs_diff(ra.q1, rb.q1), 0.0);
  EXPECT_LE(energy_balance_error(ra), 1e-8);
  EXPECT_LE(energy_balance_error(rb), 1e-8);
  // the law's work is the element's elastic energy lost and its dissipation
  const int n = static_cast<int>(ra.time.size()) - 1;
  const double elastic_a = ra.potential[n] - ra.potential[0] - (rb.potential[n] - rb.potential[0]);
  EXPECT_NEAR(rb.load_work[n], -elastic_a - ra.dissipated[n], 1e-8);
  EXPECT_GT(ra.dissipated[n], 0.1);  // the damper did work: the comparison is not vacuous
}

// k extension + c rate as a tension law is the linear spring-damper.
TEST(Laws, TensionLawEqualsTheLinearSpring) {
  const double k = 20.0, c = 0.5;
  SpringDef lin{.name = "s",
                .body_a = "ground",
                .point_a = {1, 1},
                .body_b = "bar",
                .point_b = {1, 0},
                .rest_length = 0.8,
                .stiffness = k,
                .damping = c};
  SpringDef law = lin;
  law.stiffness = law.damping = 0;
  law.tension =
      Law({"extension", "rate"}, [=](std::span<const Jet> x, Jet) { return k * x[0] + c * x[1]; });
  System a = bar_pendulum(), b = bar_pendulum();
  a.add_spring(lin);
  b.add_spring(law);
  const Trajectory ra = swing(a, rk4(2.0)), rb = swing(b, rk4(2.0));
  EXPECT_EQ(max_abs_diff(ra.q0, rb.q0), 0.0);
  EXPECT_EQ(max_abs_diff(ra.q1, rb.q1), 0.0);
  EXPECT_LE(energy_balance_error(rb), 1e-8);
  EXPECT_LT(rb.load_work[rb.time.size() - 1], -0.1);  // the law did (negative) work
}

// A point mass on a rope (a tension-only spring from the ground point O), thrown so that the rope
// goes slack: while slack the bob is in free flight (acceleration exactly -g), and the energy
// balance closes across the slack and taut phases.
TEST(Laws, TensionOnlyRopeGoesSlackIntoFreeFlight) {
  System s("rope");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bob", .nodes = {{"P", {0, -1}}}, .mass = 1.0});
  s.set_gravity({0, -9.81});
  s.add_spring({.name = "rope",
                .body_a = "ground",
                .point_a = {0, 0},
                .body_b = "bob",
                .point_b = {0, -1},
                .rest_length = 1.0,
                .stiffness = 1e4,
                .damping = 2.0,
                .acts = SpringActs::tension_only});
  const Model m = build_model(s);
  const State s0 =
      consistent_state(m, {.positions = {}, .velocities = {{"bob.P.vx", 1.0}, {"bob.P.vy", 3.0}}});
  ForwardOptions o;
  o.t1 = 1.0;
  o.samples = 201;
  o.integrator = Integrator::cvode_bdf;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  const Trajectory r = forward_dynamics(m, s0, o);
  int slack = 0, taut = 0;
  const int ix = r.column("bob.P.x"), iy = r.column("bob.P.y");
  for (int k = 0; k < r.time.size(); ++k) {
    const double l = std::hypot(r.q0(k, ix), r.q0(k, iy));
    if (l < 1.0 - 1e-6) {
      ++slack;
      EXPECT_EQ(r.a1(k, r.rate_column("bob.P.vx")), 0.0) << "t = " << r.time[k];
      EXPECT_NEAR(r.a1(k, r.rate_column("bob.P.vy")), -9.81, 1e-12) << "t = " << r.time[k];
    } else if (l > 1.0 + 1e-6) {
      ++taut;
    }
  }
  EXPECT_GT(slack, 10);
  EXPECT_GT(taut, 0);  // it falls back onto the rope
  const double scale = 0.5 * (1 + 9) + 9.81 * 1;
  EXPECT_LE(energy_balance_error(r), 1e-8 * scale);  // measured 1.2e-8 J of ~15 J
}

// A block on a horizontal rail runs into a bump stop (a compression-only spring of rest length
// 0.3 m from the ground point O): no force before contact, and without damping it leaves at the
// speed it came in (an elastic bounce); with damping it leaves slower, by the energy the balance
// says the damper took.
TEST(Laws, BumpStopBouncesElastically) {
  for (double c : {0.0, 4.0}) {
    System s("stop");
    s.add_ground_node("O", {0, 0}).add_ground_node("R", {1, 0});
    s.add_body({.name = "block", .nodes = {{"P", {0.8, 0}}}, .mass = 2.0});
    s.add_prismatic(
        {.name = "rail", .axis_from = "ground.O", .axis_to = "ground.R", .slider = "block.P"});
    s.add_spring({.name = "stop",
                  .body_a = "ground",
                  .point_a = {0, 0},
                  .body_b = "block",
                  .point_b = {0.8, 0},
                  .rest_length = 0.3,
                  .stiffness = 5e3,
                  .damping = c,
                  .acts = SpringActs::compression_only});
    const Model m = build_model(s);
    ForwardOptions o;
    o.t1 = 1.0;
    o.samples = 101;
    o.integrator = Integrator::cvode_bdf;
    // The contact puts a kink (no damping) or a jump (damping) into the force: the balance error
    // follows the tolerance (measured, no damping: 1.3e-7, 1.2e-8, 2.8e-9 J for rtol 1e-9, 1e-10,
    // 1e-11). CVODE, because its error test covers the energy terms; dopri5's leaves them out,
    // and a step across the damper's jump then puts ~1e-4 J into the dissipated energy.
    o.rtol = 1e-11;
    o.atol = 1e-12;
    const Trajectory r = forward_dynamics(
        m, consistent_state(m, {.positions = {}, .velocities = {{"rail.v", -1}}}), o);
    const int iq = r.column("rail.q"), iv = r.rate_column("rail.v");
    EXPECT_EQ(r.a1(10, iv), 0.0);  // t = 0.1: x = 0.7, not in contact yet
    const int end = static_cast<int>(r.time.size()) - 1;
    EXPECT_GT(r.q0(end, iq), 0.3);  // it has left the stop
    if (c == 0) {
      EXPECT_NEAR(r.q1(end, iv), 1.0, 1e-8);
    } else {
      EXPECT_LT(r.q1(end, iv), 0.99);
      const double lost = 0.5 * 2.0 * (1.0 - r.q1(end, iv) * r.q1(end, iv));
      EXPECT_NEAR(r.dissipated[end], lost, 1e-8);
    }
    EXPECT_LE(energy_balance_error(r), 1e-8);
  }
}

// The quantities a law may read, against hand computations at an assembled configuration.
TEST(Laws, QuantitiesMatchHandComputations) {
  System s = bar_pendulum();
  s.add_body({.name = "arm",
              .nodes = {{"A", {1, 0}}, {"B", {1, 1}}},
              .mass = 1.0,
              .inertia = 0.1,
              .com = CenterOfMass::between("A", "B", 0.25)});
  s.add_revolute({.name = "elbow", .node_a = "bar.E", .node_b = "arm.A"});
  s.add_spring({.name = "s",
                .body_a = "ground",
                .point_a = {2, 0},
                .body_b = "arm",
                .point_b = {1, 1},
                .rest_length = 0.5,
                .stiffness = 1});
  s.add_point({.name = "tip", .body = "arm", .point = {1.5, 1}});
  const Model m = build_model(s);
  // a configuration: bar at angle a, arm at absolute angle b; rates wa, wb
  const double a = 0.3, b = 1.9, wa = 0.7, wb = -1.1;
  Eigen::VectorXd q0 = m.q0, q1 = Eigen::VectorXd::Zero(m.n1);
  const Vec2 E(std::cos(a), std::sin(a)), B = E + Vec2(std::cos(b), std::sin(b));
  q0[m.coordinate("bar.E.x")] = E.x();
  q0[m.coordinate("bar.E.y")] = E.y();
  q0[m.coordinate("arm.B.x")] = B.x();
  q0[m.coordinate("arm.B.y")] = B.y();
  const Vec2 vE = wa * Vec2(-E.y(), E.x()), vB = vE + wb * Vec2(-std::sin(b), std::cos(b));
  q1[m.rate("bar.E.vx")] = vE.x();
  q1[m.rate("bar.E.vy")] = vE.y();
  q1[m.rate("arm.B.vx")] = vB.x();
  q1[m.rate("arm.B.vy")] = vB.y();
  q1[m.rate("bar.w")] = wa;
  q1[m.rate("arm.w")] = wb;
  auto value = [&](const std::string& label) {
    const CompiledLaw law = compile_law(
        m, Law({label}, [](std::span<const Jet> x, Jet) { return x[0]; }), "test", "test");
    return law_value(m, law, q0, q1, 0.0, "test", "test");
  };
  const double b0 = std::numbers::pi / 2;  // the arm's initial absolute angle
  EXPECT_NEAR(value("bar.theta"), a, 1e-15);
  EXPECT_NEAR(value("arm.theta"), b, 1e-15);
  EXPECT_NEAR(value("elbow.angle"), b - a - b0, 1e-15);
  EXPECT_NEAR(value("elbow.rate"), wb - wa, 1e-15);
  const Vec2 com = E + 0.25 * (B - E), vcom = vE + 0.25 * (vB - vE);
  EXPECT_NEAR(value("arm.com.x"), com.x(), 1e-15);
  EXPECT_NEAR(value("arm.com.vy"), vcom.y(), 1e-15);
  const Vec2 d = B - Vec2(2, 0);
  EXPECT_NEAR(value("s.length"), d.norm(), 1e-15);
  EXPECT_NEAR(value("s.extension"), d.norm() - 0.5, 1e-15);
  EXPECT_NEAR(value("s.rate"), d.dot(vB) / d.norm(), 1e-15);
  // tip: half a metre along the arm's line from B, perpendicular... in the initial frame it is
  // (1.5, 1) = A + (0.5, 1) = A + 1 * (B - A) + 0.5 * z x ... given through the first two nodes
  const Vec2 u(std::cos(b), std::sin(b)), nrm(-u.y(), u.x());
  const Vec2 tip = E + 1.0 * u - 0.5 * nrm;  // (0.5, 1) from A: 1 along the arm, 0.5 to its right
  EXPECT_NEAR(value("tip.x"), tip.x(), 1e-15);
  EXPECT_NEAR(value("tip.y"), tip.y(), 1e-15);
  EXPECT_NEAR(value("ground.O.y"), 0.0, 0);
  EXPECT_NEAR(value("bar.O.vx"), 0.0, 0);  // joined to the ground: a fixed node
}

// In inverse dynamics the state is known before the efforts: a torque -c w read from the state is
// the time function -c omega along the prescribed motion omega t.
TEST(Laws, InverseDynamicsWithAStateLawEqualsItsTimeFunction) {
  auto ex = mechanisms::slider_crank();
  const double c = 0.05, omega = 4 * std::numbers::pi;
  System a = ex.system, b = ex.system;
  a.add_torque({.name = "drag", .body = "crank", .torque = Law({"crank.w"}, [=](auto x, Jet) {
                                                   return -c * x[0];
                                                 })});
  b.add_torque({.name = "drag", .body = "crank", .torque = [=](double) { return -c * omega; }});
  std::vector<Prescribed> motion = {{"crank.angle", [=](Jet t) { return omega * t; }}};
  const InverseOptions o{.t0 = 0, .t1 = 0.5, .samples = 51};
  const Trajectory ra = inverse_dynamics(build_model(a), motion, o);
  const Trajectory rb = inverse_dynamics(build_model(b), motion, o);
  EXPECT_LE(max_abs_diff(ra.efforts, rb.efforts), 1e-12);
  EXPECT_LE(max_abs_diff(ra.reactions, rb.reactions), 1e-10);
}

// A law in a subsystem reads the instance's own quantities: two instances of one swinging bar,
// each damped by a law on its own bar.w, run as the root-level bar does.
TEST(Laws, LabelsAreLocalToTheSubsystem) {
  System sub = bar_pendulum();
  sub.set_gravity({0, 0});
  sub.add_torque({.name = "drag", .body = "bar", .torque = Law({"bar.w"}, [](auto x, Jet) {
                                                   return -0.3 * x[0];
                                                 })});
  System root("two");
  root.set_gravity({0, -9.81});
  root.add_instance("left", sub, {{-2, 0}, 0});
  root.add_instance("right", sub, {{2, 0}, 0});
  const Model m = build_model(root);
  const State s0 = consistent_state(
      m, {.positions = {}, .velocities = {{"left.bar.w", 2.0}, {"right.bar.w", 2.0}}});
  const Trajectory r = forward_dynamics(m, s0, rk4(1.0, 11));
  System one = bar_pendulum();
  one.add_torque({.name = "drag", .body = "bar", .torque = Law({"bar.w"}, [](auto x, Jet) {
                                                   return -0.3 * x[0];
                                                 })});
  const Trajectory ro = swing(one, rk4(1.0, 11));
  EXPECT_NEAR(r.q1(10, r.rate_column("left.bar.w")), ro.q1(10, ro.rate_column("bar.w")), 1e-12);
  EXPECT_NEAR(r.q1(10, r.rate_column("right.bar.w")), ro.q1(10, ro.rate_column("bar.w")), 1e-12);
}

TEST(Laws, Errors) {
  {  // an unknown label, with the closest one
    System s = bar_pendulum();
    s.add_torque({.name = "drag", .body = "bar", .torque = Law({"bar.ww"}, [](auto x, Jet) {
                                                   return x[0];
                                                 })});
    try {
      (void)build_model(s);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("torque 'drag': unknown quantity 'bar.ww'"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("did you mean 'bar.w'"), std::string::npos) << e.what();
      EXPECT_EQ(e.element(), "drag");
    }
  }
  {  // a tension law beside a stiffness
    System s = bar_pendulum();
    s.add_spring({.name = "s",
                  .body_a = "ground",
                  .point_a = {1, 1},
                  .body_b = "bar",
                  .point_b = {1, 0},
                  .stiffness = 3,
                  .tension = Law({"extension"}, [](auto x, Jet) { return x[0]; })});
    EXPECT_THROW((void)build_model(s), Error);
  }
  {  // a law that turns infinite: an Error with the time and the values of its arguments
    System p = bar_pendulum();
    p.add_torque({.name = "wall", .body = "bar", .torque = Law({"bar.theta"}, [](auto x, Jet) {
                                                   return 1.0 / x[0];
                                                 })});
    try {
      (void)swing(p, rk4(1.0), 0.0);  // starts at its pole
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("torque 'wall' is not finite at t = 0"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("bar.theta = 0"), std::string::npos) << e.what();
    }
  }
}

// The same laws from a scene file: expressions of the state, a bump stop, an unknown label at its
// file:line:column.
TEST(Laws, SceneExpressionsOfTheState) {
  const std::string text = R"yaml(
name: swing
parameters: {k: 3.0, c: 0.4}
ground: {O: [0, 0]}
bodies:
  bar: {nodes: {O: [0, 0], E: [1, 0]}, mass: 2, inertia: 2 / 12, com: {between: [O, E], gamma: 0.5}}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: bar.O}
loads:
  gravity: [0, -9.81]
  torques: {d: {body: bar, torque: -k * pivot.angle - c * bar.w}}
initial: {velocities: {bar.w: 2}}
run: {solve: forward, duration: 3, samples: 101, integrator: rk4, step: 1e-3}
)yaml";
  const Scene scene = parse_scene(text, "swing.yaml");
  const Model m = build_scene_model(scene);
  const Trajectory r = forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
  System a = bar_pendulum();
  a.add_torsional_spring({.name = "d", .joint = "pivot", .stiffness = 3.0, .damping = 0.4});
  const Trajectory ra = swing(a, rk4(3.0));
  EXPECT_LE(max_abs_diff(r.q0, ra.q0), 1e-14);

  std::string bad = text;
  bad.replace(bad.find("c * bar.w"), 9, "c * bar.ww");
  try {
    (void)build_scene_model(parse_scene(bad, "swing.yaml"));
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("swing.yaml:11:59:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'bar.w'"), std::string::npos) << e.what();
  }
}
