// The lumped transmission (mo2d/transmission.hpp) against the full train: a housing with three
// geared shafts (input -> idler -> output, the output the reference shaft), a motor between the
// housing and the input, an external load torque on the output and gravity; the housing pinned
// to the ground off its centre of mass (it swings), then free in the plane. The lumped model (the
// housing with the shafts' mass spread, two counter-rotating shafts A and B on the shafts' mass
// centre, the motor and load mapped by the cotangent lift) must give every housing signal, the
// pivot's reaction and the output's angle relative to the housing (theta_a / rho_e) to solver
// tolerance.
#include "mo2d/transmission.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

constexpr double r12 = -0.4, r23 = -2.5;  // idler from input, output from idler
constexpr double u_motor = 0.6, tau_load = -0.25, g = 9.81;
const TransmissionHousing kHousing{.mass = 3.0, .com = {0.02, -0.12}, .inertia = 0.04};
const std::vector<TransmissionShaft> kShafts = {
    {.mass = 0.4, .inertia = 0.003, .axis = {-0.07, 0.03}, .ratio = 1 / (r12 * r23)},  // input
    {.mass = 0.9, .inertia = 0.012, .axis = {0.0, 0.05}, .ratio = 1 / r23},            // idler
    {.mass = 1.2, .inertia = 0.05, .axis = {0.08, 0.02}, .ratio = 1.0}};               // output

BodyDef shaft(const std::string& name, Vec2 c, double mass, double inertia) {
  return {.name = name,
          .nodes = {{"C", c}, {"R", c + Vec2(0.01, 0)}},
          .mass = mass,
          .inertia = inertia};
}

BodyDef housing_body(const TransmissionHousing& h, const std::vector<Vec2>& axes) {
  BodyDef b{.name = "case",
            .nodes = {{"O", {0, 0}}, {"X", {0.1, 0}}},
            .mass = h.mass,
            .inertia = h.inertia,
            .com = CenterOfMass::at_point(h.com)};
  for (size_t k = 0; k < axes.size(); ++k) b.nodes.push_back({"H" + std::to_string(k), axes[k]});
  return b;
}

void housing_support(System& s, bool pinned) {
  s.set_gravity({0, -g});
  if (!pinned) return;
  s.add_ground_node("O", {0, 0});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "case.O"});
}

System full(bool pinned) {
  System s("full");
  s.add_body(housing_body(kHousing, {kShafts[0].axis, kShafts[1].axis, kShafts[2].axis}));
  const char* names[] = {"input", "idler", "output"};
  for (int k = 0; k < 3; ++k) {
    s.add_body(shaft(names[k], kShafts[k].axis, kShafts[k].mass, kShafts[k].inertia));
    s.add_revolute({.name = std::string("b_") + names[k],
                    .node_a = "case.H" + std::to_string(k),
                    .node_b = std::string(names[k]) + ".C",
                    .actuated = k == 0});
  }
  s.add_gear(
      {.name = "first", .body = "idler", .driver = "input", .carrier = "case", .ratio = r12});
  s.add_gear(
      {.name = "second", .body = "output", .driver = "idler", .carrier = "case", .ratio = r23});
  s.add_torque({.name = "load", .body = "output", .torque = [](double) { return tau_load; }});
  s.add_coordinate({.name = "rel", .rate = {{"output.w", 1.0}, {"case.w", -1.0}}});
  housing_support(s, pinned);
  return s;
}

System lumped(const LumpedTransmission& L, bool pinned) {
  System s("lumped");
  s.add_body(housing_body(L.housing, {L.axis}));
  s.add_body(shaft("A", L.axis, L.shaft_mass, L.inertia_a));
  s.add_body(shaft("B", L.axis, L.shaft_mass, L.inertia_b));
  s.add_revolute({.name = "b_a", .node_a = "case.H0", .node_b = "A.C", .actuated = true});
  s.add_revolute({.name = "b_b", .node_a = "case.H0", .node_b = "B.C"});
  s.add_gear({.name = "pair", .body = "B", .driver = "A", .carrier = "case", .ratio = -1});
  // the load tau on the output (from outside): tau on the housing and the relative torque
  // rho_out tau / rho_e on A (+ on A, - on the housing)
  const double on_a = kShafts[2].ratio * tau_load / L.ratio;
  s.add_torque({.name = "load_a", .body = "A", .torque = [on_a](double) { return on_a; }});
  s.add_torque(
      {.name = "load_case", .body = "case", .torque = [on_a](double) { return tau_load - on_a; }});
  s.add_coordinate({.name = "rel", .rate = {{"A.w", 1.0}, {"case.w", -1.0}}});
  housing_support(s, pinned);
  return s;
}

