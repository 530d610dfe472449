// Chain and belt drives (src/dynamics/chain.hpp) against independent computations:
//  - the spans' material lengths against the belt path sampled as the convex hull of two
//    sampled pitch circles (its bridging edges are the spans, the marks' arcs measured from the
//    hull's tangent points), at configurations where the centre line has turned and stretched;
//  - the energy balance of a run where the rear sprocket rides on a swinging arm: conserved with
//    the exact span length, not with Gamba's printed extension (no wrap term: its forces have no
//    potential);
//  - the stiff chain against the rigid drive it tends to (a gear pair of ratio r_a / r_b on the
//    same flywheels, viscous bearings): the tension's error falls as 1/k;
//  - the sparse engine against the dense one; bad input named.
// Runs have a 30 s budget: a wrong force (a planted mutation that feeds energy in) fails instead
// of grinding on.
#include "dynamics/chain.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "mo2d/crosscheck.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/fidelity.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

constexpr double ra = 0.04, rb = 0.1;  // drive and wheel sprockets (m)

BodyDef disc(const std::string& name, Vec2 c, double mass, double inertia) {
  return {.name = name,
          .nodes = {{"C", c}, {"R", c + Vec2(0.05, 0.01)}},
          .mass = mass,
          .inertia = inertia};
}

// A drive sprocket on a ground axis at the origin, a wheel sprocket at the end of a swing arm
// pivoted at P (a torsional spring holds it near level), the chain between them.
System swing_arm_drive(double k, ChainFidelity fidelity, double damping = 0) {
  System s("swing_arm");
  s.add_ground_node("O", {0, 0});
  s.add_ground_node("P", {0.08, -0.03});
  s.add_body(disc("drive", {0, 0}, 0.5, 2e-3));
  s.add_body({.name = "arm",
              .nodes = {{"P", {0.08, -0.03}}, {"E", {0.55, 0.02}}},
              .mass = 3,
              .inertia = 0.08});
  s.add_body(disc("wheel", {0.55, 0.02}, 8, 0.3));
  s.add_revolute({.name = "p_drive", .node_a = "ground.O", .node_b = "drive.C"});
  s.add_revolute({.name = "pivot", .node_a = "ground.P", .node_b = "arm.P"});
  s.add_revolute({.name = "axle", .node_a = "arm.E", .node_b = "wheel.C"});
  s.add_torsional_spring({.name = "suspension", .joint = "pivot", .stiffness = 400});
  s.add_chain({.name = "chain",
               .body_a = "drive",
               .centre_a = {0, 0},
               .radius_a = ra,
               .body_b = "wheel",
               .centre_b = {0.55, 0.02},
               .radius_b = rb,
               .stiffness = k,
               .damping = damping,
               .fidelity = fidelity});
  s.set_gravity({0, -9.81});
  return s;
}

// ---- the span length against the sampled belt path ----------------------------------------------

