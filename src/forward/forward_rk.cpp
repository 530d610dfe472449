// Forward dynamics: explicit Runge-Kutta drivers. rk4 (classical, fixed step), dopri5
// (Dormand-Prince 5(4), adaptive step), erk6 (Verner 6(5), 8 stages) and erk8 (Fehlberg 8(7), 13
// stages) project the state on the constraint manifolds after every step; baumgarte (RK4 with
// Baumgarte's velocity feedback, Mo2DPack's scheme) does not. The erk6/erk8 coefficients are
// SUNDIALS ARKODE's tables (ARKodeButcherTable_LoadERK); the loop is mo2d's, not ERKStep: ERKStep
// turns a recoverable right-hand-side failure into ARK_UNREC_RHSFUNC_ERR (it cannot redo a step
// whose stage falls on a singular instant, below, nor check the step's end point before accepting).
//
// Stepping over singular instants: where the constraint Jacobian loses rank, the accelerations are
// regularized and not accurate (ForwardData::accel_ok). The true motion is smooth through such an
// instant, so a step whose stages avoid it is accurate: a step with an inaccurate stage is redone
// shorter (its stages move), with the factors of kRetry in turn.
//
// Projected stages: a stage state is off the constraint manifolds by the stage's own error (O(h^2):
// explicit RK stages are first order). Near a singular instant the accelerations there are wrong
// by that deviation / sigma_min (the motion of a slightly violated constraint cannot pass the
// singular configuration at finite speed), an O(h^2) error whatever the method's order: erk8 at
// rtol 5e-9 saw error estimates of 1e4 on every straddling step and left the branch. A step whose
// stage is evaluated where the direct solve is refused (conditioning < kProjectBelow) is redone
// with every stage projected on the manifolds first: the step of y' = f(P(y)), a smooth ODE with
// the same solutions on the manifolds, so the method keeps its order, and the deviation enters
// through P only (second order in it in the degenerate direction).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "forward/forward_run.hpp"
#include "forward/rk_tableau.hpp"
#include "forward/step_failure.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/quasi_steady.hpp"
#include "run/run_budget.hpp"
#include "run/time_grid.hpp"

namespace mo2d::detail {
namespace {

// Step-length factors tried in turn when a stage falls on a singular instant: shorter ones first,
// varied so that no stage lands again where one failed; then longer ones, for steps too short to
// jump over the instant's neighbourhood (where the regularized accelerations are not accurate).
// Stages are projected in a step that evaluates one where the direct solve is refused
// (ForwardData::kDirectAccept: (sigma_min / sigma_max)^2 < 1e-2).
constexpr double kProjectBelow = ForwardData::kDirectAccept;

constexpr std::array<double, 11> kRetry = {0.5, 0.3, 0.7, 0.2, 0.85, 1.5, 2, 3, 4, 6, 8};

// One run of an explicit RK method. The state y = (q0, q1, the energy terms of EnergyTerm), the
// energy terms integrated by the same stages as the state.
class RkDriver {
 public:
  RkDriver(const Model& m, ForwardData& d, const ForwardOptions& o, Tableau tab)
      : m_(m),
        d_(d),
        o_(o),
        tab_(tab),
        budget_(forward_budget(m, d, o,
                               tab.embedded
                                   ? "loosen rtol/atol, or try cvode_bdf (stiff mechanisms)"
                                   : "use a longer step",
                               {kInputWork, kLoadWork, kConstraintWork, kDissipated})),
        n_(m.n0 + m.n1 + kEnergyTerms),
        q0_(m.n0),
        q1_(m.n1),
        y_stage_(n_),
        err_(n_),
        y_half_(n_),
        y_two_(n_) {
    for (auto& k : k_) k.resize(n_);
    k_start_.resize(n_);
    k_next_.resize(n_);
    project_ = o.integrator != Integrator::baumgarte;
    held_ = has_quasi_steady(m);
  }

