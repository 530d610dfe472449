// A stiff spring reduced to a constraint (reduce: constraint; docs/reduction.md): the thesis's
// mass-spring-mass (mechanisms/mass_spring_mass.yaml) against the closed form of its reduced
// dynamics and quasi-steady tension, the full model's 1/k approach to it, unilateral springs
// reported when they would go slack, and the fidelity report on a stiff and a soft spring.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "mo2d/crosscheck.hpp"
#include "mo2d/error.hpp"
#include "mo2d/fidelity.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

std::string scene_text() {
  std::ifstream in(std::string(MO2D_MECHANISMS_DIR) + "/mass_spring_mass.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The parameters of mass_spring_mass.yaml and the closed forms of Gamba 2009, 2.3.
struct Msm {
  double m1 = 1, m2 = 2, c1 = 0.5, c2 = 2, F1a = 2, F1b = 3, W = 3, F2 = 1, v0 = 0;
  double M() const { return m1 + m2; }
  double a() const { return (c1 + c2) / M(); }
  double F1(double t) const { return F1a + F1b * std::sin(W * t); }
  // v' = -a v + (F1 + F2) / M (2.24): steady part, the sine's particular solution, the transient
  double v(double t) const {
    const double vs = (F1a + F2) / (c1 + c2), b = F1b / M(), A = a();
    auto vp = [&](double s) {
      return b * (A * std::sin(W * s) - W * std::cos(W * s)) / (A * A + W * W);
    };
    return vs + vp(t) + (v0 - vs - vp(0)) * std::exp(-A * t);
  }
  double vdot(double t) const { return -a() * v(t) + (F1(t) + F2) / M(); }
  // the quasi-steady tension (2.31 with the signs corrected, seeds README) and its rate
  double T(double t) const { return ((c1 * m2 - c2 * m1) * v(t) - (F1(t) * m2 - F2 * m1)) / M(); }
  double Tdot(double t) const {
    return ((c1 * m2 - c2 * m1) * vdot(t) - F1b * W * std::cos(W * t) * m2) / M();
  }
};

// The reduced model: the scene as shipped.
TEST(ReducedSpring, MassSpringMassMatchesTheClosedFormAndTheQuasiSteadyTension) {
  const Scene scene = parse_scene(scene_text(), "mass_spring_mass.yaml");
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 1);
  ASSERT_EQ(m.reduced_springs.size(), 1u);
  EXPECT_TRUE(m.springs.empty());
  const Trajectory r = forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
  const Msm x;
  double worst_v = 0, worst_T = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const double v1 = r.q1(i, r.rate_column("slide1.v")), v2 = r.q1(i, r.rate_column("slide2.v"));
    worst_v = std::max({worst_v, std::abs(v1 - x.v(t)), std::abs(v2 - x.v(t))});
    worst_T = std::max(worst_T, std::abs(r.reactions(i, r.reaction("link.tension")) - x.T(t)));
    EXPECT_NEAR(r.q0(i, r.column("slide2.q")) - r.q0(i, r.column("slide1.q")), 0.5, 1e-10) << t;
  }
  EXPECT_LT(worst_v, 1e-8);
  EXPECT_LT(worst_T, 1e-7);
  EXPECT_LT(r.stats.max_drift, 1e-11);
  EXPECT_TRUE(r.stats.warnings.empty());
  std::printf("reduced mass-spring-mass: max |v - v_closed| = %.3g m/s, max |T - T_qs| = %.3g N\n",
              worst_v, worst_T);
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// The full model (reduce: none, stiffness k) from a consistent start: extension T(0) / k, its
// rate T'(0) / k, the centre of mass at v0. Returns the largest error of the centre of mass's
// velocity against the closed form and of the spring's tension against T.
std::pair<double, double> full_model_errors(double k) {
  std::string text = scene_text();
  text.replace(text.find("reduce: constraint}"), 18, "reduce: none");
  const Msm x;
  const double e0 = x.T(0) / k, u0 = x.Tdot(0) / k;
  const std::vector<ParameterOverride> set = {{"k", num(k)}, {"e0", num(e0)}};
  const Scene scene = parse_scene(text, "mass_spring_mass.yaml", set);
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 2);
  const ForwardOptions o = forward_options(scene, m);
  const State s = consistent_state(
      m, {{}, {{"slide1.v", x.v0 - x.m2 / x.M() * u0}, {"slide2.v", x.v0 + x.m1 / x.M() * u0}}});
  const Trajectory r = forward_dynamics(m, s, o);
  double ev = 0, eT = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const double V =
        (x.m1 * r.q1(i, r.rate_column("slide1.v")) + x.m2 * r.q1(i, r.rate_column("slide2.v"))) /
        x.M();
    ev = std::max(ev, std::abs(V - x.v(t)));
    const double l = r.q0(i, r.column("slide2.q")) - r.q0(i, r.column("slide1.q"));
    eT = std::max(eT, std::abs(k * (l - 0.5) - x.T(t)));  // the spring's tension k (l - l0)
  }
  return {ev, eT};
}