void compare(bool pinned) {
  const LumpedTransmission L = lump_transmission(kHousing, kShafts);
  const Model mf = build_model(full(pinned));
  const Model ml = build_model(lumped(L, pinned));
  ASSERT_EQ(mf.dof, ml.dof);
  const double w0 = 0.8, phi_dot0 = 3.0;
  std::vector<std::pair<std::string, double>> vf = {{"case.w", w0}, {"output.w", w0 + phi_dot0}};
  std::vector<std::pair<std::string, double>> vl = {{"case.w", w0},
                                                    {"A.w", w0 + L.ratio * phi_dot0}};
  if (!pinned)
    for (auto* v : {&vf, &vl}) {
      v->push_back({"case.O.vx", 0.3});
      v->push_back({"case.O.vy", 1.5});
    }
  const State sf = consistent_state(mf, {.positions = {}, .velocities = vf});
  const State sl = consistent_state(ml, {.positions = {}, .velocities = vl});
  ForwardOptions o{.t1 = 1.5, .samples = 16, .rtol = 1e-11, .atol = 1e-13};
  o.efforts = {[](double) { return u_motor; }};
  const Trajectory rf = forward_dynamics(mf, sf, o);
  o.efforts = {[&](double) { return L.input_torque(kShafts[0], u_motor); }};
  const Trajectory rl = forward_dynamics(ml, sl, o);
  double worst = 0;
  for (int i = 0; i < rf.time.size(); ++i) {
    for (const char* c : {"case.X.x", "case.X.y"})
      EXPECT_NEAR(rf.q0(i, rf.column(c)), rl.q0(i, rl.column(c)), 1e-8) << c << " " << rf.time[i];
    if (!pinned) {
      for (const char* c : {"case.O.x", "case.O.y"})
        EXPECT_NEAR(rf.q0(i, rf.column(c)), rl.q0(i, rl.column(c)), 1e-8) << c;
    }
    EXPECT_NEAR(rf.q1(i, rf.rate_column("case.w")), rl.q1(i, rl.rate_column("case.w")), 1e-7);
    EXPECT_NEAR(rf.a1(i, rf.rate_column("case.w")), rl.a1(i, rl.rate_column("case.w")), 1e-6);
    const double phi_f = rf.q0(i, rf.column("rel")) - rf.q0(0, rf.column("rel"));
    const double phi_l = (rl.q0(i, rl.column("rel")) - rl.q0(0, rl.column("rel"))) / L.ratio;
    EXPECT_NEAR(phi_f, phi_l, 1e-7) << rf.time[i];
    EXPECT_NEAR(rf.q1(i, rf.rate_column("output.w")),
                rl.q1(i, rl.rate_column("case.w")) + rl.q1(i, rl.rate_column("rel.rate")) / L.ratio,
                1e-7);
    if (pinned) {
      for (const char* c : {"pivot.Fx", "pivot.Fy"})
        EXPECT_NEAR(rf.reactions(i, rf.reaction(c)), rl.reactions(i, rl.reaction(c)), 1e-6) << c;
    }
    worst = std::max(worst, std::abs(phi_f - phi_l));
  }
  EXPECT_GT(std::abs(rf.q0(rf.time.size() - 1, rf.column("rel"))), 1.0);  // the train turns
  ::testing::Test::RecordProperty("max_phi_difference", std::to_string(worst));
}

// The element (add_transmission) at `fidelity`: the same train, the ratios relative to the input.
System element(TransmissionFidelity fidelity) {
  System s("element");
  s.add_body(housing_body(kHousing, {}));
  TransmissionDef d{.name = "gearbox", .housing = "case", .input = "input", .fidelity = fidelity};
  const char* names[] = {"input", "idler", "output"};
  for (int k = 0; k < 3; ++k) {
    TransmissionShaftDef sh{.name = names[k], .shaft = kShafts[k]};
    sh.shaft.ratio = kShafts[k].ratio / kShafts[0].ratio;
    if (k == 2) sh.torque = [](double) { return tau_load; };
    d.shafts.push_back(sh);
  }
  add_transmission(s, d);
  housing_support(s, true);
  return s;
}

