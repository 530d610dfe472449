// Forward dynamics: SUNDIALS CVODE driver (BDF with projection, Adams).
#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>
#include <vector>

#include "forward/cvode_hop.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/jacobian.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/run_stop.hpp"
#include "run/run_budget.hpp"
#include "run/time_grid.hpp"

namespace mo2d::detail {
namespace {

struct CvodeUser {
  const Model* m;
  ForwardData* d;
  VectorXd q0, q1;
  std::vector<int> terms;  // the EnergyTerms carried after (q0, q1), in order
  bool baumgarte = false;
  std::string last_error;  // message of the last failed right-hand side evaluation
  RunBudget* budget = nullptr;
  void* mem = nullptr;    // the CVODE solver (step counts for the budget)
  long steps_before = 0;  // the steps before CVODE's last restart (CVodeReInit counts from 0)
  // thrown inside a callback and kept to be rethrown once CVode has returned (no exception may
  // unwind through CVODE's C frames): the budget's Error, the monitor's own, or a failure of user
  // code (guarded)
  std::exception_ptr kept;
  AccelerationJacobian jac;  // the last Newton matrix's d a1 / d (q0, q1)
  MatrixXd energy_rows;      // its energy rows: d rates / d (q0, q1), terms x (n0 + n1)
  const ForwardOptions* o = nullptr;
  HopWatch hops;  // singular passages handed to rk4 (cvode_hop.hpp)
};

// The budget is checked at every right-hand side evaluation (a single output interval can take
// arbitrarily long); when it runs out the evaluation fails unrecoverably and run_cvode rethrows.
bool budget_ok(CvodeUser* u, const double* y) {
  long steps = 0;
  double h = 0, t = 0;
  CVodeGetNumSteps(u->mem, &steps);
  steps += u->steps_before;
  CVodeGetCurrentStep(u->mem, &h);
  CVodeGetCurrentTime(u->mem, &t);  // the time reached (not the stage's trial time)
  if (u->hops.due(h, steps, u->d->stats.regularized_evaluations, u->d->stats.rhs_evaluations)) {
    u->hops.wanted = true;  // unrecoverable: CVode returns, advance() hops (cvode_hop.cpp)
    return false;
  }
  try {
    u->budget->check(t, steps, h, y);
  } catch (...) {  // the budget's Error, or the monitor's own: not through CVODE's C frames
    u->kept = std::current_exception();
    return false;
  }
  return true;
}

// f() inside a CVODE callback, no exception leaving it: an Error of the state (a value not
// finite, a singular solve) returns 1, recoverable (CVODE retries with a smaller step; the
// message in last_error); any other exception, and an Error that carries one (user code inside a
// law, nested by call_law: a Python callable's exception, which a retry would only raise again),
// is kept (CvodeUser::kept) and returns -1, unrecoverable: run_cvode rethrows it. Once one is
// kept every later callback returns -1 at once: CVODE does not always stop at the first -1 (with
// SUNDIALS 6.4.1, cvode_adams' fixed-point solver retried the step with smaller and smaller
// steps), and the failing code must not be called again.
template <class F>
int guarded(CvodeUser* u, F&& f) {
  if (u->kept) return -1;
  try {
    return f();
  } catch (const Error& e) {
    const auto* nested = dynamic_cast<const std::nested_exception*>(&e);
    if (nested == nullptr || !nested->nested_ptr()) {
      u->last_error = e.what();
      return 1;
    }
    u->kept = std::current_exception();
  } catch (...) {
    u->kept = std::current_exception();
  }
  return -1;
}

// y' = (q1.head(n0), a1, energy rates) at (t, y) into out: 0, 1 (recoverable: the message in
// last_error) or -1 (an exception kept: guarded).
int evaluate_rhs(CvodeUser* u, double t, const double* yd, double* out) {
  const Model& m = *u->m;
  u->q0 = Eigen::Map<const VectorXd>(yd, m.n0);
  u->q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
  double rates[kEnergyTerms];
  if (const int flag = guarded(u, [&] {
        u->d->accelerations(t, u->q0, u->q1, u->baumgarte);
        energy_rates(*u->d, t, u->q0, u->q1, rates);
        return 0;
      }))
    return flag;
  Eigen::Map<VectorXd>(out, m.n0) = u->q1.head(m.n0);
  Eigen::Map<VectorXd>(out + m.n0, m.n1) = u->d->a;
  for (size_t k = 0; k < u->terms.size(); ++k) out[m.n0 + m.n1 + k] = rates[u->terms[k]];
  for (int k = 0; k < m.n1; ++k)
    if (!std::isfinite(u->d->a[k])) {  // recoverable: a shorter step may stay in range
      u->last_error =
          "the acceleration " + m.rate_labels[k] + ".dot is not finite at t = " + fmt(t) + " s";
      return 1;
    }
  return 0;
}

int cv_rhs(realtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  if (!budget_ok(u, N_VGetArrayPointer(y))) return -1;  // unrecoverable: the run stops
  return evaluate_rhs(u, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

// Forward difference quotients of the whole right-hand side (CVODE's own scheme, increments
// sqrt(eps) max(|y_j|, atol)): the Newton matrix where the accelerations are regularized (next to
// a singular configuration), so that it is the derivative of what is integrated there.
int difference_quotients(CvodeUser* u, double t, N_Vector y, N_Vector fy, SUNMatrix J) {
  const sunindextype n = N_VGetLength(y);
  const double* yd = N_VGetArrayPointer(y);
  const double* f0 = N_VGetArrayPointer(fy);
  std::vector<double> yp(yd, yd + n), fp(n);
  for (sunindextype j = 0; j < n; ++j) {
    const double h = std::sqrt(DBL_EPSILON) * std::max(std::abs(yd[j]), u->d->o.atol);
    yp[j] = yd[j] + h;
    if (const int flag = evaluate_rhs(u, t, yp.data(), fp.data())) return flag;
    yp[j] = yd[j];
    double* col = SUNDenseMatrix_Column(J, j);
    for (sunindextype i = 0; i < n; ++i) col[i] = (fp[i] - f0[i]) / h;
  }
  return 0;
}

// The Jacobian of y' = (q1.head(n0), a1(t, q0, q1), energy rates) for BDF's Newton matrix:
//   [0, [I 0], 0;  da/dq0, da/dq1, 0;  0, 0, 0]
// with da/dq0, da/dq1 from acceleration_jacobian and the energy rows from energy_rate_jacobian
// (exact directional derivatives); where the evaluation is regularized (a singular configuration
// near), difference quotients of what is integrated there.
int cv_jac(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user, N_Vector /*tmp1*/,
           N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  const double* yd = N_VGetArrayPointer(y);
  u->q0 = Eigen::Map<const VectorXd>(yd, m.n0);
  u->q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
  bool quotients = false;
  if (const int flag = guarded(u, [&] {
        acceleration_jacobian(*u->d, t, u->q0, u->q1, u->jac);
        quotients = u->jac.singular;
        if (!quotients)
          energy_rate_jacobian(*u->d, t, u->q0, u->q1, u->jac, u->terms, u->energy_rows);
        return 0;
      }))
    return flag;
  if (quotients) return difference_quotients(u, t, y, fy, J);
  if (!u->jac.da_dq0.allFinite() || !u->jac.da_dq1.allFinite()) {
    u->last_error = "the Jacobian of the accelerations is not finite at t = " + fmt(t) + " s";
    return 1;
  }
  SUNMatZero(J);
  for (int k = 0; k < m.n0; ++k) SM_ELEMENT_D(J, k, m.n0 + k) = 1.0;
  for (int j = 0; j < m.n0; ++j)
    for (int i = 0; i < m.n1; ++i) SM_ELEMENT_D(J, m.n0 + i, j) = u->jac.da_dq0(i, j);
  for (int j = 0; j < m.n1; ++j)
    for (int i = 0; i < m.n1; ++i) SM_ELEMENT_D(J, m.n0 + i, m.n0 + j) = u->jac.da_dq1(i, j);
  for (int j = 0; j < m.n0 + m.n1; ++j)
    for (Eigen::Index r = 0; r < u->energy_rows.rows(); ++r)
      SM_ELEMENT_D(J, m.n0 + m.n1 + r, j) = u->energy_rows(r, j);
  return 0;
}

int cv_proj(realtype t, N_Vector ycur, N_Vector corr, realtype eps, N_Vector err, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  ForwardData& d = *u->d;
  const double* y = N_VGetArrayPointer(ycur);
  double* c = N_VGetArrayPointer(corr);
  VectorXd q0 = Eigen::Map<const VectorXd>(y, m.n0),
           q1 = Eigen::Map<const VectorXd>(y + m.n0, m.n1);
  const VectorXd q0s = q0, q1s = q1;
  // Project well below the solver's own tolerance: CVODE measures the correction in its error
  // weights (1 / (rtol |y| + atol)), so a projection left at a looser level than atol makes every
  // step look inaccurate and drives the step size to zero. (eps: CVODE's projection tolerance.)
  (void)eps;
  const double tol = std::max(1e-3 * d.o.atol, 4e-16 * m.scale);
  if (const int flag = guarded(u, [&] {
        d.project(t, q0, q1, tol, tol);
        return 0;
      }))
    return flag;
  Eigen::Map<VectorXd>(c, m.n0) = q0 - q0s;
  Eigen::Map<VectorXd>(c + m.n0, m.n1) = q1 - q1s;

  std::fill(c + m.n0 + m.n1, c + N_VGetLength(corr), 0.0);
  if (err) {  // project the error estimate on the tangent spaces
    double* e = N_VGetArrayPointer(err);
    Eigen::Map<VectorXd> e0(e, m.n0), e1(e + m.n0, m.n1);
    if (m.m0) {
      position_jacobian(m, q0, t, d.psi, d.Psi);
      e0 -= d.Psi.transpose() * regularized_normal_solve(d.Psi, e0, 1e-13);
    }
    if (m.m1) {
      velocity_jacobian(m, q0, t, d.A, d.b);
      e1 -= d.A.transpose() * regularized_normal_solve(d.A, e1, 1e-13);
    }
  }
  return 0;
}

int cv_root(realtype t, N_Vector y, realtype* g, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  const double* yd = N_VGetArrayPointer(y);
  const VectorXd q0 = Eigen::Map<const VectorXd>(yd, m.n0);
  const VectorXd q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
  if (u->kept) return -1;
  try {
    g[0] = u->d->o.stop_when(t, q0, q1);
  } catch (...) {  // kept, rethrown by run_cvode (a root function's failure is unrecoverable)
    u->kept = std::current_exception();
    return -1;
  }
  return 0;
}

// CVODE's messages go to the run's warnings, not to stderr.
void cv_error_handler(int code, const char* module, const char* function, char* msg, void* data) {
  auto* stats = static_cast<RunStats*>(data);
  if (stats->warnings.size() < 20)
    stats->warnings.push_back(std::string(code < 0 ? "error" : "warning") + " in " + module + " " +
                              function + ": " + msg);
}

struct SundialsDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};

void check_flag(int flag, const char* call, double t) {
  if (flag < 0)
    throw Error(std::string("SUNDIALS ") + call + " failed (flag " + std::to_string(flag) +
                    ") at t = " + fmt(t),
                call, t);
}

// Restarts of CVODE in one output interval after its error test failed repeatedly (flag -3).
constexpr int kRestarts = 2;

// The restarts of a run and the counters that CVodeReInit resets, carried over them.
struct Restarts {
  int count = 0;
  double first = 0;                                // s, the first one's time
  long failures = 0, setups = 0, projections = 0;  // error-test failures, factorizations
};

// CVODE restarted at (t, y), the last step it reached, after its error test failed 7 times on
// the next step (flag -3): a jump of the loads just past t (the half-bike's brake at 10 s, where
// the output time before it was 10 - 1.8e-15 s by rounding: outputs every 2e-4 s at rtol 1e-10).
// CVODE's own recovery cuts the step by at most 10 per failure and restarts at order 1 from
// f(t), the loads before the jump, so every try still steps across it with the error of
// h times the jump. A restart (CVodeReInit) picks its first step from f at t and at a trial
// step past the jump: it goes across with a step short enough. The CVODE message of the failure
// is replaced by one line of the restarts at the run's end.
void reinit(CvodeUser& u, double t, N_Vector y, double t_out, Restarts& r) {
  long v = 0;
  CVodeGetNumSteps(u.mem, &v);
  u.steps_before += v;
  CVodeGetNumErrTestFails(u.mem, &v);
  r.failures += v;
  if (CVodeGetNumLinSolvSetups(u.mem, &v) == CV_SUCCESS) r.setups += v;
  if (CVodeGetNumProjEvals(u.mem, &v) == CV_SUCCESS) r.projections += v;
  check_flag(CVodeReInit(u.mem, t, y), "CVodeReInit", t);
  check_flag(CVodeSetStopTime(u.mem, t_out), "CVodeSetStopTime", t);
}

void restart(CvodeUser& u, double t, N_Vector y, double t_out, Restarts& r, RunStats& stats) {
  if (!stats.warnings.empty() && stats.warnings.back().starts_with("error in CVODE"))
    stats.warnings.pop_back();
  if (r.count++ == 0) r.first = t;
  reinit(u, t, y, t_out, r);
}

// The passage over a collapse by rk4 (HopWatch::next_end), from the last step CVODE accepted: on
// a failed step CVode returns t = tn and y = y(tn), its Nordsieck array restored (cvHandleNFlag,
// cvRestore). y and t at the hop's end on return, CVODE restarted there.
void hop(CvodeUser& u, N_Vector y, double& t, double t_out, Restarts& r, RunStats& stats) {
  const Model& m = *u.m;
  if (!stats.warnings.empty() && stats.warnings.back().starts_with("error in CVODE"))
    stats.warnings.pop_back();  // the callback's -1 that asked for the hop
  double* yd = N_VGetArrayPointer(y);
  long taken = 0;
  CVodeGetNumSteps(u.mem, &taken);
  HopWatch& w = u.hops;
  const double t_start = t, t_end = w.next_end(t, t_out);
  const State from{t, Eigen::Map<const VectorXd>(yd, m.n0),
                   Eigen::Map<const VectorXd>(yd + m.n0, m.n1)};
  HopResult h;
  try {  // the hop runs on what is left of the run's budgets
    h = hop_over(m, *u.o, from, t_end, u.o->max_seconds - u.budget->elapsed(),
                 u.o->max_steps - taken - u.steps_before, w.ref_h);
  } catch (const BudgetExhausted&) {  // named as the run's own budget, not the hop's remainder
    u.budget->throw_exhausted(t, taken + u.steps_before, w.ref_h);
  }
  Eigen::Map<VectorXd>(yd, m.n0) = h.state.q0;
  Eigen::Map<VectorXd>(yd + m.n0, m.n1) = h.state.q1;
  for (size_t k = 0; k < u.terms.size(); ++k) yd[m.n0 + m.n1 + k] += h.energies[u.terms[k]];
  w.done(h.steps, t_start, t_end);
  u.steps_before += h.steps;
  t = t_end;
  reinit(u, t, y, t_out, r);
}

// CVode to t_out (its stop time), restarted at most kRestarts times; max_steps bounds the whole
// run (CVODE's own limit is per call and counts from its last restart).
int advance(CvodeUser& u, N_Vector y, double t_out, double& t, long max_steps, Restarts& r,
            RunStats& stats) {
  for (int k = 0;; ++k) {
    long taken = 0;
    CVodeGetNumSteps(u.mem, &taken);
    check_flag(CVodeSetMaxNumSteps(u.mem, std::max(1L, max_steps - taken - u.steps_before)),
               "CVodeSetMaxNumSteps", t);
    const int flag = CVode(u.mem, t_out, y, &t, CV_NORMAL);
    if (u.hops.wanted) {
      hop(u, y, t, t_out, r, stats);
      if (t >= t_out) return CV_TSTOP_RETURN;
      --k;  // CVODE goes on from the hop's end (not a restart of kRestarts)
      continue;
    }
    if (u.kept) std::rethrow_exception(u.kept);
    if (flag != CV_ERR_FAILURE || k == kRestarts) return flag;
    restart(u, t, y, t_out, r, stats);
  }
}

}  // namespace

void run_cvode(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
               Recorder& rec) {
  // q0, q1 and the energy terms the model has (a term that stays 0 would dilute CVODE's RMS error
  // norm, i.e. loosen the tolerance of the state): the input work and the dissipated energy
  // always, the load work with forces or torques, the constraint work with user constraints.
  std::vector<int> terms = {kInputWork, kDissipated};
  if (!m.forces.empty() || !m.torques.empty()) terms.push_back(kLoadWork);
  for (const Constraint& k : m.constraints)
    if (k.kind() == ConstraintKind::user_position || k.kind() == ConstraintKind::user_velocity) {
      terms.push_back(kConstraintWork);
      break;
    }
  const int n = m.n0 + m.n1 + static_cast<int>(terms.size());
  SUNContext ctx = nullptr;
  check_flag(SUNContext_Create(nullptr, &ctx), "SUNContext_Create", o.t0);
  std::unique_ptr<std::remove_pointer_t<SUNContext>, SundialsDeleter> ctx_guard(ctx);
  N_Vector y = N_VNew_Serial(n, ctx);
  std::unique_ptr<std::remove_pointer_t<N_Vector>, void (*)(N_Vector)> y_guard(y, N_VDestroy);
  N_Vector atol = N_VNew_Serial(n, ctx);
  std::unique_ptr<std::remove_pointer_t<N_Vector>, void (*)(N_Vector)> a_guard(atol, N_VDestroy);
  double* yd = N_VGetArrayPointer(y);
  Eigen::Map<VectorXd>(yd, m.n0) = s0.q0;
  Eigen::Map<VectorXd>(yd + m.n0, m.n1) = s0.q1;
  std::fill(yd + m.n0 + m.n1, yd + n, 0.0);
  double energies[kEnergyTerms] = {};
  auto read_energies = [&] {
    for (size_t k = 0; k < terms.size(); ++k) energies[terms[k]] = yd[m.n0 + m.n1 + k];
  };
  N_VConst(o.atol, atol);
  // The works and dissipated energy (J) are under error control like the state: left out,
  // their error depends on the step sizes the state happens to need (energy balances then held or
  // failed by luck).
  const bool bdf = o.integrator == Integrator::cvode_bdf;
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  if (!mem) throw Error("SUNDIALS CVodeCreate failed", "CVodeCreate", o.t0);
  std::unique_ptr<void, void (*)(void*)> mem_guard(mem, [](void* p) { CVodeFree(&p); });
  RunBudget budget(forward_budget(m, d, o,
                                  bdf ? "loosen rtol/atol, or try dopri5 (non-stiff mechanisms)"
                                      : "loosen rtol/atol, or try cvode_bdf (stiff mechanisms)",
                                  terms));
  CvodeUser user{
      &m, &d, VectorXd(m.n0), VectorXd(m.n1), terms, false, {}, &budget, mem, 0, nullptr, {}, {},
      &o, {}};
  user.hops.allowed = bdf && can_hop(m, o);
  check_flag(CVodeInit(mem, cv_rhs, o.t0, y), "CVodeInit", o.t0);
  check_flag(CVodeSetUserData(mem, &user), "CVodeSetUserData", o.t0);
  check_flag(CVodeSetErrHandlerFn(mem, cv_error_handler, &d.stats), "CVodeSetErrHandlerFn", o.t0);
  check_flag(CVodeSVtolerances(mem, o.rtol, atol), "CVodeSVtolerances", o.t0);
  check_flag(CVodeSetMaxNumSteps(mem, o.max_steps), "CVodeSetMaxNumSteps", o.t0);
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  SUNNonlinearSolver NLS = nullptr;
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, void (*)(SUNMatrix)> A_guard(nullptr,
                                                                                 SUNMatDestroy);
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, int (*)(SUNLinearSolver)> LS_guard(
      nullptr, SUNLinSolFree);
  std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, int (*)(SUNNonlinearSolver)> NLS_guard(
      nullptr, SUNNonlinSolFree);
  if (bdf) {
    A = SUNDenseMatrix(n, n, ctx);
    A_guard.reset(A);
    LS = SUNLinSol_Dense(y, A, ctx);
    LS_guard.reset(LS);
    check_flag(CVodeSetLinearSolver(mem, LS, A), "CVodeSetLinearSolver", o.t0);
    // joint friction (iterated with the reactions) is not differentiated: difference quotients
    // nor are the forces of a stage above (extra_forces)
    if (o.exact_jacobian && m.frictions.empty() && !o.extra_forces)
      check_flag(CVodeSetJacFn(mem, cv_jac), "CVodeSetJacFn", o.t0);
    check_flag(CVodeSetProjFn(mem, cv_proj), "CVodeSetProjFn", o.t0);
  } else {
    NLS = SUNNonlinSol_FixedPoint(y, 0, ctx);
    NLS_guard.reset(NLS);
    check_flag(CVodeSetNonlinearSolver(mem, NLS), "CVodeSetNonlinearSolver", o.t0);
  }
  if (o.stop_when) check_flag(CVodeRootInit(mem, 1, cv_root), "CVodeRootInit", o.t0);
  VectorXd q0 = s0.q0, q1 = s0.q1;
  Restarts restarts;
  rec.record(o.t0, q0, q1, energies);
  double t = o.t0;
  for (int k = 1; k < o.samples; ++k) {
    const double t_out = sample_time(o.t0, o.t1, o.samples, k);
    check_flag(CVodeSetStopTime(mem, t_out), "CVodeSetStopTime", t);
    const int flag = advance(user, y, t_out, t, o.max_steps, restarts, d.stats);
    long taken = 0;
    CVodeGetNumSteps(mem, &taken);
    taken += user.steps_before;
    if (flag == CV_TOO_MUCH_WORK && taken >= o.max_steps) {
      double h = 0;
      CVodeGetLastStep(mem, &h);
      budget.throw_exhausted(t, taken, h);
    }
    if (flag < 0) {
      std::ostringstream s;
      s << "forward dynamics of '" << m.name << "' stopped at t = " << fmt(t)
        << " s: CVODE could not continue (flag " << flag << ")";
      if (!user.last_error.empty()) s << " after: " << user.last_error;
      q0 = Eigen::Map<const VectorXd>(yd, m.n0);
      const double piv = d.pivot_indicator(t, q0);
      if (piv < o.singular_warning)
        s << "; the constraint Jacobian is near-singular there (pivot ratio " << fmt(piv) << ")";
      s << "; configuration:";
      for (int j = 0; j < std::min(m.n0, 12); ++j)
        s << " " << m.coordinate_labels[j] << "=" << fmt(q0[j]);
      throw Error(s.str(), m.name, t);
    }
    q0 = Eigen::Map<const VectorXd>(yd, m.n0);
    q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
    // A root inside a step is CVODE's interpolant there, not a projected step's end: the error
    // test sees only the tangential error (cv_proj), so the interpolant's distance from the
    // constraint manifolds is not controlled (seen: 5e-6 of the size at rtol 1e-4 and 1e-5, a
    // wheel turning 0.07 rad in the step). Projected like a step's end, as the output times are.
    if (flag == CV_ROOT_RETURN && bdf) {
      const double tol = std::max(1e-3 * o.atol, 4e-16 * m.scale);
      d.project(t, q0, q1, tol, tol);
    }
    read_energies();
    rec.record(t, q0, q1, energies);
    if (flag == CV_ROOT_RETURN) {
      d.stats.stopped_by_event = true;
      break;
    }
  }
  d.stats.t_end = t;
  if (restarts.count > 0 && d.stats.warnings.size() < 20)
    d.stats.warnings.push_back(
        std::string(to_string(o.integrator)) + " restarted " + std::to_string(restarts.count) +
        " time" + (restarts.count > 1 ? "s" : "") + ", the first at t = " + fmt(restarts.first) +
        " s: its error test failed repeatedly on the step after it (a jump of the loads there)");
  if (user.hops.hops > 0 && d.stats.warnings.size() < 20)
    d.stats.warnings.push_back(user.hops.warning());
  if (!budget.stall_warning().empty() && d.stats.warnings.size() < 20)
    d.stats.warnings.push_back(budget.stall_warning());
  long v = 0;
  CVodeGetNumSteps(mem, &v);
  d.stats.steps = v + user.steps_before;
  CVodeGetNumErrTestFails(mem, &v);
  d.stats.error_test_failures = v + restarts.failures;
  if (bdf) {
    CVodeGetNumLinSolvSetups(mem, &v);
    d.stats.factorizations = v + restarts.setups;
    CVodeGetNumProjEvals(mem, &v);
    d.stats.projections = v + restarts.projections;
  }
}

}  // namespace mo2d::detail
