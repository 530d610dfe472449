// Inverse dynamics per sample: positions (Newton), velocities, accelerations, efforts (null space
// C = K^-1 [0; I], Theorem 4.3), multipliers and joint reactions.
#include "mo2d/inverse.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <ctime>

#include "constraints/constraints.hpp"
#include "dynamics/friction.hpp"
#include "dynamics/slack.hpp"
#include "inverse/inverse_stages.hpp"
#include "kinematics/residuals.hpp"
#include "kinematics/solve_positions.hpp"
#include "linalg/pattern_lu.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "output/result_rows.hpp"
#include "output/trajectory_labels.hpp"
#include "run/cpu_time.hpp"
#include "run/format.hpp"
#include "run/run_budget.hpp"
#include "run/time_grid.hpp"
#include "run/user_code.hpp"

namespace mo2d {

namespace {

double pivot_ratio(const Eigen::PartialPivLU<MatrixXd>& lu) {
  if (lu.matrixLU().rows() == 0) return 1.0;
  const auto d = lu.matrixLU().diagonal().cwiseAbs();
  const double mx = d.maxCoeff();
  return mx > 0 ? d.minCoeff() / mx : 0.0;
}

using detail::fmt;

// Labels of the variables that dominate the null space of J (columns given by labels).
std::string null_variables(const MatrixXd& J, const std::vector<std::string>& labels) {
  Eigen::JacobiSVD<MatrixXd> svd(J, Eigen::ComputeFullV);
  const Eigen::VectorXd v = svd.matrixV().col(J.cols() - 1);
  std::vector<int> idx(v.size());
  for (int k = 0; k < v.size(); ++k) idx[k] = k;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return std::abs(v[a]) > std::abs(v[b]); });
  std::string s;
  for (int k = 0; k < std::min(3, static_cast<int>(v.size())); ++k)
    if (std::abs(v[idx[k]]) > 1e-3) s += (s.empty() ? "" : ", ") + labels[idx[k]];
  return s;
}

// Throws if a constraint row evaluated to a non-finite value (a user function, a load).
void check_finite_rows(const VectorXd& r, const std::vector<std::string>& labels, const char* level,
                       double t) {
  for (int k = 0; k < r.size(); ++k)
    if (!std::isfinite(r[k]))
      throw Error(std::string(level) + " constraint '" + labels[k] +
                      "' is not finite at t = " + fmt(t) + " s",
                  labels[k], t);
}

std::string prescribed_values(const InverseData& d) {
  std::string s;
  for (size_t k = 0; k < d.p_labels.size(); ++k)
    s += (k ? ", " : "") + d.p_labels[k] + " = " + fmt(d.s[k]);
  return s;
}

// The first non-finite result of a sample (positions, velocities, accelerations, efforts,
// reactions): an Error naming it and the time.
void check_finite_sample(const Model& m, const InverseData& d, double t) {
  if (d.q0.allFinite() && d.q1.allFinite() && d.a1.allFinite() && d.u.allFinite() &&
      d.reactions.allFinite())
    return;  // (no allocation on this path: inverse_dynamics_sample allocates nothing)
  std::string names;
  int count = 0;
  auto scan = [&](const VectorXd& v, const std::vector<std::string>& labels, const char* suffix) {
    for (int k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k]) && count++ < 3)
        names += (names.empty() ? "'" : ", '") + labels[k] + suffix + "' = " + fmt(v[k]);
  };
  scan(d.q0, m.coordinate_labels, "");
  scan(d.q1, m.rate_labels, "");
  scan(d.a1, m.rate_labels, ".dot");
  scan(d.u, m.input_labels(), "");
  scan(d.reactions, m.reaction_labels(), "");
  if (count == 0) return;
  throw Error("inverse dynamics of '" + m.name + "': " + names + (count > 3 ? ", ..." : "") +
                  (count == 1 ? " is" : " are") + " not finite at t = " + fmt(t) +
                  " s (first non-finite result: a value overflowed, or a load or motion is not "
                  "finite there)",
              names.substr(1, names.find('\'', 1) - 1), t);
}

}  // namespace

