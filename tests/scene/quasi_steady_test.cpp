// The quasi-steady-state model of a spring (reduce: quasi_steady; mo2d/quasi_steady.hpp,
// docs/reduction.md): the thesis's mass-spring-mass against the closed form of its reduced
// dynamics, its quasi-steady tension and the quasi-steady length l0 + T / k; an elastic pendulum
// against a second formulation (the thesis's numerical QSS in polar coordinates: the radius
// solved at each evaluation so that its acceleration vanishes, at zero radial rate) with a
// linear and a nonlinear law, and against the full model as k grows; bad input.
#include "mo2d/quasi_steady.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "mo2d/crosscheck.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

std::string msm_text() {
  std::ifstream in(std::string(MO2D_MECHANISMS_DIR) + "/mass_spring_mass.yaml");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  return text.replace(text.find("reduce: constraint}"), 18, "reduce: quasi_steady");
}

// The parameters of mass_spring_mass.yaml and the closed forms of Gamba 2009, 2.3.
struct Msm {
  double m1 = 1, m2 = 2, c1 = 0.5, c2 = 2, F1a = 2, F1b = 3, W = 3, F2 = 1, v0 = 0, k = 1e4;
  double l0 = 0.5;
  double M() const { return m1 + m2; }
  double a() const { return (c1 + c2) / M(); }
  double F1(double t) const { return F1a + F1b * std::sin(W * t); }
  double v(double t) const {  // v' = -a v + (F1 + F2) / M (2.24)
    const double vs = (F1a + F2) / (c1 + c2), b = F1b / M(), A = a();
    auto vp = [&](double s) {
      return b * (A * std::sin(W * s) - W * std::cos(W * s)) / (A * A + W * W);
    };
    return vs + vp(t) + (v0 - vs - vp(0)) * std::exp(-A * t);
  }
  // the quasi-steady tension (2.31 with the signs corrected, seeds README)
  double T(double t) const { return ((c1 * m2 - c2 * m1) * v(t) - (F1(t) * m2 - F2 * m1)) / M(); }
};

Trajectory run(const std::string& text, const std::vector<ParameterOverride>& set = {},
               std::function<void(ForwardOptions&)> change = {}) {
  const Scene scene = parse_scene(text, "qss.yaml", set);
  const Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  o.integrator = Integrator::dopri5;  // QSS runs need an explicit integrator that projects
  if (change) change(o);
  return forward_dynamics(m, initial_state(scene, m), o);
}

// The masses' distance is the quasi-steady length l0 + T / k (not the rest length: T / k is up to
// 3.4e-4 m here). mo2d's row moves with that length (z2 = dT/dt, not the thesis's z2 = 0), so the
// masses' velocities differ by the stretch rate as in the full model, and the centre of mass and
// the tension follow the rigid closed form (2.24, 2.31) only to O(1/k): within the full model's
// errors at the same k (2.2e-5 m/s and 1.5e-3 N, tests/scene/reduction_scene_test.cpp).
TEST(QuasiSteady, MassSpringMassClosedFormTensionAndLength) {
  const Trajectory r = run(msm_text());
  const Msm x;
  double worst_v = 0, worst_T = 0, worst_l = 0, stretch = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const double v1 = r.q1(i, r.rate_column("slide1.v")), v2 = r.q1(i, r.rate_column("slide2.v"));
    const double T = r.reactions(i, r.reaction("link.tension"));
    const double l = r.q0(i, r.column("slide2.q")) - r.q0(i, r.column("slide1.q"));
    worst_v = std::max(worst_v, std::abs((x.m1 * v1 + x.m2 * v2) / x.M() - x.v(t)));
    worst_T = std::max(worst_T, std::abs(T - x.T(t)));
    worst_l = std::max(worst_l, std::abs(l - (x.l0 + T / x.k)));
    stretch = std::max(stretch, std::abs(l - x.l0));
  }
  EXPECT_LT(worst_v, 2.5e-5);  // the full model: 2.20e-5 (the same O(1/k) term)
  EXPECT_LT(worst_T, 1.5e-3);
  EXPECT_LT(worst_l, 1e-7);  // the held length follows l0 + T / k
  EXPECT_GT(stretch, 1e-4);
  EXPECT_TRUE(r.stats.warnings.empty());
  std::printf(
      "QSS mass-spring-mass: max |V - v_closed| = %.3g m/s, max |T - T_qs| = %.3g N, "
      "max |l - (l0 + T/k)| = %.3g m (stretch up to %.3g m)\n",
      worst_v, worst_T, worst_l, stretch);
}