  void run(const State& s0, Recorder& rec) {
    VectorXd y(n_), y_new(n_);
    y << s0.q0, s0.q1, VectorXd::Zero(kEnergyTerms);
    double t = o_.t0;
    growth_.emplace(m_, d_, t, s0.q0, s0.q1);
    record(rec, t, y);
    if (held_) held_start_ = save_held(m_);
    double g_prev = event(t, y);
    // adaptive: first step from the tolerance-free guess; the controller takes over from there
    double h = tab_.embedded ? std::min(1e-3, (o_.t1 - o_.t0) / 10) : o_.step;
    int k = 1;  // next output time
    auto output_time = [&](int i) { return sample_time(o_.t0, o_.t1, o_.samples, i); };
    while (k < o_.samples) {
      const double t_out = output_time(k);
      double hh;
      if (tab_.embedded) {  // free steps; the output times they pass are interpolated
        const double t_end = o_.t1;
        hh = std::min(h, t_end - t);
        if (t_end - t - hh < 1e-12 * std::max(1.0, std::abs(t_end))) hh = t_end - t;
      } else {  // fixed step: equal steps that end on the output time (their number is kept in
                // double: check_forward_options bounds the total by max_steps)
        const double nsteps = std::max(1.0, std::ceil((t_out - t) / o_.step - 1e-9));
        hh = (t_out - t) / nsteps;
      }
      double used = hh;
      advance(t, y, hh, h, y_new, used);
      if (held_) held_end_ = save_held(m_);  // the accepted step's (interpolations move them)
      if (o_.stop_when) {
        const double g = event(t + used, y_new);
        // a step that ends exactly on a root (g == 0) is an event there: taken as no sign change,
        // its g_prev = 0 hid every later crossing (a ball dropped 1 mm at 1 m/s with a first step
        // of 1 ms fell through the ground: tests/contact/compliant_test.cpp)
        if (g_prev != 0 && (g == 0 || (g_prev < 0) != (g < 0))) {
          locate_event(t, y, used, g_prev, g, y_new, rec, k);
          return;
        }
        g_prev = g;
      }
      const double t_new = (used == t_out - t) ? t_out : (used == o_.t1 - t) ? o_.t1 : t + used;
      // a step that jumped over a singular instant may pass output times: interpolate them
      while (k < o_.samples && output_time(k) < t_new)
        record_interpolated(rec, t, y, t_new, y_new, output_time(k++));
      if (k < o_.samples && output_time(k) == t_new) {
        record(rec, t_new, y_new);
        ++k;
      }
      if (!(t_new > t))  // cannot happen on the grid of run/time_grid.hpp: never loop on it
        throw Error("forward dynamics of '" + m_.name + "': no progress at t = " + fmt(t) +
                        " s (step " + fmt(used) + " s, output time " + fmt(t_out) +
                        " s): internal error, please report it",
                    m_.name, t);
      t = t_new;
      y.swap(y_new);
      if (held_) restore_held(m_, held_end_), held_start_.swap(held_end_);
      budget_.check(t, ++d_.stats.steps, used, y.data());
    }
    d_.stats.t_end = t;
    if (!budget_.stall_warning().empty() && d_.stats.warnings.size() < 20)
      d_.stats.warnings.push_back(budget_.stall_warning());
    // the tightest tolerance each method kept through the double four-bar's singular passages
    // (docs/performance.md): dopri5 5e-10; erk6 and erk8 1e-11 with projected stages (erk6 at
    // 1e-12 ended 1.1e-8 away, worse than at 1e-11)
    const double floor = tab_.order > 5 ? 1e-11 : 5e-10;
    if (tab_.embedded && d_.stats.regularized_evaluations > 0 && o_.rtol < floor &&
        d_.stats.warnings.size() < 20)
      d_.stats.warnings.push_back(
          "rtol " + fmt(o_.rtol) + " is below what " + to_string(o_.integrator) +
          " reaches next to singular configurations "
          "(the augmented Lagrangian's accelerations are accurate to ~1e-8 there): expect the "
          "error of rtol ~" +
          fmt(floor) + " or worse; use rk4 with a small step for more");
  }