namespace {

[[noreturn]] void throw_singular_positions(const Model& m, InverseData& d, double t, bool first) {
  std::vector<std::string> free_labels;
  for (int k = 0; k < m.n0; ++k)
    if (d.colmap[k] >= 0) free_labels.push_back(m.coordinate_labels[k]);
  const std::string vars = null_variables(d.J, free_labels);
  if (first)
    throw Error("the prescribed coordinates (" + prescribed_values(d) +
                    ") are not independent inputs: with them fixed the position constraints do "
                    "not determine " +
                    vars,
                d.p_labels.empty() ? "" : d.p_labels[0], t);
  throw Error("singular configuration at t = " + fmt(t) + " s (" + prescribed_values(d) +
                  "): the position constraints do not determine " + vars,
              vars.substr(0, vars.find(',')), t);
}

// The continuation from the last solved configuration (the model's initial one at the first
// sample) towards the prescribed values stopped at the fraction `reached`: name where it started,
// where it stopped and how singular the position constraints are there (a limit of the workspace:
// the prescribed values are beyond it, e.g. a coupler angle outside the coupler's range).
[[noreturn]] void throw_unreachable(const Model& m, InverseData& d, double t, double reached) {
  std::string from, stop;
  for (size_t k = 0; k < d.p_labels.size(); ++k) {
    from += (k ? ", " : "") + d.p_labels[k] + " = " + fmt(d.s_good[k]);
    stop += (k ? ", " : "") + d.p_labels[k] + " = " + fmt(d.q0_good[d.p_index[k]]);
  }
  detail::position_jacobian(m, d.q0_good, t, d.colmap.data(), d.psi, d.J);
  double ratio = 1;
  if (d.J.size()) {
    const Eigen::VectorXd sv = Eigen::JacobiSVD<MatrixXd>(d.J).singularValues();
    ratio = sv[0] > 0 ? sv[sv.size() - 1] / sv[0] : 0.0;
  }
  std::string vars;
  if (ratio < 1e-2) {
    std::vector<std::string> free_labels;
    for (int k = 0; k < m.n0; ++k)
      if (d.colmap[k] >= 0) free_labels.push_back(m.coordinate_labels[k]);
    vars = null_variables(d.J, free_labels);
  }
  throw Error("positions not found at t = " + fmt(t) + " s: the prescribed " +
                  prescribed_values(d) + " cannot be reached from the " +
                  (d.has_previous ? "previous sample" : "initial configuration") + " (" + from +
                  "): the positions follow it only to " + stop + " (" + fmt(100 * reached) +
                  " % of the way), where the position constraints with these coordinates "
                  "prescribed are " +
                  (ratio < 1e-2 ? "near-singular (sigma_min/sigma_max = " + fmt(ratio) +
                                      "; undetermined: " + vars +
                                      "): a limit of the workspace for this motion"
                                : "regular (sigma_min/sigma_max = " + fmt(ratio) +
                                      "): Newton did not converge beyond it"),
              d.p_labels.empty() ? "" : d.p_labels[0], t);
}

using detail::NewtonStatus;

// Newton from a prediction O(h^3) away, J square (solve_positions.hpp): the exact LU step, whose
// pivot ratio tells a singular configuration; halving until |psi|_inf decreases.
detail::NewtonOptions sample_newton(const InverseOptions& o, double scale) {
  return {.tolerance = o.position_tolerance * scale,
          .max_iterations = o.max_newton_iterations,
          .test_last = true,
          .step = detail::NewtonStep::lu,
          .singular_pivot_ratio = o.singular_pivot_ratio,
          .line_search = detail::LineSearch::decrease,
          .min_alpha = 1e-4,
          .non_finite = detail::NonFinite::stop};
}

// Newton on psi(q0) = 0 over the free coordinates from d.q0 (throws if a residual is not finite).
// Writes d.residual_position and d.newton_iterations; leaves d.J evaluated at the last iterate.
NewtonStatus newton(const Model& m, InverseData& d, double t) {
  detail::NewtonBuffers w{
      .psi = d.psi, .J = d.J, .dx = d.trial, .q_trial = &d.q0_trial, .pattern_lu = d.lu_pos.get()};
  const detail::NewtonResult r =
      detail::solve_positions(m, sample_newton(d.options, m.scale), w, t, d.colmap, d.q0);
  if (r.status == NewtonStatus::non_finite)
    check_finite_rows(d.psi, m.position_row_labels, "position", t);  // throws
  d.newton_iterations = r.iterations;
  d.residual_position = r.residual;
  return r.status;
}

// The positions just solved against their prediction from the last sample (d.q0_pred): on a
// smooth branch they differ by O(h^3); a difference comparable to the predicted motion itself
// means the positions jumped (another assembly mode) or the samples do not resolve a singular
// passage. Compared in dimensionless coordinates q0 / pos_scale.
void check_branch(const Model& m, InverseData& d, double t) {
  double dev = 0, step = 0;
  int worst = 0;
  for (int k = 0; k < m.n0; ++k) {
    const double w = 1 / d.pos_scale[k];
    const double e = std::abs(d.q0[k] - d.q0_pred[k]) * w;
    step = std::max(step, std::abs(d.q0_pred[k] - d.q0_prev[k]) * w);
    if (e > dev) dev = e, worst = k;
  }
  // floor: 1e-8 of the mechanism's size (far above the Newton tolerance), in the same units
  double floor = 0;
  for (int k = 0; k < m.n0; ++k)
    if (m.rate_refs[k].body >= 0) floor = std::max(floor, 1e-8 * m.scale / d.pos_scale[k]);
  if (!(dev > d.options.branch_jump * step && dev > floor)) return;
  d.warnings.push_back("the positions jumped between t = " + fmt(d.t_prev) +
                       " s and t = " + fmt(t) + " s (" + prescribed_values(d) + "): '" +
                       m.coordinate_labels[worst] + "' is " + fmt(d.q0[worst]) +
                       ", predicted from the velocities " + fmt(d.q0_pred[worst]) +
                       " (another assembly mode, or a singular configuration passed between the "
                       "samples; results near it are not reliable: use more samples)");
}

// The dimensionless Ks = R K D that lu_K factors (formed only for the messages).
const MatrixXd& scaled_K(InverseData& d) {
  d.Ks.noalias() = d.k_row.asDiagonal() * d.K * d.col_scale.asDiagonal();
  return d.Ks;
}

// Singular configurations between and at samples: the orientation (sign of det) of the
// dimensionless K changes where the path crosses a singular configuration; a run of samples with
// the pivot ratio below near_singular_pivot_ratio is reported at its smallest value.
void check_singular_passage(const Model& m, InverseData& d, double t) {
  d.det_sign = d.lu_K->det_sign();
  if (d.has_previous && d.det_sign * d.det_sign_prev < 0)
    d.warnings.push_back("singular configuration passed between t = " + fmt(d.t_prev) +
                         " s and t = " + fmt(t) + " s (" + prescribed_values(d) +
                         "): the constraint Jacobian with the prescribed coordinates changes "
                         "orientation (undetermined there: " +
                         null_variables(scaled_K(d), m.rate_labels) +
                         "); efforts and reactions near it are not reliable");
  if (d.pivot_ratio < d.options.near_singular_pivot_ratio) {
    if (!d.near_singular || d.pivot_ratio < d.near_min) {
      d.near_min = d.pivot_ratio;
      d.near_t = t;
      d.near_what = prescribed_values(d) + "; dimensionless pivot ratio " + fmt(d.pivot_ratio) +
                    "; nearly undetermined: " + null_variables(scaled_K(d), m.rate_labels);
    }
    d.near_singular = true;
  } else {
    finish_inverse_warnings(d);
  }
}

// ---- the stages of one sample (inverse_dynamics_sample) -------------------------------------

// x <- K^-1 x through the dimensionless factorization Ks = R K D: K^-1 = D Ks^-1 R.
template <class X>
void solve_K(InverseData& d, X&& x) {
  x.array() *= d.k_row.array();
  d.lu_K->solve_in_place(x);
  x.array() *= d.col_scale.array();
}

// The prescribed values s, s_dot, s_ddot at t (exact derivatives of the motions through Jet).
void prescribed_motion(const Model& m, InverseData& d, double t) {
  const int dof = m.dof;
  // prescribed motion, exact derivatives
  for (int k = 0; k < dof; ++k) {
    const Jet s = detail::call_user_code([&] { return d.p_motion[k](Jet(t, 1, 0)); },
                                         "prescribed motion of", d.p_labels[k], t);
    if (!std::isfinite(s.v) || !std::isfinite(s.d) || !std::isfinite(s.dd))
      throw Error("prescribed motion of '" + d.p_labels[k] + "' is not finite at t = " + fmt(t),
                  d.p_labels[k], t);
    d.s[k] = s.v;
    d.s_dot[k] = s.d;
    d.s_ddot[k] = s.dd;
  }
}

// Positions: Newton from a second-order prediction, else continuation (throws if unreachable).
void sample_positions(const Model& m, InverseData& d, double t) {
  const int dof = m.dof;
  // ---- positions: Newton from a second-order prediction; if that fails, continuation from the
  // last solved configuration (the prescribed values move there in steps, halved on failure)
  d.q0_good = d.q0;  // previous sample, or the model's initial configuration
  for (int k = 0; k < dof; ++k) d.s_good[k] = d.q0_good[d.p_index[k]];
  if (d.has_previous) {
    const double h = t - d.t_prev;
    d.q0 = d.q0_prev + h * d.q1_prev.head(m.n0) + (0.5 * h * h) * d.a1_prev.head(m.n0);
  }
  for (int k = 0; k < dof; ++k) d.q0[d.p_index[k]] = d.s[k];
  d.q0_pred = d.q0;
  NewtonStatus status = newton(m, d, t);
  if (status != NewtonStatus::converged) {
    double lambda = 0, step = 0.5;
    while (lambda < 1 && step > 1e-6) {
      const double trial = std::min(1.0, lambda + step);
      d.q0_trial = d.q0_good;
      for (int k = 0; k < dof; ++k)
        d.q0_trial[d.p_index[k]] = d.s_good[k] + trial * (d.s[k] - d.s_good[k]);
      d.q0.swap(d.q0_trial);
      status = newton(m, d, t);
      if (status == NewtonStatus::converged) {
        lambda = trial;
        d.q0_good = d.q0;
        step = std::min(2 * step, 1.0);
      } else {
        step *= 0.5;
      }
    }
    if (lambda < 1) {
      if (status == NewtonStatus::singular && lambda == 0)
        throw_singular_positions(m, d, t, !d.has_previous);
      throw_unreachable(m, d, t, lambda);
    }
  }
}

// K = [A; E] with the velocity rows b, factored in dimensionless form (throws if singular).
void factor_velocity_system(const Model& m, InverseData& d, double t) {
  const int dof = m.dof;
  // ---- velocities and accelerations: K = [A; E]
  d.K.setZero();
  d.entries.clear();
  detail::SlotRecordSink sink{d.K.topRows(m.m1), m, d.entries};
  for (const auto& c : m.constraints) detail::velocity_rows(m, c, d.q0, t, d.b, sink);
  for (int k = 0; k < dof; ++k) d.K(m.m1 + k, d.p_index[k]) = 1.0;
  check_finite_rows(d.b, m.velocity_row_labels, "velocity", t);
  // factored in dimensionless form Ks = R K D (R: unit rows of A D, and E's rows back to 1), so
  // that the singularity tests do not depend on units or size: K^-1 = D Ks^-1 R. The squared
  // row norms are summed column by column (K is column-major; each row still sums j = 0, 1, ...)
  auto s2 = d.k_row.head(m.m1);
  s2.setZero();
  for (int j = 0; j < m.n1; ++j)
    s2.array() += (d.K.col(j).head(m.m1).array() * d.col_scale[j]).square();
  // a non-finite entry of A makes its row's sum non-finite (E's rows are ones): K is scanned
  // only then (or when a finite row overflowed)
  if (!s2.allFinite() && !d.K.allFinite())
    throw Error("the velocity constraint Jacobian is not finite at t = " + fmt(t) + " s", m.name,
                t);
  for (int i = 0; i < m.m1; ++i) d.k_row[i] = s2[i] > 0 ? 1 / std::sqrt(s2[i]) : 1.0;
  for (int k = 0; k < dof; ++k) d.k_row[m.m1 + k] = 1 / d.col_scale[d.p_index[k]];
  d.pivot_ratio = d.lu_K->compute_scaled(d.K, d.k_row, d.col_scale);  // Ks
  if (d.pivot_ratio < d.options.singular_pivot_ratio) {
    const std::string vars = null_variables(scaled_K(d), m.rate_labels);
    if (!d.has_previous)
      throw Error("the prescribed coordinates (" + prescribed_values(d) +
                      ") are not independent inputs: the velocity constraints with them "
                      "prescribed are singular (undetermined: " +
                      vars + ")",
                  d.p_labels.empty() ? "" : d.p_labels[0], t);
    throw Error("singular configuration at t = " + fmt(t) + " s (" + prescribed_values(d) +
                    "): the constraint Jacobian with the prescribed coordinates loses rank "
                    "(undetermined: " +
                    vars + ")",
                vars.substr(0, vars.find(',')), t);
  }
}

// q1 = K^-1 [b; s_dot], a1 = K^-1 [c; s_ddot] and their residuals.
void velocities_and_accelerations(const Model& m, InverseData& d, double t) {
  const int dof = m.dof;
  d.rhs.head(m.m1) = d.b;
  d.rhs.tail(dof) = d.s_dot;
  d.q1 = d.rhs;
  solve_K(d, d.q1);
  acceleration_rhs(m, d.q0, d.q1, t, d.c);
  check_finite_rows(d.c, m.velocity_row_labels, "acceleration", t);
  d.rhs.head(m.m1) = d.c;
  d.rhs.tail(dof) = d.s_ddot;
  d.a1 = d.rhs;
  solve_K(d, d.a1);
  const auto A = d.K.topRows(m.m1);
  d.row_residual.noalias() = A * d.q1;
  d.residual_velocity = m.m1 ? (d.row_residual - d.b).lpNorm<Eigen::Infinity>() : 0.0;
  d.row_residual.noalias() = A * d.a1;
  d.residual_acceleration = m.m1 ? (d.row_residual - d.c).lpNorm<Eigen::Infinity>() : 0.0;
}

// Efforts and multipliers (Theorem 4.3): C, C^T B and M a - f (body-local, in d.local_a); then
// the efforts, multipliers and reactions, with the joint friction iterated (friction.cpp).
void efforts_and_multipliers(const Model& m, InverseData& d, double t) {
  const int dof = m.dof;
  const auto A = d.K.topRows(m.m1);
  // ---- efforts: C^T (M a1 - f - B u) = 0, C = K^-1 [0; I]  (Theorem 4.3, eq. 2.29)
  body_inertia(m, d.a1, d.local_a);
  body_applied(m, d.q0, d.q1, t, d.local);
  d.local_a -= d.local;  // M a - f, body-local
  // C = K^-1 [0; I]: columns of K^-1 at the prescribed rows (eq. 2.29, independent variables =
  // the prescribed coordinates); then C^T B u = C^T w gives the efforts.
  for (int k = 0; k < dof; ++k) {
    auto col = d.S.col(k);
    col.setZero();
    col[m.m1 + k] = 1.0;
    solve_K(d, col);
  }
  if (d.options.complement == ComplementMethod::recursive) d.S = recursive_complement(m, A);
  // dof x dof dot products of length n1 (coefficient-wise: Eigen's GEMM path costs more here)
  d.CtB.noalias() = d.S.transpose().lazyProduct(d.B);
  d.lu_u.compute(d.CtB);
  if (pivot_ratio(d.lu_u) < d.options.singular_pivot_ratio)
    throw Error("the actuators cannot produce the prescribed motion at t = " + fmt(t) + " s (" +
                    prescribed_values(d) +
                    "): the inputs do not act on the prescribed coordinates (C^T B is singular)",
                m.inputs.empty() ? "" : m.inputs[0].label, t);
  if (m.frictions.empty())
    inverse_efforts_and_reactions(m, d);
  else
    inverse_friction(m, d, t);
}

}  // namespace