TEST(QuasiSteady, SparsePathAgreesAndBox2DRefusesByName) {
  auto o = [](LinearAlgebra la) {
    return [la](ForwardOptions& f) {
      f.integrator = Integrator::dopri5;  // the sparse engine runs the explicit integrators
      f.linear_algebra = la;
    };
  };
  const Trajectory dense = run(msm_text(), {}, o(LinearAlgebra::dense));
  const Trajectory sparse = run(msm_text(), {}, o(LinearAlgebra::sparse));
  EXPECT_TRUE(sparse.stats.sparse);
  EXPECT_LT((dense.reactions - sparse.reactions).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((dense.q1 - sparse.q1).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((dense.q0 - sparse.q0).cwiseAbs().maxCoeff(), 1e-9);
  const Scene scene = parse_scene(msm_text(), "mass_spring_mass.yaml");
  BuildOptions b;
  b.reduction = Reduction::none;
  const Model flat = build_scene_model(scene, b);
  try {
    crosscheck_forward(flat, initial_state(scene, flat), 0.1);
    FAIL() << "Box2D accepted a quasi-steady spring";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spring 'link' reduced to its quasi-steady state (reduce: "
                                         "quasi_steady) is not translated"),
              std::string::npos)
        << e.what();
  }
}

// ---- the elastic pendulum --------------------------------------------------------------------

// A point mass of 1 kg on a spring from the ground pivot (rest length 1 m), started at angle
// th0 from the vertical at radius r0, at rest. `law`: a tension law, or "" for stiffness k.
std::string pendulum(const std::string& reduce, const std::string& law = "") {
  return "name: qss_pendulum\n"
         "parameters: {k: 1e3, k3: 0, l0: 1, r0: 1, th0: 0.5}\n"
         "ground: {O: [0, 0]}\n"
         "bodies: {bob: {nodes: {P: [r0 * sin(th0), -r0 * cos(th0)]}, mass: 1}}\n"
         "loads:\n"
         "  gravity: [0, -9.81]\n"
         "  springs:\n"
         "    s: {body_a: ground, point_a: [0, 0], body_b: bob,\n"
         "        point_b: [r0 * sin(th0), -r0 * cos(th0)], rest_length: l0, " +
         (law.empty() ? std::string("stiffness: k") : "tension: \"" + law + "\"") +
         ", reduce: " + reduce +
         "}\n"
         "initial: {velocities: {bob.P.vx: 0" +
         (reduce == "none" ? std::string(", bob.P.vy: 0") : "") +
         "}}\n"
         "run: {solve: forward, duration: 2, samples: 201, rtol: 1e-10, atol: 1e-12}\n";
}

double angle(const Trajectory& r, int i) {
  return std::atan2(r.q0(i, r.column("bob.P.x")), -r.q0(i, r.column("bob.P.y")));
}
double radius(const Trajectory& r, int i) {
  return std::hypot(r.q0(i, r.column("bob.P.x")), r.q0(i, r.column("bob.P.y")));
}

// The thesis's numerical QSS on the pendulum in polar coordinates (r, theta): the radial rate
// set to 0 and the radius r solved at each evaluation so that the radial acceleration vanishes,
// T_law(r) = m (r w^2 + g cos theta); then theta'' = -g sin theta / r. RK4, h = 1e-4 s.
struct PolarQss {
  double k = 1e3, k3 = 0, l0 = 1, g = 9.81;
  double law(double e) const { return k * e + k3 * e * e * e; }
  double r(double th, double w) const {
    double rr = l0;
    for (int it = 0; it < 60; ++it) {  // Newton on T_law(r - l0) - (r w^2 + g cos th) = 0
      const double e = rr - l0;
      const double f = law(e) - (rr * w * w + g * std::cos(th));
      const double df = k + 3 * k3 * e * e - w * w;
      rr -= f / df;
    }
    return rr;
  }
  // theta at the times `at` (ascending) from theta0 at rest
  std::vector<double> run(double th0, const Eigen::VectorXd& at) const {
    auto rhs = [&](double th, double w) { return -g * std::sin(th) / r(th, w); };
    std::vector<double> out;
    double t = 0, th = th0, w = 0;
    const double h = 1e-4;
    for (int i = 0; i < at.size(); ++i) {
      while (t < at[i] - 1e-12) {
        const double s = std::min(h, at[i] - t);
        const double k1 = w, l1 = rhs(th, w);
        const double k2 = w + 0.5 * s * l1, l2 = rhs(th + 0.5 * s * k1, k2);
        const double k3_ = w + 0.5 * s * l2, l3 = rhs(th + 0.5 * s * k2, k3_);
        const double k4 = w + s * l3, l4 = rhs(th + s * k3_, k4);
        th += s / 6 * (k1 + 2 * k2 + 2 * k3_ + k4);
        w += s / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
        t += s;
      }
      out.push_back(th);
    }
    return out;
  }
};

// mo2d's QSS against the polar one: angle, radius (the QSS length) and tension.
// Returns the largest angle difference (the thesis's z2 = 0 against mo2d's z2 = dT/dt: O(1/k)).
double expect_matches_polar(const Trajectory& r, const PolarQss& p, const char* what) {
  const std::vector<double> th = p.run(0.5, r.time);
  double e_th = 0, e_r = 0, e_T = 0, stretch = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double rr = radius(r, i);
    const double w = -(r.q1(i, r.rate_column("bob.P.vx")) * r.q0(i, r.column("bob.P.y")) -
                       r.q1(i, r.rate_column("bob.P.vy")) * r.q0(i, r.column("bob.P.x"))) /
                     (rr * rr);
    e_th = std::max(e_th, std::abs(angle(r, i) - th[i]));
    e_r = std::max(e_r, std::abs(rr - p.r(angle(r, i), w)));
    e_T = std::max(e_T, std::abs(r.reactions(i, r.reaction("s.tension")) - p.law(rr - p.l0)));
    stretch = std::max(stretch, rr - p.l0);
  }
  std::printf(
      "%s: max |theta - theta_polar| = %.3g rad, max |r - r_qs| = %.3g m, "
      "max |T - T_law(r)| = %.3g N (stretch up to %.3g m)\n",
      what, e_th, e_r, e_T, stretch);
  EXPECT_LT(e_r, 1e-10) << what;  // on the thesis's QSS manifold: f_fast = 0 at its own state
  EXPECT_LT(e_T, 1e-6) << what;
  EXPECT_GT(stretch, 0.5 * p.g / p.k) << what;  // the QSS length is not the rest length
  return e_th;
}

