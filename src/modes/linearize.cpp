// Linearization about a reference state (Orsino §4.5, eq. 4.24: dx/dt = G x + H u), in the
// independent coordinates x = (z, w) of src/modes/select.cpp (mo2d/modes.hpp has the equations):
//   dz/dt = w.head(p)                                  (z are coordinates, w their rates first)
//   dw/dt = E a1(t, q0(z), q1(z, w), u)                (E: the rows velocity_vars)
// so G = [0 [I 0]; E (da/dq0 dq0/dz + da/dq1 dq1/dz)  E da/dq1 dq1/dw], H = [0; E da/du].
// da/dq0 and da/dq1 come from acceleration_jacobian (mo2d/jacobian.hpp); da/du: the accelerations
// are affine in the efforts (M a = f + B u - A^T lambda, A a = c), so a central difference of
// them in u is exact up to rounding (joint friction, which follows the reactions, aside).
#include <cmath>

#include "mo2d/error.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/jacobian.hpp"
#include "mo2d/kinematics.hpp"
#include "modes/modes_internal.hpp"

namespace mo2d {

namespace {

void check_finite(const MatrixXd& X, const char* name, const StateSpace& ss) {
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = 0; j < X.cols(); ++j)
      if (!std::isfinite(X(i, j)))
        throw Error(std::string("linearization: ") + name + "(" + std::to_string(i) + ", " +
                        std::to_string(j) + ") is not finite",
                    name, ss.t);
}

// H = [0; E da/du], column k from efforts u* +- h e_k.
void input_matrix_of(ForwardData& d, const State& ref, StateSpace& ss) {
  const int nu = d.m.n_inputs();
  ss.H = MatrixXd::Zero(ss.n(), nu);
  VectorXd u = ss.u, ap(d.m.n1);
  for (int k = 0; k < nu; ++k) {
    const double h = 1e-3 * std::max(1.0, std::abs(ss.u[k]));
    u[k] = ss.u[k] + h;
    d.accelerations(ref.t, ref.q0, ref.q1, false, u);
    ap = d.a;
    u[k] = ss.u[k] - h;
    d.accelerations(ref.t, ref.q0, ref.q1, false, u);
    u[k] = ss.u[k];
    for (int i = 0; i < ss.dof; ++i)
      ss.H(ss.p + i, k) = (ap[ss.velocity_vars[i]] - d.a[ss.velocity_vars[i]]) / (2 * h);
  }
}

// One output row of C: a coordinate, a quasi-velocity, or a derived quantity (central
// differences of quantity_value along the chart's tangents).
Eigen::RowVectorXd output_row(const Model& m, const State& ref, const StateSpace& ss,
                              const std::string& label) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(ss.n());
  if (auto it = m.coordinate_index.find(label); it != m.coordinate_index.end()) {
    row.head(ss.p) = ss.dq0_dz.row(it->second);
    return row;
  }
  if (auto it = m.rate_index.find(label); it != m.rate_index.end()) {
    row.head(ss.p) = ss.dq1_dz.row(it->second);
    row.tail(ss.dof) = ss.dq1_dw.row(it->second);
    return row;
  }
  auto it = m.quantities.find(label);
  if (it == m.quantities.end())
    throw Error("linearization output '" + label + "' is not a coordinate, a quasi-velocity or a " +
                    "quantity of '" + m.name + "' (body angles, joint angles and rates, spring " +
                    "lengths, named points)",
                label);
  const Quantity& q = it->second;
  const VectorXd d = column_scaling(m);
  for (int j = 0; j < ss.n(); ++j) {
    const bool pos = j < ss.p;
    const double h = pos ? 1e-6 * m.scale * d[ss.coordinate_vars[j]] : 1e-6;
    const VectorXd v0 = pos ? VectorXd(ss.dq0_dz.col(j)) : VectorXd::Zero(m.n0);
    const VectorXd v1 = pos ? VectorXd(ss.dq1_dz.col(j)) : VectorXd(ss.dq1_dw.col(j - ss.p));
    const double yp = quantity_value(m, q, ref.q0 + h * v0, ref.q1 + h * v1);
    const double ym = quantity_value(m, q, ref.q0 - h * v0, ref.q1 - h * v1);
    row[j] = (yp - ym) / (2 * h);
  }
  return row;
}

}  // namespace