void inverse_efforts_and_reactions(const Model& m, InverseData& d) {
  // w = M a - f - (friction), generalized; the efforts C^T B u = C^T w
  d.w.setZero();
  if (!m.frictions.empty()) detail::add_friction_forces(m, d.friction, -1.0, true, d.local_a, d.w);
  scatter_local(m, d.local_a, d.w);
  d.Ctw.noalias() = d.S.transpose().lazyProduct(d.w);
  d.u = d.lu_u.solve(d.Ctw);
  // multipliers: K^T [lambda; mu] = B u - (M a - f), with mu = 0 for an exact solution
  d.rhs.noalias() = d.B.lazyProduct(d.u);
  d.rhs -= d.w;
  d.z = d.rhs;  // K^-T = R Ks^-T D
  d.z.array() *= d.col_scale.array();
  d.lu_K->solve_transpose_in_place(d.z);
  d.z.array() *= d.k_row.array();
  d.lambda = d.z.head(m.m1);
  // ---- reactions: direct from multipliers, or split at eliminated joints (d.local_a is spent)
  detail::joint_reactions(m, d.entries, d.lambda, d.u, d.local_a, d.edge_force, d.edge_offset,
                          d.reactions);
}

void inverse_dynamics_sample(const Model& m, InverseData& d, double t) {
  d.t = t;
  prescribed_motion(m, d, t);
  sample_positions(m, d, t);
  if (d.has_previous) check_branch(m, d, t);
  factor_velocity_system(m, d, t);
  check_singular_passage(m, d, t);
  velocities_and_accelerations(m, d, t);
  efforts_and_multipliers(m, d, t);
  check_finite_sample(m, d, t);
  d.q0_prev = d.q0;
  d.q1_prev = d.q1;
  d.a1_prev = d.a1;
  d.t_prev = t;
  d.det_sign_prev = d.det_sign;
  d.has_previous = true;
}