// Both fidelities of the element against the train built by hand (full(true)): the housing, the
// pivot's reaction and gearbox.phi (the input's angle relative to the housing, rho_in times the
// output's).
TEST(Transmission, ElementAtEitherFidelityEqualsTheTrainByHand) {
  const double rho_in = kShafts[0].ratio, w0 = 0.8, phi_dot0 = 3.0;
  const Model mh = build_model(full(true));
  ForwardOptions o{.t1 = 1.0, .samples = 11, .rtol = 1e-11, .atol = 1e-13};
  o.efforts = {[](double) { return u_motor; }};
  const Trajectory rh = forward_dynamics(
      mh,
      consistent_state(
          mh, {.positions = {}, .velocities = {{"case.w", w0}, {"output.w", w0 + phi_dot0}}}),
      o);
  for (auto f : {TransmissionFidelity::full, TransmissionFidelity::lumped}) {
    const Model me = build_model(element(f));
    ASSERT_EQ(me.input_labels(), std::vector<std::string>{"gearbox.torque"});
    const Trajectory re = forward_dynamics(
        me,
        consistent_state(me,
                         {.positions = {},
                          .velocities = {{"case.w", w0}, {"gearbox.phi.rate", rho_in * phi_dot0}}}),
        o);
    for (int i = 0; i < rh.time.size(); ++i) {
      for (const char* c : {"case.X.x", "case.X.y"})
        EXPECT_NEAR(rh.q0(i, rh.column(c)), re.q0(i, re.column(c)), 1e-8) << c;
      EXPECT_NEAR(rh.q1(i, rh.rate_column("case.w")), re.q1(i, re.rate_column("case.w")), 1e-7);
      for (const char* c : {"pivot.Fx", "pivot.Fy"})
        EXPECT_NEAR(rh.reactions(i, rh.reaction(c)), re.reactions(i, re.reaction(c)), 1e-6) << c;
      const double rel = rh.q0(i, rh.column("rel")) - rh.q0(0, rh.column("rel"));
      EXPECT_NEAR(re.q0(i, re.column("gearbox.phi")), rho_in * rel, 1e-7) << rh.time[i];
    }
  }
  System bad = element(TransmissionFidelity::lumped);
  TransmissionDef d{.name = "second", .housing = "cse", .input = "x"};
  d.shafts.push_back({.name = "x", .shaft = kShafts[0]});
  EXPECT_THROW(add_transmission(bad, d), Error);  // no such housing
  d.housing = "case";
  d.input = "y";
  EXPECT_THROW(add_transmission(bad, d), Error);  // the input is not a shaft
}

TEST(Transmission, InvariantsAndParameters) {
  const LumpedTransmission L = lump_transmission(kHousing, kShafts);
  double sigma = 0, s = 0, p = 0;
  for (const auto& sh : kShafts) {
    sigma += sh.inertia;
    s += sh.ratio * sh.inertia;
    p += sh.ratio * sh.ratio * sh.inertia;
  }
  EXPECT_NEAR(L.inertia_a + L.inertia_b, sigma, 1e-15);
  EXPECT_NEAR((L.inertia_a - L.inertia_b) * L.ratio, s, 1e-15);
  EXPECT_NEAR((L.inertia_a + L.inertia_b) * L.ratio * L.ratio, p, 1e-15);
  EXPECT_GT(L.inertia_b, 0);
  EXPECT_NEAR(2 * L.shaft_mass, 2.5, 1e-15);
  EXPECT_THROW(lump_transmission(kHousing, {}), Error);
  std::vector<TransmissionShaft> bad = kShafts;
  bad[1].inertia = -1;
  EXPECT_THROW(lump_transmission(kHousing, bad), Error);
}

TEST(Transmission, LumpedEqualsFullOnAPinnedHousing) {
  compare(true);
}

TEST(Transmission, LumpedEqualsFullOnAFreeHousing) {
  compare(false);
}

}  // namespace
