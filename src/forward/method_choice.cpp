// choose_method: the integrator for an accuracy asked for (ForwardOptions::accuracy), explicit
// unless the mechanism is stiff at the initial state.
//
// Stiffness test. The run integrates y = (q0, q1), dy/dt = f(t, y) = (q1 head, a1(t, q0, q1)).
// An explicit Runge-Kutta method is stable for steps h with h lambda inside its stability region
// for every eigenvalue lambda of J = df/dy; the regions of rk4 (real interval 2.79, imaginary
// 2.83), dopri5 (real 3.3) and Fehlberg 8(7) all hold the half-disc of radius kStabilityBound =
// 2.5 to within their error control, so the run needs about
//   N_stab = |lambda|max T / kStabilityBound
// steps for stability, T = t1 - t0, and N_acc = T / h_acc for the accuracy, h_acc the step of
// the adaptive explicit method (erk8, tol = accuracy / 1000) on the double four-bar at that
// accuracy (calibration: accuracy.cpp):
//   h_acc = 0.08 s (tol / 1e-8)^(1/8) (127 steps over 10 s at tol 1e-8, 62 at 1e-5;
//   docs/performance.md "items 2 and 4"),
// at every accuracy, also below 1e-8 where options_for_accuracy gives rk4: measured against
// rk4's fixed step (~50 times shorter than erk8's) a mechanism stiff at 1e-8 came out "not
// stiff" at 1e-9 and ran rk4 at a step its fast motion did not allow, 1.5e5 times worse than
// asked (issue 30; tests/forward/accuracy_contract_test.cpp).
// Below 1e-8 rk4's step is the double four-bar's (slow motion, |lambda|max = 3.22 /s at t0): a
// mechanism not stiff but with |lambda|max above kRk4FastestRate = 4 /s runs erk8 (tol =
// accuracy / 1000) instead, whose error control finds the step its motion needs.
// N_stab > kStiffRatio N_acc: stiff; the explicit method would take kStiffRatio times the steps
// its accuracy needs (adaptive: held at the stability limit by its error control; rk4: diverges),
// while cvode_bdf (A(alpha)-stable) takes steps of the accuracy: cvode_bdf with rtol = atol =
// accuracy / 1000, the explicit methods' tolerance per accuracy (checked on the closed form of
// a stiff mass-spring-mass, tests/forward/method_choice_test.cpp; not calibrated further).
//
// |lambda|max: power iteration on J^2 (eigenvalue lambda^2, so that a dominant complex pair
// +-i w of an undamped oscillation gives one dominant value -w^2), J v by forward differences of f
// in dimensionless variables (y scaled by ForwardData::pos_scale, col_scale: lengths), from a
// fixed start vector, until |lambda|max changes by less than 1e-4 (at most 200 evaluations: with
// a 1 % test it stopped 6 % high on the mass-spring-mass, converging slowly). With damping the
// dominant pair of J^2 is complex too (lambda^2 = w^2 (1 - 2 zeta^2 +- 2i zeta sqrt(1 - zeta^2))),
// and the iteration stops short: 12 % low at zeta = 0.09 (measured on the mass-spring-mass held
// to the ground by a damped mount); the factor kStiffRatio absorbs that.
// The estimate holds at the initial state only: a mechanism that becomes stiff later (a spring
// that loads, a stiffening law) is not seen; an adaptive explicit method then stays stable by its
// error control, slowly, and rk4's fixed step (accuracies below 1e-6) may not: the run's
// finiteness and drift checks stop it with an error; name the integrator for such a scene.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/quasi_steady.hpp"
#include "run/format.hpp"