// The radius and tension at solver tolerance; the angles differ by the rate the two hold: the
// thesis's ṙ = 0 drops the Coriolis term 2 ṙ θ' / r, mo2d's row moves with the manifold; the
// difference is O(1/k) (a tenth at ten times the stiffness).
TEST(QuasiSteady, PendulumMatchesTheThesisNumericalQss) {
  const double e3 =
      expect_matches_polar(run(pendulum("quasi_steady")), PolarQss{}, "QSS pendulum, k = 1e3");
  PolarQss p4;
  p4.k = 1e4;
  const double e4 = expect_matches_polar(run(pendulum("quasi_steady"), {{"k", "1e4"}}), p4,
                                         "QSS pendulum, k = 1e4");
  EXPECT_NEAR(std::log10(e3 / e4), 1, 0.1);
}

// A hardening law T = k e + k3 e^3: the held length by Newton on the law.
TEST(QuasiSteady, NonlinearLawPendulumMatchesThePolarQss) {
  const Trajectory r =
      run(pendulum("quasi_steady", "k * extension + k3 * extension^3 + 5 * rate"), {{"k3", "1e6"}});
  PolarQss p;
  p.k3 = 1e6;  // the damping (5 rate) gives nothing at zero rate
  expect_matches_polar(r, p, "QSS pendulum, k e + k3 e^3");
}