struct P2 {
  double x, y;
  int circle;  // 0: a, 1: b
};
double cross(const P2& o, const P2& a, const P2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}
// Andrew's monotone chain: the hull counter-clockwise.
std::vector<P2> hull(std::vector<P2> p) {
  std::sort(p.begin(), p.end(),
            [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<P2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// The upper and lower spans' material lengths from the sampled path, up to constants: the span
// (a hull edge from circle a to b, or b to a) plus the arcs from the tangent points to the marks
// at the sprockets' angles (angles unwrapped near `near`).
struct Sampled {
  double upper, lower;
};
Sampled sampled_spans(Vec2 ca, Vec2 cb, double th_a, double th_b) {
  const int n = 40000;
  std::vector<P2> pts;
  for (int i = 0; i < n; ++i) {
    const double f = 2 * std::numbers::pi * i / n;
    pts.push_back({ca.x() + ra * std::cos(f), ca.y() + ra * std::sin(f), 0});
    pts.push_back({cb.x() + rb * std::cos(f), cb.y() + rb * std::sin(f), 1});
  }
  const std::vector<P2> h = hull(pts);
  Sampled s{0, 0};
  for (size_t i = 0; i < h.size(); ++i) {
    const P2 &p = h[i], &q = h[(i + 1) % h.size()];
    if (p.circle == q.circle) continue;
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    // counter-clockwise: the hull goes b -> a along the upper span (left of a -> b)
    const P2& on_a = p.circle == 0 ? p : q;
    const P2& on_b = p.circle == 0 ? q : p;
    const double fa = std::atan2(on_a.y - ca.y(), on_a.x - ca.x());
    const double fb = std::atan2(on_b.y - cb.y(), on_b.x - cb.x());
    if (p.circle == 1) {  // upper: arcs r_a (theta_a - phi) and r_b (phi - theta_b), phi near pi/2
      s.upper = len + ra * (th_a - fa) + rb * (fb - th_b);
    } else {  // lower: arcs r_a (phi - theta_a) and r_b (theta_b - phi), phi near -pi/2
      s.lower = len + ra * (fa - th_a) + rb * (th_b - fb);
    }
  }
  return s;
}

TEST(Chain, SpanLengthsEqualTheSampledBeltPath) {
  const Model m = build_model(swing_arm_drive(1e4, ChainFidelity::bilateral));
  const ChainLoad& c = m.chains.at(0);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.n1);
  auto lengths = [&](Vec2 ca, Vec2 cb, double th_a, double th_b) {
    const detail::ChainInput<double> in{ca.x(), ca.y(), cb.x(), cb.y(), 0, 0,
                                        0,      0,      th_a,   th_b,   0, 0};
    const detail::Spans<double> sp = detail::chain_spans(c, in, 0.0);
    return Sampled{sp.upper.length, sp.lower.length};
  };
  const Vec2 ca0(0, 0), cb0(0.55, 0.02);
  const Sampled e0 = lengths(ca0, cb0, 0.1, -0.2), s0 = sampled_spans(ca0, cb0, 0.1, -0.2);
  // moved: the centre line turned by 0.35 rad and longer by 6 cm, the sprockets turned
  struct Case {
    Vec2 ca, cb;
    double th_a, th_b;
  };
  const double b = 0.35 + std::atan2(0.02, 0.55);
  for (const Case& k :
       {Case{{0, 0}, {0.61 * std::cos(b), 0.61 * std::sin(b)}, 1.3, 0.4},
        Case{{0.02, 0.01}, {0.5, -0.15}, -2.0, 0.7}, Case{{-0.1, 0.05}, {0.3, 0.2}, 7.0, 2.5}}) {
    const Sampled e = lengths(k.ca, k.cb, k.th_a, k.th_b);
    const Sampled s = sampled_spans(k.ca, k.cb, k.th_a, k.th_b);
    EXPECT_NEAR(e.upper - e0.upper, s.upper - s0.upper, 1e-7);
    EXPECT_NEAR(e.lower - e0.lower, s.lower - s0.lower, 1e-7);
    std::printf("span length changes: upper %.9f (sampled %.9f), lower %.9f (sampled %.9f) m\n",
                e.upper - e0.upper, s.upper - s0.upper, e.lower - e0.lower, s.lower - s0.lower);
  }
}

// ---- energy -------------------------------------------------------------------------------------

// The arm swings (the centre distance and the centre line's direction change) while both spans
// take turns pulling: no damping, so K + V is conserved to the integration error.
Trajectory swinging_run(const Model& m) {
  const State s0 = consistent_state(
      m, {.positions = {}, .velocities = {{"drive.w", 20.0}, {"arm.w", 1.5}, {"wheel.w", 3.0}}});
  return forward_dynamics(
      m, s0, {.t1 = 1, .samples = 101, .rtol = 1e-10, .atol = 1e-12, .max_seconds = 30});
}

double swing_of_centre_line(const Model& m, const Trajectory& r) {
  double lo = 1e9, hi = -1e9;
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    const double y = r.q0(i, m.coordinate("arm.E.y")), x = r.q0(i, m.coordinate("arm.E.x"));
    lo = std::min(lo, std::atan2(y, x));
    hi = std::max(hi, std::atan2(y, x));
  }
  return hi - lo;
}

TEST(Chain, EnergyConservedWithTheExactSpanLengthNotWithThePrintedOne) {
  for (ChainFidelity f : {ChainFidelity::bilateral, ChainFidelity::unilateral}) {
    const Model m = build_model(swing_arm_drive(2e4, f));
    const Trajectory r = swinging_run(m);
    Model printed = m;  // Gamba's printed extension: no wrap term
    printed.chains[0].printed_extension = true;
    detail::init_chain(printed, printed.chains[0]);
    const Trajectory rp = swinging_run(printed);
    double tmax = 0, tmin = 0;
    for (Eigen::Index i = 0; i < r.time.size(); ++i) {
      const ChainValue v =
          chain_value(m, m.chains[0], r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
      tmax = std::max({tmax, v.upper_tension, v.lower_tension});
      tmin = std::min({tmin, v.upper_tension, v.lower_tension});
    }
    const double e = energy_balance_error(r), ep = energy_balance_error(rp);
    std::printf(
        "%s: centre line swings %.3f rad, tensions %.1f .. %.1f N; energy balance error %.2e J "
        "(exact length), %.2e J (printed extension)\n",
        f == ChainFidelity::bilateral ? "bilateral" : "unilateral", swing_of_centre_line(m, r),
        tmin, tmax, e, ep);
    EXPECT_GT(swing_of_centre_line(m, r), 0.05);  // the centre line really turns
    EXPECT_GT(tmax, 50);                          // the chain really pulls
    EXPECT_LT(e, 1e-6);
    EXPECT_GT(ep, 1000 * e);
  }
}

// The sparse engine evaluates the same element (body_applied): equal runs (bilateral with
// damping: smooth, so that dopri5 keeps its order; a damped unilateral span's tension jumps by
// c de/dt where it engages).
TEST(Chain, SparseEngineAgreesWithDense) {
  const Model m = build_model(swing_arm_drive(2e4, ChainFidelity::bilateral, 5));
  const State s0 = consistent_state(
      m, {.positions = {}, .velocities = {{"drive.w", 20.0}, {"arm.w", 1.5}, {"wheel.w", 3.0}}});
  ForwardOptions o{.t1 = 0.2,
                   .samples = 5,
                   .integrator = Integrator::dopri5,
                   .rtol = 1e-10,
                   .atol = 1e-12,
                   .max_seconds = 30};
  o.linear_algebra = LinearAlgebra::dense;
  const Trajectory d = forward_dynamics(m, s0, o);
  o.linear_algebra = LinearAlgebra::sparse;
  const Trajectory s = forward_dynamics(m, s0, o);
  EXPECT_LT((d.q1 - s.q1).lpNorm<Eigen::Infinity>(), 1e-6);
  EXPECT_LT(energy_balance_error(d), 1e-6);
}

// ---- the stiff limit ----------------------------------------------------------------------------

// Two flywheels on ground axes, the drive torque ramped smoothly, a viscous bearing: with a chain
// of stiffness k, or rigidly geared (omega_b = (r_a / r_b) omega_a, the inextensible chain with
// its upper span taut), whose mesh torque on b is r_b T.
constexpr double Ia = 0.01, Ib = 0.4, cb_visc = 0.05, Tdrive = 2.0;
// The chain's damper (N s/m, the same at every k) makes the fast mode's transient die out at the
// rate c / (2 m_eff) ~ 18/s (m_eff = 1 / (r_a^2 / I_a + r_b^2 / I_b) = 5.4 kg); what remains is
// the quasi-steady stretch T / k, whose rate changes the motion by O(1/k).
constexpr double c_chain = 200;
System flywheels(double k) {
  System s("flywheels");
  s.add_ground_node("A", {0, 0});
  s.add_ground_node("B", {0.5, 0});
  s.add_body(disc("a", {0, 0}, 1, Ia));
  s.add_body(disc("b", {0.5, 0}, 1, Ib));
  s.add_revolute({.name = "pa", .node_a = "ground.A", .node_b = "a.C"});
  s.add_revolute({.name = "pb", .node_a = "ground.B", .node_b = "b.C"});
  s.add_torsional_spring({.name = "bearing", .joint = "pb", .damping = cb_visc});
  s.add_torque({.name = "drive", .body = "a", .torque = [](double t) {
                  const double x = std::min(t / 0.5, 1.0);
                  return Tdrive * x * x * x * (10 - 15 * x + 6 * x * x);  // C2 ramp
                }});
  if (k > 0)
    s.add_chain({.name = "chain",
                 .body_a = "a",
                 .centre_a = {0, 0},
                 .radius_a = ra,
                 .body_b = "b",
                 .centre_b = {0.5, 0},
                 .radius_b = rb,
                 .stiffness = k,
                 .damping = c_chain});
  else
    s.add_gear({.name = "mesh", .body = "b", .driver = "a", .ratio = ra / rb});
  return s;
}

TEST(Chain, StiffChainTendsToTheRigidDriveAsOneOverK) {
  const ForwardOptions o{.t1 = 1, .samples = 11, .rtol = 1e-12, .atol = 1e-14, .max_seconds = 30};
  const Model rigid = build_model(flywheels(0));
  const Trajectory rr = forward_dynamics(
      rigid, consistent_state(rigid, {.positions = {}, .velocities = {{"a.w", 0.0}}}), o);
  const double T_rigid = rr.reactions(10, rr.reaction("mesh.torque")) / rb;
  std::vector<double> err;
  for (double k : {1e4, 1e5, 1e6}) {
    const Model m = build_model(flywheels(k));
    const Trajectory r = forward_dynamics(
        m, consistent_state(m, {.positions = {}, .velocities = {{"a.w", 0.0}, {"b.w", 0.0}}}), o);
    const ChainValue v =
        chain_value(m, m.chains[0], r.q0.row(10).transpose(), r.q1.row(10).transpose(), 1.0);
    err.push_back(v.upper_tension - T_rigid);
    std::printf("k = %.0e N/m: upper tension %.9f N, rigid %.9f N, error %.3e N; lower %.3g N\n", k,
                v.upper_tension, T_rigid, err.back(), v.lower_tension);
    EXPECT_EQ(v.lower_tension, 0);  // slack
  }
  EXPECT_GT(T_rigid, 10);
  EXPECT_LT(std::abs(err[2]), 1e-6 * T_rigid);
  // 1/k: a factor 10 per decade, from the same side (at rtol 1e-11 the error of the positions,
  // ~1e-11 m, times k = 1e6 would already be 1e-5 N: the reason for rtol 1e-12)
  for (size_t i = 1; i < err.size(); ++i) {
    EXPECT_GT(err[i - 1] / err[i], 6) << i;
    EXPECT_LT(err[i - 1] / err[i], 16) << i;
  }
}

// ---- bad input ----------------------------------------------------------------------------------

void expect_error(const System& s, const std::string& needle) {
  try {
    build_model(s);
    ADD_FAILURE() << "no error, expected one containing '" << needle << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Chain, BadInputIsNamed) {
  auto with = [](auto edit) {
    System s = swing_arm_drive(1e4, ChainFidelity::unilateral);
    System t("swing_arm");
    ChainDef c = s.chains()[0];
    edit(c);
    // rebuild without the chain, then add the edited one
    for (const auto& n : s.ground()) t.add_ground_node(n.name, n.position);
    for (const auto& b : s.bodies()) t.add_body(b);
    for (const auto& j : s.revolutes()) t.add_revolute(j);
    t.add_chain(c);
    return t;
  };
  expect_error(with([](ChainDef& c) { c.radius_a = 0; }), "chain 'chain': radius_a must be");
  expect_error(with([](ChainDef& c) { c.radius_b = -0.1; }), "chain 'chain': radius_b must be");
  expect_error(with([](ChainDef& c) { c.stiffness = 0; }), "stiffness must be");
  expect_error(with([](ChainDef& c) { c.radius_b = 0.6; }), "the pitch circles overlap");
  expect_error(with([](ChainDef& c) { c.body_b = "wheeel"; }),
               "chain 'chain'.body_b: unknown body 'wheeel' (did you mean 'wheel'?)");
  expect_error(with([](ChainDef& c) { c.body_b = "drive"; }), "both sprockets are on body");
  expect_error(with([](ChainDef& c) { c.rest_upper = -1.0; }), "rest_upper must be");
}

// Box2D has no chain or belt drive: the cross-check refuses the element by name.
TEST(Chain, Box2DCrosscheckRefusesIt) {
  System s("two_discs");  // the flywheels without their bearing (Box2D refuses that too)
  s.add_ground_node("A", {0, 0});
  s.add_ground_node("B", {0.5, 0});
  s.add_body(disc("a", {0, 0}, 1, Ia));
  s.add_body(disc("b", {0.5, 0}, 1, Ib));
  s.add_revolute({.name = "pa", .node_a = "ground.A", .node_b = "a.C"});
  s.add_revolute({.name = "pb", .node_a = "ground.B", .node_b = "b.C"});
  s.add_chain({.name = "chain",
               .body_a = "a",
               .centre_a = {0, 0},
               .radius_a = ra,
               .body_b = "b",
               .centre_b = {0.5, 0},
               .radius_b = rb,
               .stiffness = 1e4});
  const Model m = build_model(s, {.reduction = Reduction::none});
  const State s0 =
      consistent_state(m, {.positions = {}, .velocities = {{"a.w", 1.0}, {"b.w", 0.0}}});
  try {
    crosscheck_forward(m, s0, 0.1);
    ADD_FAILURE() << "a chain was translated to Box2D";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("chain 'chain' is not translated"), std::string::npos)
        << e.what();
  }
}

}  // namespace

// The wrap term needs the line of centres' angle unwrapped, which is tracked within
// kChainMaxTurn of its initial direction: past that the length would jump by 2 pi (r_b - r_a),
// so the evaluation stops with an error naming the chain and the time (here the initial
// direction is moved instead of the sprockets).
TEST(Chain, LineOfCentresTurningTooFarIsAnError) {
  Model m = build_model(swing_arm_drive(1e4, ChainFidelity::unilateral));
  const Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
  EXPECT_NO_THROW(chain_value(m, m.chains[0], m.q0, q1, 0.0));
  m.chains[0].beta0 += 0.9 * detail::kChainMaxTurn;  // still within: no error
  EXPECT_NO_THROW(chain_value(m, m.chains[0], m.q0, q1, 0.0));
  m.chains[0].beta0 += 0.35;  // 3.05 rad in all: past kChainMaxTurn, short of pi
  try {
    chain_value(m, m.chains[0], m.q0, q1, 1.25);
    ADD_FAILURE() << "no error past kChainMaxTurn";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("chain 'chain': the line of centres turned"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("t = 1.25"), std::string::npos) << e.what();
  }
}

// The fidelity report lists both spans. On fixed centres a span's own inertia is that of the two
// flywheels reflected to the chain in series, m_r = 1 / (r_a^2 / I_a + r_b^2 / I_b), so
// omega = sqrt(k / m_r) (136 rad/s, ten times what outputs every 0.5 s resolve); the verdict
// names the gear pair, not a reduction that chains lack.
TEST(Chain, FidelityReportListsTheSpansWithTheirFrequency) {
  const double k = 1e5;
  const Model m = build_model(flywheels(k));
  const std::vector<CompliantElement> rep = fidelity_report(
      m, m.q0, Eigen::VectorXd::Zero(m.n1), 0.0, {.duration = 10, .output_interval = 0.5});
  const double mr = 1 / (ra * ra / Ia + rb * rb / Ib);
  int found = 0;
  for (const CompliantElement& c : rep) {
    if (c.name != "chain.upper" && c.name != "chain.lower") continue;
    ++found;
    EXPECT_EQ(c.kind, "chain span (taut)");
    EXPECT_NEAR(c.inertia, mr, 1e-12 * mr) << c.name;
    EXPECT_NEAR(c.omega, std::sqrt(k / mr), 1e-9 * std::sqrt(k / mr)) << c.name;
    EXPECT_NE(c.verdict.find("gear pair"), std::string::npos) << c.verdict;
  }
  EXPECT_EQ(found, 2);
}