namespace mo2d {

namespace {

constexpr int kMaxPowerPairs = 100;       // power iterations on J^2 at most
constexpr double kPowerConverged = 1e-4;  // relative change of |lambda|max between iterations
constexpr double kFiniteStep = 1e-7;      // forward-difference step, relative to Model::scale
constexpr double kBdfTolerancePerAccuracy = 1e-3;       // cvode_bdf: rtol = atol = accuracy x this
constexpr double kExplicitTolerancePerAccuracy = 1e-3;  // erk8: the same (accuracy.cpp)
// rk4's step (accuracies below 1e-8, accuracy.cpp) is calibrated on the double four-bar, whose
// |lambda|max at t0 is 3.22 /s, with a margin of 3 in the error: rk4's error grows as
// (h |lambda|)^4, so a mechanism with |lambda|max above kRk4FastestRate (1.25 times that:
// 1.25^4 = 2.4, within the margin) moves faster than the step allows and runs erk8 instead.
constexpr double kRk4FastestRate = 4;  // 1/s

// f(t, y) of the run (without the energy terms); false where the accelerations are regularized
// (a singular configuration: the derivatives there say nothing about stiffness) or not finite.
bool rate(ForwardData& d, double t, const VectorXd& y, VectorXd& f) {
  const Model& m = d.m;
  const VectorXd q0 = y.head(m.n0), q1 = y.tail(m.n1);
  d.accelerations(t, q0, q1, false);
  f.resize(m.n0 + m.n1);
  f.head(m.n0) = q1.head(m.n0);
  f.tail(m.n1) = d.a;
  return d.accel_ok && f.allFinite();
}

// |lambda|max of df/dy at s (NaN where it cannot be estimated).
double spectral_radius(const Model& m, const State& s, const ForwardOptions& o) {
  ForwardOptions eo = o;
  eo.integrator = Integrator::dopri5;  // the explicit workspace (dense or sparse as the run's)
  ForwardData d(m, eo);
  const int n = m.n0 + m.n1;
  VectorXd scale(n);                  // y = scale .* z, z in lengths
  scale << d.pos_scale, d.col_scale;  // a rotation: an arc of the mechanism's size
  VectorXd y0(n), f0, f1;
  y0 << s.q0, s.q1;
  if (!rate(d, s.t, y0, f0)) return NAN;
  const double eps = kFiniteStep * m.scale;
  VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = std::sin(1.7 * i + 0.3) + 0.5;  // no special direction
  v.normalize();
  const auto times_J = [&](const VectorXd& x, VectorXd& out) {  // out = D^-1 J D x, |x| = 1
    if (!rate(d, s.t, y0 + eps * scale.cwiseProduct(x), f1)) return false;
    out = (f1 - f0).cwiseQuotient(scale) / eps;
    return out.allFinite();
  };
  double rho = NAN;
  VectorXd w1, w2;
  for (int k = 0; k < kMaxPowerPairs; ++k) {
    if (!times_J(v, w1)) return NAN;
    const double n1 = w1.norm();
    if (n1 == 0) return 0;  // J v = 0: no dynamics along v (and J^2 v = 0)
    if (!times_J(w1 / n1, w2)) return NAN;
    const double n2 = w2.norm() * n1;  // |J^2 v|
    const double next = std::sqrt(n2);
    if (n2 == 0) return rho > 0 ? rho : n1;  // nilpotent along v (q0' = q1 with no force)
    v = w2 / w2.norm();
    if (std::abs(next - rho) <= kPowerConverged * next) return next;
    rho = next;
  }
  return rho;
}

// The step an adaptive explicit method (erk8, rtol = atol = accuracy / 1000) needs for the
// accuracy (header comment): the yardstick of the stiffness test at every accuracy, continuous in
// it. (rk4's fixed step below 1e-8 is not: it is ~50 times shorter than erk8's, so measured
// against it a mechanism stiff at 1e-8 came out "not stiff" at 1e-9 and ran rk4 at a step its
// fast motion did not allow: issue 30.)
double accuracy_step(double accuracy) {
  return 0.08 * std::pow(kExplicitTolerancePerAccuracy * accuracy / 1e-8, 1.0 / 8);
}

std::string method_text(const ForwardOptions& o) {
  if (o.integrator == Integrator::rk4) return "rk4, step " + detail::fmt(o.step) + " s";
  return std::string(to_string(o.integrator)) + ", rtol = atol = " + detail::fmt(o.rtol);
}

}  // namespace

MethodChoice choose_method(const Model& m, const State& s, const ForwardOptions& o) {
  MethodChoice c;
  c.options = options_for_accuracy(m, o);
  if (o.accuracy == 0) return c;
  const double T = o.t1 - o.t0;
  c.spectral_radius = spectral_radius(m, s, o);
  c.accuracy_steps = T / accuracy_step(o.accuracy);
  const std::string asked = "accuracy " + detail::fmt(o.accuracy);
  if (!std::isfinite(c.spectral_radius)) {
    c.reason = asked + ", stiffness not estimated (the accelerations at t0 are regularized: a " +
               "singular configuration): " + method_text(c.options);
    return c;
  }
  c.stability_steps = c.spectral_radius * T / kStabilityBound;
  c.stiff = c.stability_steps > kStiffRatio * c.accuracy_steps;
  char why[200];
  std::snprintf(why, sizeof why,
                "|lambda|max = %.3g /s at t0: %.3g steps for stability, %s %g x %.3g for the "
                "accuracy",
                c.spectral_radius, c.stability_steps, c.stiff ? "more than" : "not more than",
                kStiffRatio, c.accuracy_steps);
  const bool sparse_only = o.linear_algebra == LinearAlgebra::sparse;  // cvode_bdf is dense
  if (c.stiff && sparse_only) {
    c.reason = asked + ", stiff (" + why +
               ") but linear_algebra sparse, which cvode_bdf lacks: " + method_text(c.options);
    return c;
  }
  if (c.stiff && has_quasi_steady(m)) {  // start_quasi_steady refuses cvode_bdf
    c.reason =
        asked + ", stiff (" + why +
        ") but with quasi-steady springs, which cvode_bdf cannot follow: " + method_text(c.options);
    return c;
  }
  std::string fast;
  if (c.stiff) {
    c.options.integrator = Integrator::cvode_bdf;
    c.options.rtol = c.options.atol = kBdfTolerancePerAccuracy * o.accuracy;
  } else if (c.options.integrator == Integrator::rk4 && c.spectral_radius > kRk4FastestRate) {
    c.options.integrator = Integrator::erk8;  // rk4's step is too long for this motion
    c.options.rtol = c.options.atol = kExplicitTolerancePerAccuracy * o.accuracy;
    fast = "; faster than rk4's calibrated step allows (|lambda|max above " +
           detail::fmt(kRk4FastestRate) + " /s)";
  }
  c.reason = asked + (c.stiff ? ", stiff (" : ", not stiff (") + why + fast +
             "): " + method_text(c.options);
  return c;
}

}  // namespace mo2d