// Against the full model (reduce: none) from the QSS radius at rest, k = 1e3 ... 1e5: the angle
// error falls as k grows, and is far below the constraint model's (which holds the rest length:
// a pendulum shorter by m g / k).
TEST(QuasiSteady, PendulumApproachesTheFullModelAsKGrows) {
  std::vector<double> e_qss, e_con;
  for (double k : {1e3, 1e4, 1e5}) {
    const std::vector<ParameterOverride> set = {{"k", num(k)}};
    std::vector<ParameterOverride> full = set;
    full.push_back({"r0", num(1 + 9.81 * std::cos(0.5) / k)});
    const Trajectory f = run(pendulum("none"), full);
    const Trajectory q = run(pendulum("quasi_steady"), set);
    const Trajectory c = run(pendulum("constraint"), set);
    double eq = 0, ec = 0;
    for (int i = 0; i < f.time.size(); ++i) {
      eq = std::max(eq, std::abs(angle(q, i) - angle(f, i)));
      ec = std::max(ec, std::abs(angle(c, i) - angle(f, i)));
    }
    std::printf(
        "pendulum k = %.0e: max angle error against the full model: QSS %.3e rad, "
        "constraint %.3e rad\n",
        k, eq, ec);
    e_qss.push_back(eq);
    e_con.push_back(ec);
  }
  for (size_t j = 0; j < e_qss.size(); ++j) EXPECT_LT(10 * e_qss[j], e_con[j]) << j;
  for (size_t j = 0; j + 1 < e_qss.size(); ++j) EXPECT_LT(e_qss[j + 1], 0.2 * e_qss[j]) << j;
}

// ---- bad input -------------------------------------------------------------------------------

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(QuasiSteady, BadInputIsRefusedByName) {
  std::string text = pendulum("quasi_steady");
  text.replace(text.find("stiffness: k"), 12, "stiffness: 0");
  std::string e = error_of([&] { run(text); });
  EXPECT_NE(e.find("spring 's' (reduce: quasi_steady): needs stiffness > 0"), std::string::npos)
      << e;
  EXPECT_NE(e.find("qss.yaml:8:"), std::string::npos) << e;  // at the spring's line
  text = pendulum("quasi_stead");
  e = error_of([&] { run(text); });
  EXPECT_NE(e.find("did you mean 'quasi_steady'"), std::string::npos) << e;
  EXPECT_NE(e.find("qss.yaml:9:"), std::string::npos) << e;
  e = error_of([&] {
    run(pendulum("quasi_steady"), {},
        [](ForwardOptions& o) { o.integrator = Integrator::cvode_adams; });
  });
  EXPECT_NE(e.find("quasi-steady elements 's'"), std::string::npos) << e;
  EXPECT_NE(e.find("need an explicit integrator that projects"), std::string::npos) << e;
  e = error_of([&] {
    run(pendulum("quasi_steady"), {},
        [](ForwardOptions& o) { o.integrator = Integrator::cvode_bdf; });
  });
  EXPECT_NE(e.find("not cvode_bdf"), std::string::npos) << e;
  // a law without an equilibrium length for the tension: T = 0.001 atan2(extension, 1) saturates
  e = error_of([&] { run(pendulum("quasi_steady", "0.001 * atan2(extension, 1)")); });
  EXPECT_NE(e.find("spring 's' (reduce: quasi_steady): no equilibrium length"), std::string::npos)
      << e;
}

}  // namespace
}  // namespace mo2d

namespace mo2d {
namespace {

double held_length_of(const Model& m) {
  for (const ReducedSpring& s : m.reduced_springs)
    if (s.held_length) return held_of(s).length;
  return NAN;
}

// The held lengths are the model's: a run that throws leaves them at the rest length (the next
// run, an inverse run or modes see the model as built), and a second run holding them at the
// same time is refused by name instead of moving the first one's lengths.
TEST(QuasiSteady, HeldLengthsAreResetWhenARunThrowsAndClaimedByOneRun) {
  const Scene scene = parse_scene(msm_text(), "qss.yaml");
  const Model m = build_scene_model(scene);
  const double rest = held_length_of(m);
  ForwardOptions o = forward_options(scene, m);
  o.integrator = Integrator::dopri5;
  o.max_steps = 5;  // the budget runs out after the lengths have moved
  EXPECT_THROW(forward_dynamics(m, initial_state(scene, m), o), Error);
  EXPECT_EQ(held_length_of(m), rest);
  {
    const detail::QuasiSteadyRun first(m);
    const Model copy = m;  // shares the cells
    try {
      const detail::QuasiSteadyRun second(copy);
      ADD_FAILURE() << "a second run held the same cells";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("held by another forward run"), std::string::npos)
          << e.what();
    }
  }
  o.max_steps = 1000000;
  EXPECT_NO_THROW(forward_dynamics(m, initial_state(scene, m), o));  // released
}

}  // namespace
}  // namespace mo2d