void finish_inverse_warnings(InverseData& d) {
  if (!d.near_singular) return;
  d.near_singular = false;
  d.warnings.push_back("near-singular configuration at t = " + fmt(d.near_t) + " s (" +
                       d.near_what + ")");
}

Trajectory detail::inverse_run(const Model& m, InverseData& d, const InverseOptions& options,
                               const std::string& run,
                               const std::function<void(int)>& after_sample) {
  const int N = options.samples;
  Trajectory r = detail::labelled_trajectory(m, RunKind::inverse);
  r.time.resize(N);
  r.q0.resize(N, m.n0);
  r.q1.resize(N, m.n1);
  r.a1.resize(N, m.n1);
  r.efforts.resize(N, m.n_inputs());
  r.reactions.resize(N, m.n_reactions());
  r.residuals.resize(N, 3);
  const double start = detail::cpu_seconds();
  detail::RunBudget budget({.run = run,
                            .name = m.name,
                            .t0 = options.t0,
                            .t1 = options.t1,
                            .max_steps = 0,
                            .max_seconds = options.max_seconds,
                            .monitor = options.monitor,
                            .interval = options.monitor_interval,
                            .hint = "use fewer samples",
                            .unit = "samples solved"});
  for (int k = 0; k < N; ++k) {
    const double t = detail::sample_time(options.t0, options.t1, N, k);
    budget.check(t, k, 0);
    inverse_dynamics_sample(m, d, t);
    if (after_sample) after_sample(k);
    r.time[k] = t;
    detail::set_row(r.q0, k, d.q0);
    detail::set_row(r.q1, k, d.q1);
    detail::set_row(r.a1, k, d.a1);
    detail::set_row(r.efforts, k, d.u);
    detail::set_row(r.reactions, k, d.reactions);
    r.residuals.row(k) << d.residual_position, d.residual_velocity, d.residual_acceleration;
  }
  finish_inverse_warnings(d);
  r.stats.warnings = d.warnings;
  detail::reduced_spring_slack(m, r, r.stats.warnings);
  r.stats.cpu_seconds = detail::cpu_seconds() - start;
  return r;
}

Trajectory inverse_dynamics(const Model& m, std::span<const Prescribed> prescribed,
                            const InverseOptions& options) {
  InverseData d(m, prescribed, options);
  return detail::inverse_run(m, d, options, "inverse dynamics of '" + m.name + "'", {});
}

}  // namespace mo2d