TEST(ReducedSpring, FullModelApproachesTheReducedOneAsOneOverK) {
  const std::vector<double> ks = {1e3, 1e4, 1e5};
  std::vector<double> ev, eT;
  for (double k : ks) {
    const auto [v, T] = full_model_errors(k);
    ev.push_back(v);
    eT.push_back(T);
    std::printf("full model k = %.0e: max |V - v_closed| = %.3e m/s, max |T - T_qs| = %.3e N\n", k,
                v, T);
  }
  // slopes of log(error) against log(k) between successive stiffnesses: -1
  for (size_t j = 0; j + 1 < ks.size(); ++j) {
    const double sv = std::log(ev[j + 1] / ev[j]) / std::log(ks[j + 1] / ks[j]);
    const double sT = std::log(eT[j + 1] / eT[j]) / std::log(ks[j + 1] / ks[j]);
    EXPECT_NEAR(sv, -1, 0.1) << ks[j];
    EXPECT_NEAR(sT, -1, 0.1) << ks[j];
  }
}

// A point mass on a rope (reduced, acts: tension) thrown upwards from the horizontal: the rope
// would go slack where v^2 / L < g sin(theta); the run warns with the time. A hanging one does not.
std::string rope_scene(const std::string& vy, const std::string& acts) {
  return "name: rope\n"
         "ground: {O: [0, 0]}\n"
         "bodies: {bob: {nodes: {P: [1, 0]}, mass: 1}}\n"
         "loads:\n"
         "  gravity: [0, -9.81]\n"
         "  springs:\n"
         "    rope: {body_a: ground, point_a: [0, 0], body_b: bob, point_b: [1, 0],\n"
         "           rest_length: 1, stiffness: 1e6, acts: " +
         acts +
         ", reduce: constraint}\n"
         "initial: {velocities: {bob.P.vy: " +
         vy +
         "}}\n"
         "run: {solve: forward, duration: 0.5, samples: 51}\n";
}

Trajectory run_scene(const std::string& text) {
  const Scene scene = parse_scene(text, "rope.yaml");
  const Model m = build_scene_model(scene);
  return forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
}

TEST(ReducedSpring, SlackRopeIsAWarningNamingTheTime) {
  const Trajectory r = run_scene(rope_scene("2", "tension"));
  ASSERT_EQ(r.stats.warnings.size(), 1u);
  EXPECT_NE(r.stats.warnings[0].find("spring 'rope'"), std::string::npos) << r.stats.warnings[0];
  EXPECT_NE(r.stats.warnings[0].find("go slack at t = "), std::string::npos);
  // the tension there is m (v^2 / L - g sin theta) (the constraint keeps it on the circle)
  const int i = 10;
  const double x = r.q0(i, r.column("bob.P.x")), y = r.q0(i, r.column("bob.P.y"));
  const double vx = r.q1(i, r.rate_column("bob.P.vx")), vy = r.q1(i, r.rate_column("bob.P.vy"));
  EXPECT_NEAR(r.reactions(i, r.reaction("rope.tension")), vx * vx + vy * vy - 9.81 * y, 1e-6);
  EXPECT_NEAR(std::hypot(x, y), 1, 1e-10);
  EXPECT_TRUE(run_scene(rope_scene("2", "both")).stats.warnings.empty());      // bilateral: a rod
  EXPECT_TRUE(run_scene(rope_scene("-2", "tension")).stats.warnings.empty());  // swings below
}

