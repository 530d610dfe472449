// Forward dynamics, one evaluation: accelerations in three formulations, projection on the
// constraint manifolds (the stages of ForwardData, mo2d/forward_data.hpp) and
// forward_accelerations; reactions and joint friction: forward_reactions.cpp. The recorder:
// recorder.cpp.
#include "mo2d/forward_data.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <sstream>

#include "constraints/constraints.hpp"
#include "dynamics/reactions.hpp"
#include "forward/alf_iterate.hpp"
#include "forward/forward_run.hpp"
#include "forward/sparse_engine.hpp"
#include "kinematics/conditioning.hpp"
#include "kinematics/solve_positions.hpp"
#include "linalg/small_lu.hpp"
#include "linalg/structured_schur.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/quasi_steady.hpp"

namespace mo2d {

namespace detail {

VectorXd regularized_normal_solve(const MatrixXd& J, const VectorXd& x, double eps) {
  MatrixXd G = J * J.transpose();
  G.diagonal().array() += eps * std::max(1.0, G.diagonal().maxCoeff());
  return G.llt().solve(J * x);
}

}  // namespace detail

using detail::fmt;
using detail::regularized_normal_solve;

namespace {

// The vectors of both paths (one evaluation, the projection, the reactions), the input matrix,
// the compiled effort laws and the column scaling.
void init_vectors(ForwardData& d) {
  d.B = input_matrix(d.m);
  d.b = d.c = d.r1 = d.lambda = d.lam_ls = d.ls_d = VectorXd::Zero(d.m.m1);
  d.f = d.Bu = d.rhs = d.a = d.ap = d.tmp0 = d.tmp1 = d.dq1 = d.w = VectorXd::Zero(d.m.n1);
  d.f_extra = VectorXd::Zero(d.m.n1);
  d.ls_x = d.ls_r = VectorXd::Zero(d.m.n1);
  d.u = VectorXd::Zero(d.m.n_inputs());
  d.effort_laws.resize(d.m.n_inputs());
  for (int k = 0; k < d.m.n_inputs() && k < static_cast<int>(d.o.efforts.size()); ++k)
    d.effort_laws[k] = compile_law(
        d.m, d.o.efforts[k], "effort of input '" + d.m.inputs[k].label + "'", d.m.inputs[k].label);
  d.psi = VectorXd::Zero(d.m.m0);
  d.dq0 = VectorXd::Zero(d.m.n0);
  d.local = d.la = VectorXd::Zero(d.m.n_slots);
  d.row_scale = VectorXd::Ones(d.m.m1);
  d.pos_row_scale = VectorXd::Ones(d.m.m0);
  d.col_scale = column_scaling(d.m);
  d.pos_scale = d.col_scale.head(d.m.n0);
  d.eval_min_q0 = d.m.q0;
  d.edge_force.assign(detail::merge_edge_layout(d.m, d.edge_offset), 0.0);
  d.reactions = VectorXd::Zero(d.m.n_reactions());
  d.friction = d.friction_next = VectorXd::Zero(static_cast<int>(d.m.frictions.size()));
}

}  // namespace

ForwardData::ForwardData(const Model& model, const ForwardOptions& opt) : m(model), o(opt) {
  init_vectors(*this);
  quasi_steady_ = has_quasi_steady(m);
  if (uses_sparse(m, o)) {
    init_sparse();
    return;
  }
  M = mass_matrix(m);
  A = MatrixXd::Zero(m.m1, m.n1);
  Psi = MatrixXd::Zero(m.m0, m.n0);
  H = MatrixXd::Zero(m.n1, m.n1);
  An = MatrixXd::Zero(m.m1, m.n1);
  G1 = MatrixXd::Zero(m.m1, m.m1);
  G_ls = MatrixXd::Zero(m.m1, m.m1);
  // its storage allocated here, not in the hot path: a factorization of the identity (not a
  // move-assignment of LLT(m1), which copies its uninitialized info: UBSan's invalid enum load)
  llt_ls.compute(MatrixXd::Identity(m.m1, m.m1));
  lu_G1_ = std::make_unique<detail::SmallLU>(m.m1);
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
  if (has_Minv) {
    schur_ = std::make_unique<detail::StructuredSchur>();
    // A's pattern: the entries the constraints write at q0 (the first fill grows the empty one)
    schur_->analyse(std::vector<std::vector<int>>(m.m1), Minv);
    fill_velocity_schur(0.0, m.q0);
  }
  KKT = MatrixXd::Zero(m.n1 + m.m1, m.n1 + m.m1);
  KKT.topLeftCorner(m.n1, m.n1) = M;
  kkt_x = VectorXd::Zero(m.n1 + m.m1);
  lu_kkt_ = std::make_unique<detail::SmallLU>(m.n1 + m.m1);
  K = MatrixXd::Zero(m.n1, m.n1);
  lu_K_ = std::make_unique<detail::SmallLU>(m.n1);
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
}

ForwardData::~ForwardData() = default;

// u = the effort laws at (t, q0, q1): a law that reads the state is a feedback (a controller).
void ForwardData::inputs(double t, const VectorXd& q0, const VectorXd& q1) {
  for (int k = 0; k < m.n_inputs(); ++k) {
    u[k] = law_value(m, effort_laws[k], q0, q1, t, "effort of input", m.inputs[k].label);
    if (!std::isfinite(u[k]))
      throw Error("effort of input '" + m.inputs[k].label + "' is not finite at t = " + fmt(t),
                  m.inputs[k].label, t);
  }
  Bu.noalias() = B * u;
}

void ForwardData::set_inputs(const VectorXd& efforts, double t) {
  for (int k = 0; k < m.n_inputs(); ++k) {
    u[k] = efforts[k];
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
  const double r = lu_kkt_->compute(KKT);
  kkt_x.head(m.n1) = rhs;
  kkt_x.tail(m.m1) = c;
  lu_kkt_->solve_in_place(kkt_x);
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
  // the pattern covers A: fill_velocity_rows grew it if the state wrote an entry outside it
  assert(schur_->covers(A));
  const double ratio = schur_->factor(A, col_scale, row_scale);
  if (!(ratio >= kDirectAccept)) return ratio;
  schur_->solve(rhs, c, row_scale, r1, a, lambda);
  return ratio;
}

// out[i] = 1 / |row i of J diag(d)| (1 for a zero row).
void ForwardData::row_scale_of(const MatrixXd& J, const VectorXd& d, VectorXd& out) const {
  detail::unit_row_scale(J, d, out);
}

// (sigma_min / sigma_max)^2 of the dimensionless N A diag(d), estimated by the pivot ratio of the
// LU of its Gram matrix: independent of the units of the rows and variables and of the size.
double ForwardData::row_conditioning() {
  if (m.m1 == 0) return 1.0;
  row_scale_of(A, col_scale, row_scale);
  An.noalias() = row_scale.asDiagonal() * A * col_scale.asDiagonal();
  G1.noalias() = An * An.transpose();
  return lu_G1_->compute(G1);
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

// The evaluation stage: A, b, c (with Baumgarte's feedback if asked), the applied forces f, the
// efforts (from the options' functions at t, or given), then a and lambda by the formulation.
void ForwardData::accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte) {
  load(t, q0, q1, baumgarte);
  inputs(t, q0, q1);
  evaluate(t, q0, q1);
}

void ForwardData::accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte,
                                const VectorXd& efforts) {
  load(t, q0, q1, baumgarte);
  set_inputs(efforts, t);
  evaluate(t, q0, q1);
}

// Velocity rows, acceleration right-hand side and applied forces at (t, q0, q1).
void ForwardData::load(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte) {
  ++stats.rhs_evaluations;
  accel_ok = true;
  eval_ratio = INFINITY;
  fill_velocity_rows(t, q0);
  acceleration_rhs(m, q0, q1, t, c);
  if (baumgarte) {
    velocity_residual_into(q1, r1);
    c.noalias() -= o.baumgarte_alpha * r1;
  }
  body_applied(m, q0, q1, t, local);
  f.setZero();
  scatter_local(m, local, f);
  if (o.extra_forces) {  // a stage above (contact): its forces and their dissipation
    f_extra.setZero();
    extra_dissipation = o.extra_forces(t, q0, q1, f_extra);
    f += f_extra;
  }
}

// a and lambda from rhs = f + B u (+ the joint friction) by the options' formulation; checks
// that they are finite.
void ForwardData::evaluate(double t, const VectorXd& q0, const VectorXd& q1) {
  if (m.frictions.empty()) {
    rhs = f + Bu;
    solve_formulation(t, q0);
  } else {
    evaluate_friction(t, q0, q1);
  }
  if (!q0.allFinite() || !q1.allFinite() || !a.allFinite()) throw_not_finite(t, q0, q1);
}

// The state or the accelerations are not finite: the first such variable and the largest rate,
// so that a run that diverged (steps too long for its time scales) says so.
void ForwardData::throw_not_finite(double t, const VectorXd& q0, const VectorXd& q1) const {
  std::string what = "non-finite accelerations", label;
  auto first = [&](const VectorXd& x, const std::vector<std::string>& labels, const char* suffix) {
    for (Eigen::Index i = 0; label.empty() && i < x.size(); ++i)
      if (!std::isfinite(x[i])) label = labels[static_cast<size_t>(i)] + suffix;
  };
  first(q0, m.coordinate_labels, "");
  first(q1, m.rate_labels, "");
  if (!label.empty()) what = "the integrator produced a non-finite state";
  first(a, m.rate_labels, ".dot");
  Eigen::Index k = 0;
  const double largest = q1.size() ? q1.cwiseAbs().maxCoeff(&k) : 0;
  throw Error("forward dynamics of '" + m.name + "': " + what + " at t = " + fmt(t) + " s ('" +
                  label + "'; the largest rate " +
                  (q1.size() ? m.rate_labels[static_cast<size_t>(k)] : "") + " = " + fmt(largest) +
                  "): the run diverged, its steps too long for the motion's time scales (a "
                  "stiff or huge load?), or a value overflowed",
              label, t);
}

void ForwardData::solve_formulation(double t, const VectorXd& q0) {
  switch (o.formulation) {
    case Formulation::augmented_lagrangian:
      solve_augmented_lagrangian(t, q0);
      break;
    case Formulation::lagrange:
      solve_lagrange(t, q0);
      break;
    case Formulation::null_space:
      solve_null_space(t, q0);
      break;
  }
}

void ForwardData::solve_augmented_lagrangian(double t, const VectorXd& q0) {
  // Away from singular configurations: a direct solve (exact up to rounding); by the Schur
  // complement with the constant M^-1 when M is positive definite, else of the KKT matrix.
  // Near a singular configuration, a state slightly off the constraint manifold (a stage of
  // a Runge-Kutta step) makes c inconsistent in the direction A is losing, and the direct
  // solution blows up as 1/sigma_min: there the augmented Lagrangian takes over.
  if (sparse_) {
    solve_sparse(t, q0);
    return;
  }
  if (has_Minv) {
    if (note_conditioning(t, q0, solve_schur()) >= kDirectAccept) return;
  } else if (note_conditioning(t, q0, row_conditioning()) >= kDirectAccept && solve_kkt() > 0 &&
             kkt_x.allFinite()) {
    a = kkt_x.head(m.n1);
    lambda = kkt_x.tail(m.m1);
    return;
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
  if (!lambda.allFinite()) lambda.setZero();
  double prev = INFINITY;
  const int it = detail::alf_iterate(
      A, M, [this](VectorXd& x) { llt_H.solveInPlace(x); }, *this, prev);
  stats.solver_iterations += it;
  accel_residual = prev;
  accel_ok = prev <= kAlfAccept;
  ++stats.regularized_evaluations;
  if (!lambda.allFinite()) lambda.setZero();
}

void ForwardData::solve_lagrange(double t, const VectorXd& q0) {
  if (!projects()) note_conditioning(t, q0, row_conditioning());
  const double r = solve_kkt();
  if (r < 1e-14)
    throw Error("forward dynamics of '" + m.name + "': [M A^T; A 0] is singular at t = " + fmt(t) +
                    " s (singular configuration; use the augmented Lagrangian)",
                m.name, t);
  a = kkt_x.head(m.n1);
  lambda = kkt_x.tail(m.m1);
  accel_ok = r >= kKktAccept;
}

void ForwardData::solve_null_space(double t, const VectorXd& q0) {
  if (!projects()) note_conditioning(t, q0, row_conditioning());
  if (independent.empty()) choose_independent(q0, t);
  auto build = [&] {
    K.setZero();
    K.topRows(m.m1) = A;
    for (int k = 0; k < m.dof; ++k) K(m.m1 + k, independent[k]) = 1.0;
    ++stats.factorizations;
    return lu_K_->compute(K);
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
  lu_K_->solve_in_place(ap);
  for (int k = 0; k < m.dof; ++k) {
    auto col = S.col(k);
    col.setZero();
    col[m.m1 + k] = 1.0;
    lu_K_->solve_in_place(col);
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
}

double ForwardData::note_conditioning(double t, const VectorXd& q0, double ratio) {
  eval_ratio = ratio;
  if (ratio < eval_min_ratio) {
    eval_min_ratio = ratio;
    eval_min_t = t;
    eval_min_q0 = q0;
  }
  return ratio;
}

namespace {

using detail::LineSearch;
using detail::NewtonBuffers;
using detail::NewtonOptions;
using detail::NewtonStep;
using detail::NonFinite;

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
  if (quasi_steady_)
    detail::settle_quasi_steady(*this, t, q0, q1, tol_pos, tol_vel);
  else
    project_held(t, q0, q1, tol_pos, tol_vel);
}

void ForwardData::project_held(double t, VectorXd& q0, VectorXd& q1, double tol_pos,
                               double tol_vel) {
  ++stats.projections;
  if (sparse_) {
    project_sparse(t, q0, q1, tol_pos, tol_vel);
    return;
  }
  NewtonBuffers pos{.psi = psi,
                    .J = Psi,
                    .dx = dq0,
                    .metric = &M0,
                    .col_scale = &pos_scale,
                    .row_scale = &pos_row_scale,
                    .W = &W0,
                    .llt = &llt_G0};
  detail::solve_positions(m, projection_newton(tol_pos, alpha), pos, t, {}, q0);
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

double ForwardData::pivot_indicator(double t, const VectorXd& q0) {
  fill_velocity_rows(t, q0);
  if (sparse_) {
    detail::SparseEngine::unit_row_scale(sparse_->A, col_scale, row_scale);
    return sparse_->conditioning(col_scale, row_scale);
  }
  return row_conditioning();
}

const VectorXd& forward_accelerations(const Model& model, ForwardData& d, double t,
                                      const VectorXd& q0, const VectorXd& q1,
                                      const VectorXd& efforts) {
  if (&model != &d.m)
    throw Error(
        "forward_accelerations: the workspace was built for another model ('" + d.m.name + "')",
        model.name);
  if (q0.size() != model.n0 || q1.size() != model.n1 || efforts.size() != model.n_inputs())
    throw Error("forward_accelerations of '" + model.name + "': the state (" +
                    std::to_string(q0.size()) + " coordinates, " + std::to_string(q1.size()) +
                    " quasi-velocities) or the efforts (" + std::to_string(efforts.size()) +
                    ") do not match the model (" + std::to_string(model.n0) + ", " +
                    std::to_string(model.n1) + ", " + std::to_string(model.n_inputs()) + ")",
                model.name, t);
  d.accelerations(t, q0, q1, d.o.integrator == Integrator::baumgarte, efforts);
  return d.a;
}

}  // namespace mo2d
