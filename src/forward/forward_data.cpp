// Forward dynamics, one evaluation: accelerations in three formulations, projection on the
// constraint manifolds, reactions of a recorded state, and the output recorder.
#include "forward/forward_data.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "constraints/constraints.hpp"
#include "kinematics/conditioning.hpp"
#include "kinematics/solve_positions.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "output/result_rows.hpp"

namespace mo2d::detail {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

VectorXd regularized_normal_solve(const MatrixXd& J, const VectorXd& x, double eps) {
  MatrixXd G = J * J.transpose();
  G.diagonal().array() += eps * std::max(1.0, G.diagonal().maxCoeff());
  return G.llt().solve(J * x);
}

ForwardData::ForwardData(const Model& model, const ForwardOptions& opt) : m(model), o(opt) {
  M = mass_matrix(m);
  B = input_matrix(m);
  A = MatrixXd::Zero(m.m1, m.n1);
  Psi = MatrixXd::Zero(m.m0, m.n0);
  H = MatrixXd::Zero(m.n1, m.n1);
  b = c = VectorXd::Zero(m.m1);
  f = Bu = rhs = a = ap = tmp0 = tmp1 = VectorXd::Zero(m.n1);
  u = VectorXd::Zero(m.n_inputs());
  lambda = VectorXd::Zero(m.m1);
  psi = VectorXd::Zero(m.m0);
  local = VectorXd::Zero(m.n_slots);
  An = MatrixXd::Zero(m.m1, m.n1);
  G1 = MatrixXd::Zero(m.m1, m.m1);
  lu_G1 = detail::SmallLU(m.m1);
  row_scale = VectorXd::Ones(m.m1);
  pos_row_scale = VectorXd::Ones(m.m0);
  col_scale = column_scaling(m);
  pos_scale = col_scale.head(m.n0);
  eval_min_q0 = m.q0;
  AMinv = MatrixXd::Zero(m.m1, m.n1);
  {
    // on the dimensionless D M D (D = col_scale): the test does not depend on units or size
    Eigen::LLT<MatrixXd> llt_M(col_scale.asDiagonal() * M * col_scale.asDiagonal());
    const auto d = llt_M.matrixLLT().diagonal();
    // M positive definite and not nearly singular (a massless body makes it singular); a model
    // without quasi-velocities has an empty M (and no minCoeff)
    has_Minv = llt_M.info() == Eigen::Success && (m.n1 == 0 || d.minCoeff() > 1e-6 * d.maxCoeff());
    if (has_Minv)  // M^-1 = D (D M D)^-1 D
      Minv = col_scale.asDiagonal() * llt_M.solve(MatrixXd::Identity(m.n1, m.n1)) *
             col_scale.asDiagonal();
  }
  KKT = MatrixXd::Zero(m.n1 + m.m1, m.n1 + m.m1);
  KKT.topLeftCorner(m.n1, m.n1) = M;
  kkt_x = VectorXd::Zero(m.n1 + m.m1);
  lu_kkt = detail::SmallLU(m.n1 + m.m1);
  K = MatrixXd::Zero(m.n1, m.n1);
  lu_K = detail::SmallLU(m.n1);
  S = MatrixXd::Zero(m.n1, m.dof);
  CtMC = MatrixXd::Zero(m.dof, m.dof);
  red = VectorXd::Zero(m.dof);
  // penalty: large against the mass, as in Bayo & Garcia de Jalon's augmented Lagrangian, on the
  // dimensionless rows (alpha N^2) against the largest entry of the dimensionless D M D
  const VectorXd dmd = M.diagonal().cwiseProduct(col_scale.cwiseAbs2());
  const double mscale = dmd.maxCoeff() > 0 ? dmd.maxCoeff() : 1.0;
  alpha = o.penalty > 0 ? o.penalty : 1e7 * mscale;
  // position metric: the mass of the node coordinates, kept definite for massless nodes (and the
  // extra coordinates, which carry no mass) by 1e-6 of the mass scale in dimensionless terms
  M0 = M.topLeftCorner(m.n0, m.n0);
  for (int k = 0; k < m.n0; ++k) M0(k, k) += 1e-6 * mscale / (pos_scale[k] * pos_scale[k]);
  W0 = MatrixXd::Zero(m.n0, m.n0);
  dq0 = VectorXd::Zero(m.n0);
  dq1 = VectorXd::Zero(m.n1);
  r1 = VectorXd::Zero(m.m1);
  edge_force.assign(detail::merge_edge_layout(m, edge_offset), 0.0);
  reactions = VectorXd::Zero(m.n_reactions());
  la = VectorXd::Zero(m.n_slots);
  w = VectorXd::Zero(m.n1);
  lam_ls = VectorXd::Zero(m.m1);
}

void ForwardData::inputs(double t) {
  for (int k = 0; k < m.n_inputs(); ++k) {
    const bool has = k < static_cast<int>(o.efforts.size()) && o.efforts[k];
    u[k] = has ? o.efforts[k](t) : 0.0;
    if (!std::isfinite(u[k]))
      throw Error("effort of input '" + m.inputs[k].label + "' is not finite at t = " + fmt(t),
                  m.inputs[k].label, t);
  }
  Bu.noalias() = B * u;
}

// [M A^T; A 0] [a; lambda] = [f + B u; c] by LU with partial pivoting, into kkt_x; returns the
// pivot ratio.
double ForwardData::solve_kkt() {
  KKT.topRightCorner(m.n1, m.m1) = A.transpose();
  KKT.bottomLeftCorner(m.m1, m.n1) = A;
  ++stats.factorizations;
  const double r = lu_kkt.compute(KKT);
  kkt_x.head(m.n1) = rhs;
  kkt_x.tail(m.m1) = c;
  lu_kkt.solve_in_place(kkt_x);
  return r;
}

// Direct accelerations by the Schur complement (M positive definite, M^-1 constant, eq. 4.1):
// with unit rows A_n = D A, c_n = D c:  (A_n M^-1 A_n^T) lambda_n = A_n M^-1 rhs - c_n,
// a = M^-1 (rhs - A_n^T lambda_n), lambda = D lambda_n. Returns (min/max of the Cholesky
// diagonal)^2 of A_n M^-1 A_n^T, a conditioning estimate of A in the mass metric; a and lambda
// are set only when it is >= kDirectAccept.
double ForwardData::solve_schur() {
  if (m.m1 == 0) {
    a.noalias() = Minv * rhs;
    return 1.0;
  }
  row_scale_of(A, col_scale, row_scale);
  An = row_scale.asDiagonal() * A;
  AMinv.noalias() = An * Minv;
  G1.noalias() = AMinv * An.transpose();
  llt_G.compute(G1);
  const auto d = llt_G.matrixLLT().diagonal();
  const double dmax = d.maxCoeff(), dmin = d.minCoeff();
  const double ratio =
      (llt_G.info() == Eigen::Success && dmax > 0) ? (dmin / dmax) * (dmin / dmax) : 0;
  if (!(ratio >= kDirectAccept)) return ratio;
  tmp0.noalias() = Minv * rhs;  // unconstrained accelerations
  r1 = -c.cwiseProduct(row_scale);
  r1.noalias() += AMinv * rhs;
  llt_G.solveInPlace(r1);  // lambda_n
  a = tmp0;
  a.noalias() -= AMinv.transpose() * r1;
  lambda = r1.cwiseProduct(row_scale);
  return ratio;
}

// out[i] = 1 / |row i of J diag(d)| (1 for a zero row).
void ForwardData::row_scale_of(const MatrixXd& J, const VectorXd& d, VectorXd& out) const {
  unit_row_scale(J, d, out);
}

// (sigma_min / sigma_max)^2 of the dimensionless N A diag(d), estimated by the pivot ratio of the
// LU of its Gram matrix: independent of the units of the rows and variables and of the size.
double ForwardData::row_conditioning() {
  if (m.m1 == 0) return 1.0;
  row_scale_of(A, col_scale, row_scale);
  An.noalias() = row_scale.asDiagonal() * A * col_scale.asDiagonal();
  G1.noalias() = An * An.transpose();
  return lu_G1.compute(G1);
}

// M + alpha A^T N^2 A (the augmented-Lagrangian matrix; N = row_scale, set by the caller).
const MatrixXd& ForwardData::H_of(double penalty) {
  H = M;
  An.noalias() = row_scale.asDiagonal() * A;
  H.noalias() += penalty * An.transpose() * An;
  return H;
}

void ForwardData::choose_independent(const VectorXd& q0, double t) {
  velocity_jacobian(m, q0, t, A, b);
  Eigen::ColPivHouseholderQR<MatrixXd> qr(A);
  const auto& p = qr.colsPermutation().indices();
  independent.assign(p.data() + (m.n1 - m.dof), p.data() + m.n1);
}

void ForwardData::accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte) {
  ++stats.rhs_evaluations;
  accel_ok = true;
  velocity_jacobian(m, q0, t, A, b);
  acceleration_rhs(m, q0, q1, t, c);
  if (baumgarte) c.noalias() -= o.baumgarte_alpha * (A * q1 - b);
  body_applied(m, q0, q1, t, local);
  f.setZero();
  scatter_local(m, local, f);
  inputs(t);
  rhs = f + Bu;
  switch (o.formulation) {
    case Formulation::augmented_lagrangian: {
      // Away from singular configurations: a direct solve (exact up to rounding); by the Schur
      // complement with the constant M^-1 when M is positive definite, else of the KKT matrix.
      // Near a singular configuration, a state slightly off the constraint manifold (a stage of
      // a Runge-Kutta step) makes c inconsistent in the direction A is losing, and the direct
      // solution blows up as 1/sigma_min: there the augmented Lagrangian takes over.
      if (has_Minv) {
        if (note_conditioning(t, q0, solve_schur()) >= kDirectAccept) break;
      } else if (note_conditioning(t, q0, row_conditioning()) >= kDirectAccept && solve_kkt() > 0 &&
                 kkt_x.allFinite()) {
        a = kkt_x.head(m.n1);
        lambda = kkt_x.tail(m.m1);
        break;
      }
      // Near a singular configuration: the augmented Lagrangian (M + alpha A^T A) stays positive
      // definite and regularizes the degenerate direction.
      row_scale_of(A, col_scale, row_scale);
      llt_H.compute(H_of(alpha));
      ++stats.factorizations;
      if (llt_H.info() != Eigen::Success)
        throw Error("forward dynamics of '" + m.name +
                        "': the mass matrix is not positive on "
                        "the mechanism's motions at t = " +
                        fmt(t) + " (a body without mass or inertia?)",
                    m.name, t);
      // Iterate in residual form, warm-started from the last accepted multipliers (reset if not
      // finite): r1 = f + B u - M a - A^T lambda, r2 = c - A a; H da = r1 + alpha A^T N^2 r2,
      // a += da, lambda -= alpha N^2 (c - A a). Written on the true residuals, the iteration also
      // refines away the rounding of the (ill-conditioned) H solves. It stops when converged or
      // when the residual no longer halves: there the penalty regularizes the constraint instead
      // of enforcing it with unbounded multipliers, and the result is flagged as inaccurate
      // (accel_ok = false) so that an explicit integrator can step over this instant.
      if (!lambda.allFinite()) lambda.setZero();
      a.setZero();
      double prev = INFINITY;
      int it = 0;
      // Both residuals are measured in dimensionless terms: the generalized forces as D r1 against
      // D (f + B u) and D A^T lambda, the constraint rows as N r2 against N c plus a tenth of the
      // accelerations D^-1 a (so that a state at rest, c = 0, is judged on the size of a).
      auto inf_scaled = [](const VectorXd& v, const VectorXd& sc, bool divide) {
        double x = 0;
        for (Eigen::Index k = 0; k < v.size(); ++k)
          x = std::max(x, std::abs(divide ? v[k] / sc[k] : v[k] * sc[k]));
        return x;
      };
      for (; it < 40; ++it) {
        tmp0 = rhs;
        tmp0.noalias() -= M * a;
        tmp1.noalias() = A.transpose() * lambda;
        tmp0 -= tmp1;  // r1
        ap.head(m.m1) = c;
        ap.head(m.m1).noalias() -= A * a;  // r2
        const double s1 = inf_scaled(rhs, col_scale, false) + inf_scaled(tmp1, col_scale, false);
        const double s2 = inf_scaled(c, row_scale, false) + 0.1 * inf_scaled(a, col_scale, true);
        const double e = std::max(inf_scaled(tmp0, col_scale, false) / (s1 + 1e-300),
                                  inf_scaled(ap.head(m.m1), row_scale, false) / (s2 + 1e-300));
        if (it > 0 && (e <= 1e-14 || e > 0.5 * prev)) break;
        prev = e;
        ap.head(m.m1).array() *= row_scale.array().square();
        tmp0.noalias() += alpha * A.transpose() * ap.head(m.m1);
        llt_H.solveInPlace(tmp0);
        a += tmp0;
        ap.head(m.m1) = c;
        ap.head(m.m1).noalias() -= A * a;
        ap.head(m.m1).array() *= row_scale.array().square();
        lambda.noalias() -= alpha * ap.head(m.m1);
      }
      stats.solver_iterations += it;
      accel_residual = prev;
      accel_ok = prev <= kAlfAccept;
      ++stats.regularized_evaluations;
      if (!lambda.allFinite()) lambda.setZero();
      break;
    }
    case Formulation::lagrange: {
      if (!projects()) note_conditioning(t, q0, row_conditioning());
      const double r = solve_kkt();
      if (r < 1e-14)
        throw Error("forward dynamics of '" + m.name + "': [M A^T; A 0] is singular at t = " +
                        fmt(t) + " s (singular configuration; use the augmented Lagrangian)",
                    m.name, t);
      a = kkt_x.head(m.n1);
      lambda = kkt_x.tail(m.m1);
      accel_ok = r >= kKktAccept;
      break;
    }
    case Formulation::null_space: {
      if (!projects()) note_conditioning(t, q0, row_conditioning());
      if (independent.empty()) choose_independent(q0, t);
      auto build = [&] {
        K.setZero();
        K.topRows(m.m1) = A;
        for (int k = 0; k < m.dof; ++k) K(m.m1 + k, independent[k]) = 1.0;
        ++stats.factorizations;
        return lu_K.compute(K);
      };
      if (build() < 1e-8) {  // partition switch: re-choose the independent variables
        choose_independent(q0, t);
        velocity_jacobian(m, q0, t, A, b);
        if (build() < 1e-14)
          throw Error("forward dynamics of '" + m.name + "': no independent coordinates at t = " +
                          fmt(t) + " s (singular configuration; use the augmented Lagrangian)",
                      m.name, t);
      }
      // a = a_p + C x with a_p = K^-1 [c; 0], C = K^-1 [0; I]; C^T M C x = C^T (f + B u - M a_p)
      ap.setZero();
      ap.head(m.m1) = c;
      lu_K.solve_in_place(ap);
      for (int k = 0; k < m.dof; ++k) {
        auto col = S.col(k);
        col.setZero();
        col[m.m1 + k] = 1.0;
        lu_K.solve_in_place(col);
      }
      CtMC.noalias() = S.transpose() * M * S;
      red.noalias() = S.transpose() * (rhs - M * ap);
      llt_red.compute(CtMC);
      if (llt_red.info() != Eigen::Success)
        throw Error("forward dynamics of '" + m.name +
                        "': the reduced mass matrix C^T M C is "
                        "not positive definite at t = " +
                        fmt(t) + " (a body without mass?)",
                    m.name, t);
      llt_red.solveInPlace(red);
      a = ap;
      a.noalias() += S * red;
      break;
    }
  }
  if (!q0.allFinite() || !q1.allFinite())
    throw Error("forward dynamics of '" + m.name +
                    "': the integrator produced a non-finite state "
                    "at t = " +
                    fmt(t),
                m.name, t);
  if (!a.allFinite())
    throw Error("forward dynamics of '" + m.name + "': non-finite accelerations at t = " + fmt(t),
                m.name, t);
}