StateSpace linearize(const Model& m, const State& ref, const LinearizeOptions& o) {
  const std::string what = "linearization of '" + m.name + "'";
  detail::check_modes_budget(what, m, o.forward.max_seconds, o.forward.max_memory, 1, false);
  detail::RunBudget budget(detail::modes_budget(what, m, ref.t, o.forward.max_seconds));
  return detail::linearize_within(m, ref, o, budget);
}

StateSpace detail::linearize_within(const Model& m, const State& ref, const LinearizeOptions& o,
                                    RunBudget& budget) {
  if (ref.q0.size() != m.n0 || ref.q1.size() != m.n1)
    throw Error("linearization of '" + m.name + "': the state has the wrong size", m.name, ref.t);
  if (!ref.q0.allFinite() || !ref.q1.allFinite())
    throw Error("linearization of '" + m.name + "': the reference state is not finite", m.name,
                ref.t);
  StateSpace ss;
  ss.t = ref.t;
  ss.q0 = ref.q0;
  ss.q1 = ref.q1;
  long stage = 0;
  budget.check(ref.t, stage++, 0);
  detail::choose_coordinates(m, ref, o, ss);
  budget.check(ref.t, stage++, 0);
  detail::tangent_bases(m, ref, ss);
  budget.check(ref.t, stage++, 0);

  // the Jacobian of the accelerations is dense (its columns, G): a dense workspace, whatever the
  // run's linear algebra (a large mechanism's runs are sparse)
  ForwardOptions dense = o.forward;
  dense.linear_algebra = LinearAlgebra::dense;
  ForwardData d(m, dense);
  AccelerationJacobian J;
  acceleration_jacobian(d, ref.t, ref.q0, ref.q1, J);
  budget.check(ref.t, stage++, 0);
  if (!J.approximate.empty()) ss.approximate = "da/dq: " + J.approximate + ss.approximate;
  ss.u = d.u;
  const VectorXd a = d.a;
  const int p = ss.p, n = ss.n();
  ss.G = MatrixXd::Zero(n, n);
  ss.G.block(0, p, p, p).setIdentity();
  const MatrixXd dz = J.da_dq0 * ss.dq0_dz + J.da_dq1 * ss.dq1_dz;  // n1 x p
  const MatrixXd dw = J.da_dq1 * ss.dq1_dw;                         // n1 x dof
  ss.drift = VectorXd::Zero(n);
  for (int i = 0; i < p; ++i) ss.drift[i] = ref.q1[ss.coordinate_vars[i]];
  for (int i = 0; i < ss.dof; ++i) {
    const int k = ss.velocity_vars[i];
    ss.G.block(p + i, 0, 1, p) = dz.row(k);
    ss.G.block(p + i, p, 1, ss.dof) = dw.row(k);
    ss.drift[p + i] = a[k];
  }
  ss.inputs = m.input_labels();
  input_matrix_of(d, ref, ss);
  budget.check(ref.t, stage++, 0);
  ss.outputs = o.outputs;
  ss.C.resize(static_cast<Eigen::Index>(o.outputs.size()), n);
  for (size_t i = 0; i < o.outputs.size(); ++i)
    ss.C.row(static_cast<Eigen::Index>(i)) = output_row(m, ref, ss, o.outputs[i]);
  ss.D = MatrixXd::Zero(ss.C.rows(), m.n_inputs());
  check_finite(ss.G, "G", ss);
  check_finite(ss.H, "H", ss);
  check_finite(ss.C, "C", ss);
  return ss;
}

VectorXd chart_positions(const Model& m, const StateSpace& ss, const VectorXd& dz) {
  VectorXd q = ss.q0;
  for (int i = 0; i < ss.p; ++i) q[ss.coordinate_vars[i]] += dz[i];
  return assemble(m, q, ss.t, ss.coordinate_vars, 1e-13);
}

}  // namespace mo2d