 private:
  const Model& m_;
  ForwardData& d_;
  const ForwardOptions& o_;
  Tableau tab_;
  RunBudget budget_;
  int n_;
  bool project_ = true;
  double last_stepped_over_ = -std::numeric_limits<double>::infinity();
  std::array<VectorXd, kMaxStages> k_;
  VectorXd k_start_, k_next_;  // rates at the start of the next step (at the end of the last one)
  bool have_start_ = false;
  bool project_stages_ = false;
  VectorXd q0_, q1_, y_stage_, err_;
  VectorXd y_half_, y_two_;  // step doubling (step_through)
  // quasi-steady elements (mo2d/quasi_steady.hpp): their held cells at the accepted state every
  // step starts from, and at the accepted step's end
  bool held_ = false;
  HeldValues held_start_, held_end_;
  std::optional<LoadGrowth> growth_;  // named when the step collapses in the error test

  void split(const VectorXd& y) {
    q0_ = y.head(m_.n0);
    q1_ = y.segment(m_.n0, m_.n1);
  }
  // dy/dt at (t, y) into k; false if the accelerations are not accurate there
  bool derivative(double t, const VectorXd& y, VectorXd& k) {
    split(y);
    if (project_stages_) d_.project(t, q0_, q1_, 1e-13 * m_.scale, 1e-13 * m_.scale);
    d_.accelerations(t, q0_, q1_, !project_);
    k.head(m_.n0) = q1_.head(m_.n0);
    k.segment(m_.n0, m_.n1) = d_.a;
    energy_rates(d_, t, q0_, q1_, k.data() + m_.n0 + m_.n1);
    return d_.accel_ok;
  }
  // One step of length h from (t, y) into y_new (projected). Returns false if a stage was not
  // accurate. err: scaled error estimate (embedded methods), else 0.
  // check = false: every stage is evaluated afresh and used whatever its accuracy (the fallback
  // when a singular instant cannot be avoided, and the event search); returns true.
  bool step(double t, const VectorXd& y, double h, VectorXd& y_new, double& err,
            bool check = true) {
    bool ok = true;
    project_stages_ = false;
    if (held_) restore_held(m_, held_start_);  // every step starts from the accepted state (t, y)
    for (int i = 0; i < tab_.stages; ++i) {
      if (i == 0 && have_start_ &&
          check) {  // the rates at the start: evaluated when the last step ended
        k_[0] = k_start_;
        continue;
      }
      y_stage_ = y;
      for (int j = 0; j < i; ++j)
        if (tab_.a[i][j] != 0) y_stage_.noalias() += (h * tab_.a[i][j]) * k_[j];
      ok = derivative(t + tab_.c[i] * h, y_stage_, k_[i]) && ok;
      if (!project_stages_ && project_ && i > 0 && d_.eval_ratio < kProjectBelow) {
        // near a singular instant: redo the step's stages projected (k_[0] is at y, projected)
        project_stages_ = true;
        ok = true;
        i = 0;
        continue;
      }
      if (!ok && check) return false;
    }
    y_new = y;
    for (int i = 0; i < tab_.stages; ++i)
      if (tab_.b[i] != 0) y_new.noalias() += (h * tab_.b[i]) * k_[i];
    err = 0;
    if (tab_.embedded) {
      err_.setZero();
      for (int i = 0; i < tab_.stages; ++i)
        if (tab_.b[i] != tab_.bhat[i]) err_.noalias() += (h * (tab_.b[i] - tab_.bhat[i])) * k_[i];
      for (int j = 0; j < m_.n0 + m_.n1; ++j) {
        const double scale = o_.atol + o_.rtol * std::max(std::abs(y[j]), std::abs(y_new[j]));
        err = std::max(err, std::abs(err_[j]) / scale);
      }
    }
    if (project_) {
      split(y_new);
      d_.project(t + h, q0_, q1_, 1e-13 * m_.scale, 1e-13 * m_.scale);
      y_new.head(m_.n0) = q0_;
      y_new.segment(m_.n0, m_.n1) = q1_;
    }
    if (!check) return true;
    // the next step starts here: its first rates must be accurate too, or the next step could
    // not avoid the instant whatever its length
    project_stages_ = false;
    return derivative(t + h, y_new, k_next_);
  }
  // Take one accepted step from (t, y) with a first try of length hh; `used` returns the length
  // taken, h the controller's next step (adaptive).
  void advance(double t, const VectorXd& y, double hh, double& h, VectorXd& y_new, double& used) {
    const double t_limit = o_.t1;  // a longer step may pass output times (they are interpolated)
    const double h_first = hh;
    std::size_t retry = 0;
    for (;;) {
      double err = 0;
      const bool ok = step(t, y, hh, y_new, err);
      if (!ok) {
        // a stage fell on a singular instant: shorten the step so that its stages move
        if (retry < kRetry.size()) {
          ++d_.stats.stepped_over;
          hh = std::min(h_first * kRetry[retry++], t_limit - t);
          continue;
        }
        step_through(t, y, hh, h_first * *std::min_element(kRetry.begin(), kRetry.end()), y_new);
        used = hh;
        return;
      }
      if (retry > 0 && d_.stats.warnings.size() < 20 && t > last_stepped_over_ + 10 * h_first) {
        d_.stats.warnings.push_back("stepped over a singular configuration near t = " + fmt(t) +
                                    " s (the constraint Jacobian loses rank there)");
        last_stepped_over_ = t;
      }
      if (!tab_.embedded) {
        used = hh;
        k_start_.swap(k_next_);
        have_start_ = true;
        return;
      }
      const double factor =
          err > 0 ? 0.9 * std::pow(err, -1.0 / (std::min(tab_.order, tab_.embedded_order) + 1))
                  : 5.0;  // elementary controller
      // Next to a singular instant the accelerations are accurate to ~1e-8 relative only (the
      // augmented Lagrangian's floor), so a step that straddles the instant can show an error
      // estimate of a few tolerances whatever its length (seen: ~3 from h = 2e-3 to 1e-2 s at
      // tol 3e-9): while stepping over, accept up to 10 rather than shrink into the instant.
      if (err <= (retry > 0 ? 10.0 : 1.0)) {
        used = hh;
        k_start_.swap(k_next_);
        have_start_ = true;
        // the next step grows from the step just taken, unless that one was clipped short
        h = std::max(h, hh) == hh ? hh * std::clamp(factor, 0.2, 5.0) : h;
        return;
      }
      ++d_.stats.error_test_failures;
      hh *= std::clamp(factor, 0.1, 0.9);
      h = hh;
      if (hh < 1e-14 * std::max(1.0, std::abs(t)))
        throw Error("forward dynamics of '" + m_.name + "': step size too small at t = " + fmt(t) +
                        " s (error test)" +
                        growth_->describe(t, y.head(m_.n0), y.segment(m_.n0, m_.n1)),
                    m_.name, t);
    }
  }