TEST(ReducedSpring, SparsePathAgreesAndBox2DComparesTheRigidLink) {
  const Scene scene = parse_scene(scene_text(), "mass_spring_mass.yaml");
  const Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  o.integrator = Integrator::dopri5;  // the sparse engine runs the explicit integrators
  o.linear_algebra = LinearAlgebra::dense;
  const Trajectory dense = forward_dynamics(m, initial_state(scene, m), o);
  o.linear_algebra = LinearAlgebra::sparse;
  const Trajectory sparse = forward_dynamics(m, initial_state(scene, m), o);
  EXPECT_TRUE(sparse.stats.sparse);
  EXPECT_LT((dense.reactions - sparse.reactions).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((dense.q1 - sparse.q1).cwiseAbs().maxCoeff(), 1e-8);
  BuildOptions b;
  b.reduction = Reduction::none;
  const Model flat = build_scene_model(scene, b);
  // Box2D compares the spring reduced to a constraint as a rigid distance joint (issue 32;
  // add_rigid_spring, crosscheck/box2d_world.cpp): the reduced model's motion, within Box2D's
  // first-order error (measured 1.3e-6 of the size over 0.1 s; with the link 10 % long, 1.7e-3,
  // which the cross-check's default tolerance of 1e-2 lets pass)
  const ForwardCrosscheck c = crosscheck_forward(flat, initial_state(scene, flat), 0.1);
  EXPECT_LT(c.relative_position_error, 1e-4) << c.max_position_error;
}

TEST(ReducedSpring, BadInputIsRefusedAtTheSpring) {
  std::string text = rope_scene("2", "tension");
  try {
    run_scene(text.replace(text.find("rest_length: 1"), 14, "rest_length: 0"));
    FAIL() << "a zero rest length was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("needs rest_length > 0"), std::string::npos) << e.what();
  }
  text = rope_scene("2", "tension");
  try {
    run_scene(text.replace(text.find("reduce: constraint"), 18, "reduce: constrain"));
    FAIL() << "an unknown reduction was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'constraint'"), std::string::npos)
        << e.what();
  }
}

// The mass-spring-mass with its link a spring (k = 1e8) and a soft spring (k = 2) from the
// ground to mass 1. Each spring's own frequency: the link's length sees the reduced mass
// m1 m2 / (m1 + m2) (omega = sqrt(k (m1 + m2) / (m1 m2))), the soft spring's sees m1 alone (the
// link is free in this model); at outputs every 0.01 s the link is to be reduced, the soft one
// kept.
TEST(FidelityReport, StiffAndSoftSprings) {
  std::string text = scene_text();
  text.replace(text.find("reduce: constraint}"), 19,
               "reduce: none}\n    soft: {body_a: ground, point_a: [-1, 0], body_b: mass1, "
               "point_b: [0, 0], rest_length: 1, stiffness: 2}");
  const Scene scene = parse_scene(text, "msm.yaml", std::vector<ParameterOverride>{{"k", "1e8"}});
  const Model m = build_scene_model(scene);
  const RunTimeScale scale{3, 0.01, 0};
  const std::vector<CompliantElement> rep =
      fidelity_report(m, m.q0, Eigen::VectorXd::Zero(m.n1), 0, scale);
  ASSERT_EQ(rep.size(), 2u);
  const CompliantElement& soft = rep[0].name == "soft" ? rep[0] : rep[1];
  const CompliantElement& link = rep[0].name == "link" ? rep[0] : rep[1];
  EXPECT_NEAR(link.inertia, 2.0 / 3, 1e-12);
  EXPECT_NEAR(link.omega, std::sqrt(1e8 * 1.5), 1e-6);
  EXPECT_NEAR(soft.inertia, 1, 1e-12);
  EXPECT_NEAR(soft.omega, std::sqrt(2.0), 1e-12);
  const double w_out = std::acos(-1.0) / 0.01;
  EXPECT_NEAR(link.error_output, w_out * w_out / 1.5e8, 1e-15);
  EXPECT_NE(link.verdict.find("reduce: constraint"), std::string::npos) << link.verdict;
  EXPECT_NE(soft.verdict.find("keep it"), std::string::npos) << soft.verdict;
  std::printf("%s", describe_fidelity(rep, scale).c_str());
}

