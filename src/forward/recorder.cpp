// Forward dynamics, what a run records at each output time: the energy rates integrated with the
// state, the Recorder (state, accelerations, reactions, energies, residuals, the checks of drift
// and of singular configurations), and the budget of a run.
#include <algorithm>
#include <cmath>

#include "dynamics/friction.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "output/result_rows.hpp"

namespace mo2d::detail {

namespace {

// q1^T (M a - f - B u - Q_friction): the power of the constraint forces -A^T lambda (the joint
// friction's generalized force is not in f: its power q1^T Q_friction is friction_power)
double constraint_power(ForwardData& d, const VectorXd& q1) {
  d.mass_times(d.a, d.tmp1);
  d.tmp1 -= d.f;
  d.tmp1 -= d.Bu;
  const double friction = d.m.frictions.empty() ? 0.0 : friction_power(d.m, d.friction, q1);
  return q1.dot(d.tmp1) - friction;
}

}  // namespace

void energy_rates(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1, double* rates) {
  rates[kInputWork] = d.Bu.dot(q1);
  rates[kLoadWork] = load_power(d.m, q0, q1, t);
  // A time-dependent constraint (A q1 = b, b != 0) moves its bodies: its force -A^T lambda =
  // M a - f - B u does the work -lambda^T b. Zero (not evaluated) for fixed constraints.
  rates[kConstraintWork] =
      d.m.m1 > 0 && d.b.lpNorm<Eigen::Infinity>() > 0 ? constraint_power(d, q1) : 0.0;
  rates[kDissipated] = damping_power(d.m, q0, q1);
  // joint friction (its values at this evaluation) dissipates -F v >= 0
  if (!d.m.frictions.empty()) rates[kDissipated] -= friction_power(d.m, d.friction, q1);
  // the forces of a stage above (ForwardOptions::extra_forces): their power, and what they
  // dissipate
  if (d.o.extra_forces) {
    rates[kLoadWork] += d.f_extra.dot(q1) + d.extra_dissipation;
    rates[kDissipated] += d.extra_dissipation;
  }
}

// An integrator that does not project (cvode_adams, baumgarte) cannot hold the constraints
// through a singular configuration: the drift in the direction the Jacobian loses is not
// corrected and the run can leave its branch without any other sign (the double four-bar on
// cvode_adams: tips 1 m off, residuals 1e-7). So such a run stops with an error as soon as one of
// its evaluations comes near one (below o.singular_warning).
void Recorder::check_unprojected() {
  if (d.projects() || m.m1 == 0 || !(d.eval_min_ratio < d.o.singular_warning)) return;
  const SingularDirection s = singular_direction(d.dense_velocity_rows(d.eval_min_t, d.eval_min_q0),
                                                 d.col_scale, m.velocity_row_labels, m.rate_labels);
  throw Error("forward dynamics of '" + m.name + "': " + to_string(d.o.integrator) +
                  " does not project on the constraints and cannot pass the near-singular "
                  "configuration at t = " +
                  fmt(d.eval_min_t) + " s (dimensionless pivot ratio " + fmt(d.eval_min_ratio) +
                  "; nearly dependent constraints " + s.rows + ", nearly undetermined motion of " +
                  s.variables +
                  ") without the risk of leaving its branch: use cvode_bdf, dopri5 or rk4, "
                  "which project",
              s.variables.empty() ? m.name : s.variables.substr(1, s.variables.find('\'', 1) - 1),
              d.eval_min_t);
}

void Recorder::record(double t, const VectorXd& q0, const VectorXd& q1, const double* energies) {
  check_unprojected();
  if (d.o.progress) d.o.progress(t);
  r.time[k] = t;
  set_row(r.q0, k, q0);
  set_row(r.q1, k, q1);
  d.accelerations(t, q0, q1, d.o.integrator == Integrator::baumgarte);
  set_row(r.a1, k, d.a);
  d.compute_reactions(t, q0, q1);
  set_row(r.reactions, k, d.reactions);
  set_row(r.efforts, k, d.u);
  r.kinetic[k] = kinetic_energy(m, q1);
  r.potential[k] = potential_energy(m, q0);
  r.input_work[k] = energies[kInputWork];
  r.load_work[k] = energies[kLoadWork];
  r.constraint_work[k] = energies[kConstraintWork];
  r.dissipated[k] = energies[kDissipated];
  VectorXd psi(m.m0);
  position_residual(m, q0, t, psi);
  r.residuals(k, 0) = m.m0 ? psi.lpNorm<Eigen::Infinity>() : 0.0;
  d.fill_velocity_rows(t, q0);
  d.velocity_residual_into(q1, d.r1);
  r.residuals(k, 1) = m.m1 ? d.r1.lpNorm<Eigen::Infinity>() : 0.0;
  check_drift(t, q0);
  const double piv = d.pivot_indicator(t, q0);
  d.stats.min_pivot_ratio = std::min(d.stats.min_pivot_ratio, piv);
  if (piv < d.o.singular_warning) {
    if (!near) near_first = t;
    near_last = t;
    if (!near || piv < near_min) {
      near_min = piv;
      near_t = t;
      const SingularDirection s = singular_direction(d.dense_velocity_rows(t, q0), d.col_scale,
                                                     m.velocity_row_labels, m.rate_labels);
      near_what = "; nearly dependent constraints " + s.rows + ", nearly undetermined motion of " +
                  s.variables;
    }
    near = true;
  } else {
    flush_near();
  }
  check_finite_sample(m, r, k);
  ++k;
}

void Recorder::flush_near() {
  if (!near) return;
  near = false;
  std::string span;
  if (near_last > near_first)
    span = ", output times " + fmt(near_first) + " to " + fmt(near_last) + " s";
  if (d.stats.warnings.size() < 20)
    d.stats.warnings.push_back("near-singular configuration at t = " + fmt(near_t) +
                               " s (dimensionless pivot ratio " + fmt(near_min) + span + near_what +
                               ")");
}

// Constraint drift at an output time, dimensionless: each position row in the units of the
// dimensionless coordinates (unit rows of Psi diag(pos_scale)) against the mechanism's size in
// the same units. Projecting integrators keep it near 1e-13; beyond o.drift_tolerance the run has
// left the constraint manifold (and possibly its branch): an error naming the time and the worst
// constraint row (a warning, once, for the integrators that do not project).
void Recorder::check_drift(double t, const VectorXd& q0) {
  if (m.m0 == 0 || drift_reported) return;
  d.fill_position_rows(t, q0);
  double size = 0;
  for (int j = 0; j < m.n0; ++j)
    if (m.rate_refs[j].body >= 0) size = std::max(size, m.scale / d.pos_scale[j]);
  if (!(size > 0)) size = m.scale;
  double worst = 0;
  int row = 0;
  for (int i = 0; i < m.m0; ++i) {
    const double e = std::abs(d.psi[i]) * d.pos_row_scale[i] / size;
    if (!(e <= worst)) worst = e, row = i;
  }
  d.stats.max_drift = std::max(d.stats.max_drift, worst);
  if (!(worst > d.o.drift_tolerance)) return;
  drift_reported = true;
  // without projection the drift grows with the integrator's tolerance: a warning (such a run
  // stops at a singular configuration, check_unprojected); with projection it is a failure
  if (!d.projects()) {
    if (d.stats.warnings.size() < 20)
      d.stats.warnings.push_back(
          "the constraints drifted by " + fmt(worst) + " of the mechanism's size at t = " + fmt(t) +
          " s (worst row '" + m.position_row_labels[row] + "', residual " + fmt(d.psi[row]) +
          "): " + to_string(d.o.integrator) +
          " does not project on the constraints (cvode_bdf, dopri5 and rk4 do)");
    return;
  }
  const std::string msg = "forward dynamics of '" + m.name + "': the constraints drifted by " +
                          fmt(worst) + " of the mechanism's size at t = " + fmt(t) +
                          " s (worst row '" + m.position_row_labels[row] + "', residual " +
                          fmt(d.psi[row]) + "; drift tolerance " + fmt(d.o.drift_tolerance) +
                          "): the motion has left the constraint manifold";
  throw Error(msg, m.position_row_labels[row], t);
}

void Recorder::finish() {
  flush_near();
}

detail::RunBudget::Settings forward_budget(const Model& m, ForwardData& d, const ForwardOptions& o,
                                           std::string hint, std::vector<int> terms) {
  return {.run = "forward dynamics of '" + m.name + "' (" + to_string(o.integrator) + ")",
          .name = m.name,
          .t0 = o.t0,
          .t1 = o.t1,
          .max_steps = o.max_steps,
          .max_seconds = o.max_seconds,
          .monitor = o.monitor,
          .interval = o.monitor_interval,
          .hint = std::move(hint),
          .collapse_cause = [&d, terms = std::move(terms)](double t, const double* y) {
            return collapse_cause(d, t, y, terms);
          }};
}

}  // namespace mo2d::detail