double ForwardData::note_conditioning(double t, const VectorXd& q0, double ratio) {
  if (ratio < eval_min_ratio) {
    eval_min_ratio = ratio;
    eval_min_t = t;
    eval_min_q0 = q0;
  }
  return ratio;
}

namespace {

// Regularized Newton in the mass metric from a state within the integrator's tolerance of psi = 0
// (solve_positions.hpp): six steps, the last not tested, no line search, no finiteness test (the
// recorder's drift and finiteness checks judge the result).
NewtonOptions projection_newton(double tolerance, double penalty) {
  return {.tolerance = tolerance,
          .max_iterations = 6,
          .test_last = false,
          .step = NewtonStep::damped,
          .penalty = penalty,
          .line_search = LineSearch::none,
          .non_finite = NonFinite::ignore};
}

}  // namespace

void ForwardData::project(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel) {
  ++stats.projections;
  NewtonBuffers pos{.psi = psi,
                    .J = Psi,
                    .dx = dq0,
                    .metric = &M0,
                    .col_scale = &pos_scale,
                    .row_scale = &pos_row_scale,
                    .W = &W0,
                    .llt = &llt_G0};
  solve_positions(m, projection_newton(tol_pos, alpha), pos, t, {}, q0);
  if (m.m1 == 0) return;
  velocity_jacobian(m, q0, t, A, b);
  bool factored = false;
  for (int it = 0; it < 6; ++it) {
    r1.noalias() = A * q1;
    r1 -= b;
    if (r1.lpNorm<Eigen::Infinity>() <= tol_vel) break;
    if (!factored) {
      row_scale_of(A, col_scale, row_scale);
      llt_G1.compute(H_of(alpha));
      factored = true;
    }
    r1.array() *= row_scale.array().square();
    dq1.noalias() = -alpha * A.transpose() * r1;
    llt_G1.solveInPlace(dq1);
    q1 += dq1;
  }
}

