// Exact sensitivities of inverse dynamics to mass data and load coefficients
// (mo2d/sensitivity.hpp): per sample, the derivative of the body-local force l = M a1 - f from the
// parameter models, then the run's own factorizations map it to the efforts, multipliers and
// reactions.
#include <algorithm>
#include <cmath>
#include <string>

#include "dynamics/reactions.hpp"
#include "inverse/inverse_stages.hpp"
#include "linalg/pattern_lu.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/sensitivity.hpp"
#include "run/format.hpp"

namespace mo2d {

namespace {

using detail::fmt;

// l = M a1 - f(q0, q1, t), body-local, for the model `pm` at the state of sample d.
void local_force(const Model& pm, const InverseData& d, Eigen::VectorXd& l,
                 Eigen::VectorXd& scratch) {
  body_inertia(pm, d.a1, l);
  body_applied(pm, d.q0, d.q1, d.t, scratch);
  l -= scratch;
}

// The body owning body-local slot `slot`.
const std::string& slot_body(const Model& m, Eigen::Index slot) {
  for (const Body& b : m.bodies)
    if (slot >= b.offset && slot < b.offset + b.slots()) return b.name;
  return m.name;
}

// Whether two row vectors differ beyond rounding (4 ulps of the larger entry).
bool rows_differ(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (std::abs(a[k] - b[k]) > 4e-16 * std::max(std::abs(a[k]), std::abs(b[k])) + 1e-300)
      return true;
  return false;
}

// A model with user constraints: its parameter models' constraint rows must equal the run's at
// the sample (the closures cannot be compared before the run).
void check_user_rows(const Model& m, const InverseData& d, const ParameterModels& p,
                     SensitivityData& s) {
  position_residual(m, d.q0, d.t, s.psi);
  const Eigen::VectorXd psi0 = s.psi;  // (user constraints only: allocation accepted here)
  acceleration_rhs(m, d.q0, d.q1, d.t, s.cc);
  const Eigen::VectorXd c0 = s.cc;
  velocity_jacobian(m, d.q0, d.t, s.A, s.bb);
  const Eigen::MatrixXd A0 = s.A;
  const Eigen::VectorXd b0 = s.bb;
  for (const Model& pm : p.at) {
    position_residual(pm, d.q0, d.t, s.psi);
    acceleration_rhs(pm, d.q0, d.q1, d.t, s.cc);
    velocity_jacobian(pm, d.q0, d.t, s.A, s.bb);
    const Eigen::VectorXd a = Eigen::Map<const Eigen::VectorXd>(s.A.data(), s.A.size());
    const Eigen::VectorXd a0 = Eigen::Map<const Eigen::VectorXd>(A0.data(), A0.size());
    if (rows_differ(s.psi, psi0) || rows_differ(s.cc, c0) || rows_differ(s.bb, b0) ||
        rows_differ(a, a0))
      throw Error("sensitivity to '" + p.name + "': it changes the constraints at t = " + fmt(d.t) +
                      " s (a user constraint reads it); geometric parameters are not supported "
                      "yet",
                  p.name, d.t);
  }
}

// The derivative of l to parameter p (s.dl) by the one-sided three-point formula, after checking
// that its third difference is rounding (dependence of degree <= 2).
void local_derivative(const Model& m, const InverseData& d, const ParameterModels& p,
                      SensitivityData& s) {
  local_force(p.at[0], d, s.l1, s.local);
  local_force(p.at[1], d, s.l2, s.local);
  local_force(p.at[2], d, s.l3, s.local);
  const double scale = std::max({s.l0.lpNorm<Eigen::Infinity>(), s.l1.lpNorm<Eigen::Infinity>(),
                                 s.l2.lpNorm<Eigen::Infinity>(), s.l3.lpNorm<Eigen::Infinity>()});
  s.dl = s.l3 - 3 * s.l2 + 3 * s.l1 - s.l0;  // third difference
  Eigen::Index worst = 0;
  const double third = s.dl.size() ? s.dl.cwiseAbs().maxCoeff(&worst) : 0.0;
  if (!(third <= kSensitivityThirdDifference * scale))
    throw Error("sensitivity to '" + p.name + "': the forces on body '" + slot_body(m, worst) +
                    "' at t = " + fmt(d.t) +
                    " s are not a polynomial of degree <= 2 in it (third difference " + fmt(third) +
                    " of forces up to " + fmt(scale) +
                    "): only parameters that enter the mass data and loads linearly or "
                    "quadratically (masses, inertias, centres of mass, spring and damper "
                    "coefficients, gravity, load coefficients) have exact sensitivities",
                p.name, d.t);
  s.dl = (-3 * s.l0 + 4 * s.l1 - s.l2) / (2 * p.step);
}

}  // namespace

SensitivityData::SensitivityData(const Model& m, std::span<const ParameterModels> parameters) {
  const int k = static_cast<int>(parameters.size());
  efforts = Eigen::MatrixXd::Zero(m.n_inputs(), k);
  reactions = Eigen::MatrixXd::Zero(m.n_reactions(), k);
  l0 = l1 = l2 = l3 = dl = local = Eigen::VectorXd::Zero(m.n_slots);
  w = rhs = z = Eigen::VectorXd::Zero(m.n1);
  Ctw = du = Eigen::VectorXd::Zero(m.dof);
  std::vector<int> offsets;
  edge_force.assign(detail::merge_edge_layout(m, offsets), 0.0);
  for (const Constraint& c : m.constraints)
    user_rows = user_rows || c.kind() == ConstraintKind::user_position ||
                c.kind() == ConstraintKind::user_velocity;
  psi = Eigen::VectorXd::Zero(m.m0);
  bb = cc = Eigen::VectorXd::Zero(m.m1);
  A = Eigen::MatrixXd::Zero(m.m1, m.n1);
}

void inverse_sensitivity_sample(const Model& m, const InverseData& d,
                                std::span<const ParameterModels> parameters, SensitivityData& s) {
  local_force(m, d, s.l0, s.local);
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    const ParameterModels& p = parameters[j];
    if (s.user_rows) check_user_rows(m, d, p, s);
    local_derivative(m, d, p, s);
    // du = (C^T B)^-1 C^T P^T dl (Theorem 4.3, differentiated: C, B and K do not depend on p)
    s.w.setZero();
    scatter_local(m, s.dl, s.w);
    s.Ctw.noalias() = d.S.transpose().lazyProduct(s.w);
    s.du = d.lu_u.solve(s.Ctw);
    s.efforts.col(static_cast<Eigen::Index>(j)) = s.du;
    // K^T [dlambda; dmu] = B du - P^T dl, through the dimensionless factorization (as the run)
    s.rhs.noalias() = d.B.lazyProduct(s.du);
    s.rhs -= s.w;
    s.z = s.rhs;
    s.z.array() *= d.col_scale.array();
    d.lu_K->solve_transpose_in_place(s.z);
    s.z.array() *= d.k_row.array();
    detail::joint_reactions(m, d.entries, s.z.head(m.m1), s.du, s.dl, s.edge_force, d.edge_offset,
                            s.reactions.col(static_cast<Eigen::Index>(j)));
  }
  if (!s.efforts.allFinite() || !s.reactions.allFinite())
    throw Error("the sensitivities of '" + m.name + "' are not finite at t = " + fmt(d.t) + " s",
                m.name, d.t);
}

InverseSensitivity inverse_dynamics_sensitivity(const Model& m,
                                                std::span<const Prescribed> prescribed,
                                                const InverseOptions& options,
                                                std::span<const ParameterModels> parameters,
                                                Trajectory& r) {
  for (const ParameterModels& p : parameters) check_parameter_models(m, p);
  InverseData d(m, prescribed, options);
  SensitivityData s(m, parameters);
  const int N = options.samples, k = static_cast<int>(parameters.size());
  InverseSensitivity out;
  for (const ParameterModels& p : parameters) {
    out.parameters.push_back(p.name);
    out.efforts.emplace_back(N, m.n_inputs());
    out.reactions.emplace_back(N, m.n_reactions());
  }
  r = detail::inverse_run(m, d, options, "inverse dynamics of '" + m.name + "' with sensitivities",
                          [&](int i) {
                            inverse_sensitivity_sample(m, d, parameters, s);
                            for (int j = 0; j < k; ++j) {
                              out.efforts[j].row(i) = s.efforts.col(j).transpose();
                              out.reactions[j].row(i) = s.reactions.col(j).transpose();
                            }
                          });
  return out;
}

}  // namespace mo2d