  // No retry avoided the instant: the longest try hh is taken, its error estimated (embedded pair,
  // or step doubling / (2^p - 1)) on rtol/atol and reported. At rtol 1e-10/1e-11 on the double
  // four-bar these are 1e2 to 1e6 x tol (accelerations accurate to ~1e-8 there; the runs end 5e-9
  // to 3e-8 away): only |e| / (atol / rtol + |y|) > kGrossStep is an error (a branch may be lost).
  static constexpr double kGrossStep = 1e-3;
  void step_through(double t, const VectorXd& y, double hh, double h_min, VectorXd& y_new) {
    d_.accel_ok = true;
    double err = 0;
    step(t, y, hh, y_new, err, false);
    if (!tab_.embedded) {  // step doubling
      step(t, y, hh / 2, y_half_, err, false);
      step(t + hh / 2, y_half_, hh / 2, y_two_, err, false);
      err_ = (y_new - y_two_) / (std::pow(2.0, tab_.order) - 1);
    }
    have_start_ = false;
    int worst = 0;
    err = 0;
    for (int j = 0; j < m_.n0 + m_.n1; ++j) {
      const double e =
          std::abs(err_[j]) / (o_.atol + o_.rtol * std::max(std::abs(y[j]), std::abs(y_new[j])));
      if (!(e <= err)) err = e, worst = j;
    }
    const auto& var = worst < m_.n0 ? m_.coordinate_labels[worst] : m_.rate_labels[worst - m_.n0];
    const std::string w = "could not step over a singular configuration near t = " + fmt(t) +
                          " s (steps of " + fmt(h_min) + " to " + fmt(hh) +
                          " s all meet it); error estimate of the " + fmt(hh) + " s step " +
                          fmt(err) + " times rtol/atol, largest in '" + var + "'";
    if (!(err * o_.rtol <= kGrossStep)) {
      const std::string stiff = stiffness_cause(
          m_, o_, d_, State{t, y.head(m_.n0), y.segment(m_.n0, m_.n1)}, h_min, kProjectBelow);
      if (!stiff.empty())
        throw Error("forward dynamics of '" + m_.name + "': no step of " + fmt(h_min) + " to " +
                        fmt(hh) + " s from t = " + fmt(t) + " s is accurate: " + stiff,
                    m_.name, t);
      throw Error("forward dynamics of '" + m_.name + "': " + w + ", gross (" + fmt(err * o_.rtol) +
                      " relative): try other tolerances or another method",
                  var, t);
    }
    if (d_.stats.warnings.size() < 20) d_.stats.warnings.push_back(w + "; step taken");
  }