void ForwardData::compute_reactions(double t, const VectorXd& q0, const VectorXd& q1) {
  A.setZero();
  entries.clear();
  detail::SlotRecordSink sink{A, m, entries};
  for (const auto& k : m.constraints) detail::velocity_rows(m, k, q0, t, b, sink);
  body_inertia(m, a, la);
  body_applied(m, q0, q1, t, local);
  la -= local;  // M a - f, body-local
  w.setZero();
  scatter_local(m, la, w);
  inputs(t);
  if (m.m1 > 0) {
    lam_ls = regularized_normal_solve(A, Bu - w, 1e-14);
  }
  detail::joint_reactions(m, entries, lam_ls, u, la, edge_force, edge_offset, reactions);
}

double ForwardData::pivot_indicator(double t, const VectorXd& q0) {
  velocity_jacobian(m, q0, t, A, b);
  return row_conditioning();
}

void energy_rates(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1, double* rates) {
  rates[kInputWork] = d.Bu.dot(q1);
  rates[kLoadWork] = load_power(d.m, q0, q1, t);
  // A time-dependent constraint (A q1 = b, b != 0) moves its bodies: its force -A^T lambda =
  // M a - f - B u does the work -lambda^T b. Zero (not evaluated) for fixed constraints.
  rates[kConstraintWork] =
      d.m.m1 > 0 && d.b.lpNorm<Eigen::Infinity>() > 0 ? q1.dot(d.M * d.a - d.f - d.Bu) : 0.0;
  rates[kDissipated] = damping_power(d.m, q0, q1);
}