// mechanisms/half_bike.yaml's report, its suspension (a torsional spring with a law) reduced by
// `reduce` ("" none) and its chain at `fidelity`.
std::vector<CompliantElement> half_bike_fidelity(const std::string& reduce,
                                                 const std::string& fidelity) {
  std::ifstream in(std::string(MO2D_MECHANISMS_DIR) + "/half_bike.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string susp = "tau_pre}\n", chain = "fidelity: unilateral,";
  const std::string v = "velocities: {shaft.w: 0, arm.w: 0, wheel.w: 0}";
  if (s.find(susp) == std::string::npos || s.find(chain) == std::string::npos ||
      s.find(v) == std::string::npos)
    return {};
  if (!reduce.empty()) s.replace(s.find(susp), susp.size(), "tau_pre, reduce: " + reduce + "}\n");
  s.replace(s.find(chain), chain.size(), "fidelity: " + fidelity + ",");
  if (fidelity != "unilateral") s.replace(s.find(v), v.size(), "velocities: {shaft.w: 0}");
  const std::vector<ParameterOverride> no_slack = {{"slack", "0"}};  // the same assembly
  const Model m = build_scene_model(parse_scene(s, "half_bike.yaml", no_slack));
  return fidelity_report(m, m.q0, Eigen::VectorXd::Zero(m.n1), 0, {15, 0.01, 0});
}

const CompliantElement* element_named(const std::vector<CompliantElement>& rep,
                                      const std::string& name) {
  for (const CompliantElement& c : rep)
    if (c.name == name) return &c;
  return nullptr;
}

// Every compliant element is listed with its current fidelity: the reduced suspension (reduce:
// constraint or quasi_steady) and the reduced chain (fidelity: inextensible or quasi_steady),
// each with the stiffness, inertia and frequency of its own mode. Reduced alone (the other
// element as in the full model), that is the mode the full model (the suspension a load, the
// chain unilateral) reports for it: the reduced model frees the element's own row, the full
// model has none. (Both reduced, each sees the other's row: its inertia is 9e-4 larger.)
// Without the scene's slack the initial configurations are the same.
TEST(FidelityReport, ListsReducedTorsionalSpringsAndChainsWithTheirFidelity) {
  const std::vector<CompliantElement> full = half_bike_fidelity("", "unilateral");
  ASSERT_FALSE(full.empty());
  for (const auto& [reduce, fidelity] :
       {std::pair<std::string, std::string>{"constraint", "inextensible"},
        {"quasi_steady", "quasi_steady"}}) {
    const std::vector<CompliantElement> both = half_bike_fidelity(reduce, fidelity);
    EXPECT_EQ(both.size(), full.size());
    for (const std::string name : {"suspension", "chain.upper", "chain.lower"}) {
      SCOPED_TRACE(name + " " + reduce);
      const bool susp = name == "suspension";
      const std::vector<CompliantElement> alone =
          susp ? half_bike_fidelity(reduce, "unilateral") : half_bike_fidelity("", fidelity);
      const CompliantElement* a = element_named(full, name);
      const CompliantElement* b = element_named(alone, name);
      const CompliantElement* c = element_named(both, name);
      ASSERT_TRUE(a && b && c);
      EXPECT_FALSE(a->reduced);
      EXPECT_TRUE(b->reduced && c->reduced);
      const std::string how = susp ? "reduce: " + reduce : "fidelity: " + fidelity;
      EXPECT_EQ(c->reduction, how);
      EXPECT_NE(c->verdict.find("reduced (" + how + ")"), std::string::npos) << c->verdict;
      EXPECT_EQ(b->stiffness, a->stiffness);
      EXPECT_NEAR(b->inertia, a->inertia, 1e-9 * a->inertia);
      EXPECT_NEAR(b->omega, a->omega, 1e-9 * a->omega);
      EXPECT_GT(c->omega, 10);
      std::printf("%-12s %-24s inertia %.9g (full %.9g; both reduced %.6g), omega %.6g rad/s\n",
                  name.c_str(), how.c_str(), b->inertia, a->inertia, c->inertia, b->omega);
    }
  }
}

}  // namespace
}  // namespace mo2d