  // State at an output time t_s inside the accepted step (t, y) -> (t1, y1), recorded. First
  // choice: one step of the method itself from (t, y) to t_s, as accurate as the run. If that step
  // falls on a singular instant: Hermite interpolation (quintic for q0 from q0, its rates and
  // accelerations; cubic for q1, the work and the dissipated energy from their values and rates),
  // projected on the constraint manifolds.
  void record_interpolated(Recorder& rec, double t, const VectorXd& y, double t1,
                           const VectorXd& y1, double t_s) {
    {
      const bool had_start = have_start_;  // k_start_ belongs to t1: not the rates at t
      have_start_ = false;
      VectorXd ys(n_);
      double err = 0;
      const bool ok = step(t, y, t_s - t, ys, err);
      have_start_ = had_start;
      if (ok) {
        record(rec, t_s, ys);
        return;
      }
    }
    VectorXd& f0 = k_[0];  // rates at both ends (k_ is free between steps)
    VectorXd& f1 = k_[1];
    derivative(t, y, f0);
    const VectorXd a0 = d_.a;
    derivative(t1, y1, f1);
    const VectorXd a1 = d_.a;
    const double h = t1 - t, s = (t_s - t) / h;
    const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    // cubic Hermite basis
    const double c00 = 2 * s3 - 3 * s2 + 1, c10 = s3 - 2 * s2 + s, c01 = -2 * s3 + 3 * s2,
                 c11 = s3 - s2;
    VectorXd ys = c00 * y + c01 * y1 + (h * c10) * f0 + (h * c11) * f1;
    // quintic Hermite basis for the positions
    const double q00 = 1 - 10 * s3 + 15 * s4 - 6 * s5, q10 = s - 6 * s3 + 8 * s4 - 3 * s5,
                 q20 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), q01 = 10 * s3 - 15 * s4 + 6 * s5,
                 q11 = -4 * s3 + 7 * s4 - 3 * s5, q21 = 0.5 * (s3 - 2 * s4 + s5);
    const int n0 = m_.n0;
    ys.head(n0) = q00 * y.head(n0) + q01 * y1.head(n0) + (h * q10) * f0.head(n0) +
                  (h * q11) * f1.head(n0) + (h * h * q20) * a0.head(n0) +
                  (h * h * q21) * a1.head(n0);
    if (project_) {
      split(ys);
      d_.project(t_s, q0_, q1_, 1e-13 * m_.scale, 1e-13 * m_.scale);
      ys.head(m_.n0) = q0_;
      ys.segment(m_.n0, m_.n1) = q1_;
    }
    record(rec, t_s, ys);
  }
  double event(double t, const VectorXd& y) {
    if (!o_.stop_when) return 1.0;
    split(y);
    return o_.stop_when(t, q0_, q1_);
  }
  void record(Recorder& rec, double t, const VectorXd& y) {
    split(y);
    const VectorXd q0 = q0_, q1 = q1_;
    rec.record(t, q0, q1, y.data() + m_.n0 + m_.n1);
  }
  // The stop condition changed sign over the step (t, t + h] (y_hi: the step's end): locate the
  // crossing by the secant method on the step length (each try redoes the step from (t, y)),
  // record it and stop. Illinois variant: an end kept twice has its value halved (plain regula
  // falsi stalls at one end of a convex or nearly flat condition, e.g. the span lengths of an
  // inextensible chain). An iteration that did not halve the bracket is followed by a bisection:
  // at a jump of the condition (a torque step) from a small value to a large one of the other
  // sign the secant point stays next to the small end, and Illinois alone took more than 60 tries
  // to get the bracket from 1e-2 s to 1e-7 s. The state recorded is the bracket's far end, where
  // the condition has changed sign (as CVODE's root finding returns): at a jump the near end is
  // before it, where the caller sees no crossing.
  void locate_event(double t, const VectorXd& y, double h, double g_lo, double g_hi,
                    const VectorXd& y_hi, Recorder& rec, int k) {
    double lo = 0, hi = h;
    VectorXd y_try(n_), y_best = y_hi;
    double t_best = t + h;
    HeldValues held_best = held_end_;  // the cells of the best try (the step's end: y_hi)
    int kept = 0;                      // -1: lo moved last, +1: hi moved last
    bool bisect = false;
    for (int it = 0; it < 120; ++it) {
      const double width = hi - lo;
      const double mid = bisect ? lo + 0.5 * width : lo + width * g_lo / (g_lo - g_hi);
      double err = 0;
      step(t, y, mid, y_try, err, false);
      const double g = event(t + mid, y_try);
      if ((g < 0) != (g_lo < 0) || g == 0) {
        y_best = y_try, t_best = t + mid;
        if (held_) held_best = save_held(m_);
      }
      if ((g < 0) == (g_lo < 0)) {
        lo = mid, g_lo = g;
        if (kept == -1) g_hi /= 2;
        kept = -1;
      } else {
        hi = mid, g_hi = g;
        if (kept == 1) g_lo /= 2;
        kept = 1;
      }
      if (std::abs(hi - lo) < 1e-13 * std::max(1.0, std::abs(t)) || g == 0) break;
      bisect = hi - lo > 0.5 * width;
    }
    d_.stats.stopped_by_event = true;
    d_.stats.t_end = t_best;
    // output times the step passed before the event (a free step of an embedded pair)
    for (; k < o_.samples; ++k) {
      const double t_out = sample_time(o_.t0, o_.t1, o_.samples, k);
      if (!(t_out < t_best)) break;
      record_interpolated(rec, t, y, t_best, y_best, t_out);
    }
    if (held_) restore_held(m_, held_best);  // the run goes on from the located state
    record(rec, t_best, y_best);
  }
};

}  // namespace

void run_explicit_rk(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
                     Recorder& rec) {
  RkDriver driver(m, d, o, tableau(o.integrator));
  driver.run(s0, rec);
}

}  // namespace mo2d::detail
