// Limits of a run: time grid, memory estimates, step and wall-clock budgets (mo2d/budget.hpp).
#include "mo2d/budget.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "kinematics/sparse_kinematics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/model.hpp"
#include "mo2d/run_stop.hpp"
#include "run/format.hpp"
#include "run/run_budget.hpp"

namespace mo2d {

namespace detail {
std::string fmt(double v) {
  return fmt(v, 6);
}
std::string fmt(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}
}  // namespace detail

namespace {
using detail::fmt;
std::string gigabytes(double bytes) {
  std::ostringstream s;
  s.precision(3);
  s << bytes / 1e9 << " GB";
  return s.str();
}
}  // namespace

namespace {
std::atomic<InterruptCheck> the_interrupt_check{nullptr};
}  // namespace

void set_interrupt_check(InterruptCheck check) {
  the_interrupt_check.store(check);
}

InterruptCheck interrupt_check() {
  return the_interrupt_check.load();
}

void poll_interrupt() {
  if (const InterruptCheck f = the_interrupt_check.load(); f != nullptr && f()) throw Interrupted();
}

void check_time_grid(const char* run, double t0, double t1, long long samples) {
  if (!std::isfinite(t0))
    throw Error(std::string(run) + ": t0 = " + fmt(t0) + " is not finite", "t0");
  if (!std::isfinite(t1))
    throw Error(std::string(run) + ": the end time t0 + duration = " + fmt(t1) + " is not finite",
                "t1");
  if (samples < 2) return;
  const double spacing = (t1 - t0) / static_cast<double>(samples - 1);
  const double tmax = std::max(std::abs(t0), std::abs(t1));
  if (!(spacing >= kTimeResolution * tmax))
    throw Error(std::string(run) + ": t0 = " + fmt(t0) + " s: " + std::to_string(samples) +
                    " samples over [" + fmt(t0) + ", " + fmt(t1) + "] s, " + fmt(spacing) +
                    " s apart, are not resolved by double precision there (doubles are " +
                    fmt(std::nextafter(tmax, INFINITY) - tmax) + " s apart near t = " + fmt(tmax) +
                    " s; the spacing must be at least " + fmt(kTimeResolution * tmax) +
                    " s): use a t0 closer to 0, or fewer samples",
                "t0");
}

void check_memory(const std::string& what, double bytes, double limit, const std::string& sizes,
                  const std::string& setting) {
  if (limit > 0 && !(bytes <= limit))
    throw Error(what + " needs about " + gigabytes(bytes) + " of dense matrices (" + sizes +
                    "), more than the limit of " + gigabytes(limit) + " (" + setting +
                    "): the mechanism is too large for mo2d's dense solvers",
                setting);
}

double build_memory_bytes(int n0, int m0, int n1, int m1) {
  // large models: sparse Jacobians and QR factors (kinematics/sparse_kinematics.hpp), O(n) for a
  // chain; 2 kB per variable and row is a generous bound
  if (n1 + m1 >= detail::kSparseKinematics) return 2048.0 * (n0 + m0 + n1 + m1);
  // assemble: J (m0 x n0) and its complete orthogonal decomposition (a copy and Householder
  // coefficients); rank checks: Psi, A and the QR of their transposes
  const double d0 = static_cast<double>(m0) * n0, d1 = static_cast<double>(m1) * n1;
  return 8.0 * (4 * d0 + 2 * d1);
}

double conditioning_memory_bytes(const Model& m) {
  if (detail::sparse_kinematics(m)) return 2048.0 * (m.m1 + m.n1);  // sparse QR and LDL^T
  // A (m1 x n1), the SVD's working copy and its QR preconditioner
  return 8.0 * 3 * static_cast<double>(m.m1) * m.n1;
}

void check_magnitudes(const Model& m) {
  const double g = std::max(1.0, std::hypot(m.gravity.x(), m.gravity.y()));
  const double L2 = std::max(1.0, m.scale) * std::max(1.0, m.scale);
  auto refuse = [&](const std::string& what, const std::string& name, const char* quantity,
                    double value, const char* unit, double scale, const char* product) {
    if (std::isfinite(value) && std::abs(value) * scale <= kMaxMagnitude) return;
    throw Error(what + " '" + name + "': " + quantity + " " + fmt(value) + " " + unit +
                    " is out of range: " + product + " = " + fmt(std::abs(value) * scale) +
                    " exceeds " + fmt(kMaxMagnitude) +
                    ", beyond what double precision carries through a run (forces and energies "
                    "overflow to inf, efforts to NaN)",
                name);
  };
  for (const auto& b : m.bodies) {
    refuse("body", b.name, "mass", b.mass, "kg", g * L2, "m max(1, |g|) max(1, L)^2");
    refuse("body", b.name, "inertia", b.inertia, "kg m^2", g, "I max(1, |g|)");
  }
  for (const auto& s : m.springs) {
    refuse("spring", s.name, "stiffness", s.stiffness, "N/m", L2, "k max(1, L)^2");
    refuse("spring", s.name, "damping", s.damping, "N s/m", L2, "c max(1, L)^2");
  }
  for (const auto& s : m.torsional_springs) {
    refuse("torsional spring", s.name, "stiffness", s.stiffness, "N m/rad", 1, "k");
    refuse("torsional spring", s.name, "damping", s.damping, "N m s/rad", 1, "c");
  }
  // gravity: the accelerations it gives are squared (kinetic energies, the integrators' error
  // norms), so |g| max(1, L) is held below the square root of the limit (g = 1e200 m/s^2 passed
  // the bodies' checks with a mass of 1 kg, then overflowed in the first step)
  const double gl = std::hypot(m.gravity.x(), m.gravity.y()) * std::max(1.0, m.scale);
  if (!(gl <= std::sqrt(kMaxMagnitude)))
    throw Error("gravity (" + fmt(m.gravity.x()) + ", " + fmt(m.gravity.y()) +
                    ") m/s^2 is out of range: |g| max(1, L) = " + fmt(gl) + " exceeds " +
                    fmt(std::sqrt(kMaxMagnitude)) + " = sqrt(" + fmt(kMaxMagnitude) +
                    "), beyond what double precision carries through a run (the squares of "
                    "accelerations and velocities overflow to inf)",
                "gravity");
}

std::string model_sizes(const Model& m) {
  return "n0 = " + std::to_string(m.n0) + " coordinates, n1 = " + std::to_string(m.n1) +
         " quasi-velocities, " + std::to_string(m.m0) + " + " + std::to_string(m.m1) +
         " constraint rows";
}

namespace detail {

RunBudget::RunBudget(Settings s) : s_(std::move(s)) {
  start_ = wall_seconds();
  next_report_ = start_ + s_.interval;
  next_poll_ = start_ + kInterruptPoll;
}

double RunBudget::elapsed() const {
  return wall_seconds() - start_;
}

bool RunBudget::out_of_time() const {
  return s_.max_seconds > 0 && std::isfinite(s_.max_seconds) && elapsed() > s_.max_seconds;
}

void RunBudget::check(double t, long steps, double step_size, const double* y) {
  if (s_.max_steps > 0 && steps > s_.max_steps) throw_exhausted(t, steps, step_size);
  check_collapse(t, steps, step_size, y);
  const double now = wall_seconds();
  if (s_.max_seconds > 0 && std::isfinite(s_.max_seconds) && now - start_ > s_.max_seconds)
    throw_exhausted(t, steps, step_size);
  if (now >= next_poll_) {
    next_poll_ = now + kInterruptPoll;
    poll_interrupt();
  }
  if (now < next_report_) return;
  next_report_ = now + s_.interval;
  // a collapsed step size, judged at report times only (not in a run's first second nor at its
  // first steps, where the integrator's start-up steps are small)
  const bool collapsed =
      steps > 10 && step_size > 0 && step_size < RunProgress::stall_ratio * (s_.t1 - s_.t0);
  if (collapsed && !stalled_)
    stall_warning_ = "the step size collapsed to " + fmt(step_size) + " s at t = " + fmt(t) +
                     " s after " + std::to_string(steps) + " steps (below " +
                     fmt(RunProgress::stall_ratio) +
                     " of the run's duration): the run may not finish within its budget";
  stalled_ = stalled_ || collapsed;
  if (s_.monitor) {
    RunProgress p;
    p.t = t;
    p.t0 = s_.t0;
    p.t1 = s_.t1;
    p.steps = steps;
    p.step_size = step_size;
    p.seconds = now - start_;
    p.stalled = collapsed;
    s_.monitor(p);
  }
}

namespace {
// Two kinds of collapse of the step size, each judged after the run's first kStartSteps steps
// (an integrator's start-up steps are small):
// - sudden: a step below kCollapseRatio x the recent accepted steps (their maximum, decaying by
//   kRefDecay per accepted step that is not itself collapsed), for kSustain checks in a row and
//   kSustainSteps accepted steps, with no healthy step (kHealthy x the recent ones) between: the
//   40-loop four-bar chain on cvode_bdf went from 1e-3 s steps to 1e-8 ... 1e-14 s. A legitimate
//   singular passage on cvode_bdf takes steps of 1e-6 to 1e-8 s among 1e-3 s ones: 1e-5 of the
//   recent steps and above, far from the ratio.
// - steady: a step so short that the rest of the run would need more than kHopeless x max_steps
//   steps, over 1000 checks and 1000 accepted steps in a row, and still shrinking (halved since
//   the first of them): a motion that speeds up without bound (the steps shrink a little each,
//   and the recent ones with them). A singular passage's short steps do not shrink on: the
//   double four-bar on cvode_bdf under a step budget of 2e5 takes > 100 steps near 3e-8 s.
constexpr double kCollapseRatio = 1e-9, kHealthy = 1e-3, kRefDecay = 0.97, kHopeless = 10;
constexpr long kStartSteps = 10, kSustain = 100, kSustainSteps = 10;
}  // namespace

void RunBudget::check_collapse(double t, long steps, double step_size, const double* y) {
  if (!(step_size > 0)) return;
  const bool tiny = step_size < kCollapseRatio * ref_step_;
  if (steps > last_steps_) {  // accepted steps since the last check
    if (!tiny)
      ref_step_ =
          std::max(step_size, ref_step_ * std::pow(kRefDecay, static_cast<double>(std::min(
                                                                  steps - last_steps_, 1000L))));
    last_steps_ = steps;
  }
  if (steps < kStartSteps) return;
  const double remaining = s_.t1 - t;
  const bool hopeless = s_.max_steps > 0 && remaining > kHopeless * s_.max_steps * step_size;
  if (!tiny && step_size >= kHealthy * ref_step_) tiny_checks_ = 0;
  if (tiny && tiny_checks_++ == 0) tiny_from_ = steps;
  if (!hopeless) hopeless_checks_ = 0;
  if (hopeless && hopeless_checks_++ == 0) hopeless_from_ = steps, hopeless_step_ = step_size;
  const bool sudden = tiny && tiny_checks_ >= kSustain && steps - tiny_from_ >= kSustainSteps;
  const bool steady = hopeless && hopeless_checks_ >= 10 * kSustain &&
                      steps - hopeless_from_ >= 100 * kSustainSteps &&
                      step_size <= 0.5 * hopeless_step_;
  if (!sudden && !steady) return;
  std::ostringstream m;
  m << s_.run << ": the step size collapsed to " << fmt(step_size) << " s at t = " << fmt(t)
    << " s after " << steps << " " << s_.unit;
  if (sudden)
    m << " (" << fmt(step_size / ref_step_) << " of the steps just before, " << fmt(ref_step_)
      << " s)";
  else
    m << " (at that size the remaining " << fmt(remaining) << " s need "
      << fmt(remaining / step_size) << " steps, more than " << fmt(kHopeless)
      << " x the step budget of " << s_.max_steps << ")";
  const std::string cause = s_.collapse_cause ? s_.collapse_cause(t, y) : std::string();
  if (!cause.empty())
    m << ": " << cause;
  else if (!s_.hint.empty())
    m << "; " << s_.hint;
  throw Error(m.str(), s_.name, t);
}

void RunBudget::throw_exhausted(double t, long steps, double step_size) const {
  const double secs = elapsed();
  const bool time_out = s_.max_seconds > 0 && secs > s_.max_seconds;
  std::ostringstream m;
  m << s_.run << ": ";
  if (time_out)
    m << "the wall-time budget of " << fmt(s_.max_seconds) << " s ran out";
  else
    m << "the step budget of " << s_.max_steps << " steps ran out";
  m << " at t = " << fmt(t) << " s";
  if (s_.t1 > s_.t0) m << " of [" << fmt(s_.t0) << ", " << fmt(s_.t1) << "] s";
  m << ", after " << steps << " " << s_.unit << " in " << fmt(secs) << " s";
  if (step_size > 0) m << " (last step " << fmt(step_size) << " s)";
  m << "; raise "
    << (time_out ? "max_seconds (scene run.max_seconds, mo2d --max-seconds)"
                 : "max_steps (scene run.max_steps, mo2d --max-steps)");
  if (!s_.hint.empty()) m << ", or " << s_.hint;
  throw BudgetExhausted(m.str(), s_.name, t);
}

}  // namespace detail
}  // namespace mo2d