// An integrator that does not project (cvode_adams, baumgarte) cannot hold the constraints
// through a singular configuration: the drift in the direction the Jacobian loses is not
// corrected and the run can leave its branch without any other sign (the double four-bar on
// cvode_adams: tips 1 m off, residuals 1e-7). So such a run stops with an error as soon as one of
// its evaluations comes near one (below o.singular_warning).
void Recorder::check_unprojected() {
  if (d.projects() || m.m1 == 0 || !(d.eval_min_ratio < d.o.singular_warning)) return;
  velocity_jacobian(m, d.eval_min_q0, d.eval_min_t, d.A, d.b);
  const SingularDirection s =
      singular_direction(d.A, d.col_scale, m.velocity_row_labels, m.rate_labels);
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
  velocity_jacobian(m, q0, t, d.A, d.b);
  r.residuals(k, 1) = m.m1 ? (d.A * q1 - d.b).lpNorm<Eigen::Infinity>() : 0.0;
  check_drift(t, q0);
  const double piv = d.pivot_indicator(t, q0);
  d.stats.min_pivot_ratio = std::min(d.stats.min_pivot_ratio, piv);
  if (piv < d.o.singular_warning) {
    if (!near) near_first = t;
    near_last = t;
    if (!near || piv < near_min) {
      near_min = piv;
      near_t = t;
      const SingularDirection s =
          singular_direction(d.A, d.col_scale, m.velocity_row_labels, m.rate_labels);
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
  position_jacobian(m, q0, t, d.psi, d.Psi);
  d.row_scale_of(d.Psi, d.pos_scale, d.pos_row_scale);
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

detail::RunBudget::Settings forward_budget(const Model& m, const ForwardOptions& o,
                                           std::string hint) {
  return {.run = "forward dynamics of '" + m.name + "' (" + to_string(o.integrator) + ")",
          .name = m.name,
          .t0 = o.t0,
          .t1 = o.t1,
          .max_steps = o.max_steps,
          .max_seconds = o.max_seconds,
          .monitor = o.monitor,
          .interval = o.monitor_interval,
          .hint = std::move(hint)};
}

}  // namespace mo2d::detail
