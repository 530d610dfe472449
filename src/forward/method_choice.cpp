// choose_method: the integrator for an accuracy asked for (ForwardOptions::accuracy), explicit
// unless the mechanism is stiff at the initial state.
//
// Stiffness test. The run integrates y = (q0, q1), dy/dt = f(t, y) = (q1 head, a1(t, q0, q1)).
// An explicit Runge-Kutta method is stable for steps h with h lambda inside its stability region
// for every eigenvalue lambda of J = df/dy; the regions of rk4 (real interval 2.79, imaginary
// 2.83), dopri5 (real 3.3) and Fehlberg 8(7) all hold the half-disc of radius kStabilityBound =
// 2.5 to within their error control, so the run needs about
//   N_stab = |lambda|max T / kStabilityBound
// steps for stability, T = t1 - t0, and N_acc = T / h_acc for the accuracy, h_acc the step of the
// calibration (accuracy.cpp) on the double four-bar at that accuracy:
//   erk8 (accuracy >= 1e-5, tol = accuracy / 1000): h_acc = 0.08 s (tol / 1e-8)^(1/8) (127 steps
//        over 10 s at tol 1e-8, 62 at 1e-5; docs/performance.md "items 2 and 4"),
//   dopri5 (tol = accuracy / 1000): h_acc = 0.013 s (tol / 1e-9)^(1/5) (757 steps at 1e-9),
//   rk4: its fixed step.
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
constexpr double kBdfTolerancePerAccuracy = 1e-3;  // cvode_bdf: rtol = atol = accuracy x this

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

// The step the explicit method of options_for_accuracy needs for the accuracy (header comment).
double accuracy_step(const ForwardOptions& e) {
  switch (e.integrator) {
    case Integrator::erk8:
      return 0.08 * std::pow(e.rtol / 1e-8, 1.0 / 8);
    case Integrator::dopri5:
      return 0.013 * std::pow(e.rtol / 1e-9, 1.0 / 5);
    default:
      return e.step;
  }
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
  c.accuracy_steps = T / accuracy_step(c.options);
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
  if (c.stiff) {
    c.options.integrator = Integrator::cvode_bdf;
    c.options.rtol = c.options.atol = kBdfTolerancePerAccuracy * o.accuracy;
  }
  c.reason =
      asked + (c.stiff ? ", stiff (" : ", not stiff (") + why + "): " + method_text(c.options);
  return c;
}

}  // namespace mo2d
