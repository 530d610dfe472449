// The inverse-dynamics workspace: the check of the options (time grid, budget, memory) and the
// construction of InverseData (the prescribed coordinates, the free columns, the buffers of one
// sample).
#include <algorithm>
#include <cmath>
#include <string>

#include "constraints/constraints.hpp"
#include "dynamics/reactions.hpp"
#include "linalg/pattern_lu.hpp"
#include "mo2d/budget.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/kinematics.hpp"
#include "run/format.hpp"

namespace mo2d {

namespace {

using detail::fmt;

// Dense matrices of the inverse workspace (J, K and their factorizations: each PatternLU holds
// three matrices of its size, S, B) and the results.
double inverse_memory_bytes(const Model& m, const InverseOptions& o) {
  const double n0 = m.n0, n1 = m.n1, m0 = m.m0;
  const double dense = 4 * m0 * n0 + 5 * n1 * n1 + 2 * n1 * m.dof + n1 * m.n_inputs();
  const double columns = n0 + 2 * n1 + m.n_inputs() + m.n_reactions() + 4;
  return 8 * (dense + static_cast<double>(o.samples) * columns);
}

}  // namespace

void check_inverse_options(const Model& m, const InverseOptions& o) {
  if (!(o.samples >= 1))
    throw Error("inverse dynamics: samples must be >= 1 (got " + std::to_string(o.samples) + ")",
                "samples");
  if (o.t1 < o.t0)
    throw Error("inverse dynamics: need t0 <= t1 (t0 = " + fmt(o.t0) + ", t1 = " + fmt(o.t1) + ")",
                "t1");
  check_time_grid("inverse dynamics", o.t0, o.t1, o.samples);
  if (o.samples > 1 && !(o.t1 > o.t0))
    throw Error("inverse dynamics: " + std::to_string(o.samples) + " samples need a duration > 0",
                "t1");
  if (std::isnan(o.max_seconds))
    throw Error("inverse dynamics: max_seconds is not a number", "max_seconds");
  check_magnitudes(m);
  check_memory("inverse dynamics of '" + m.name + "' (" + std::to_string(o.samples) + " samples)",
               inverse_memory_bytes(m, o), o.max_memory, model_sizes(m), "max_memory");
}

InverseData::InverseData(const Model& m, std::span<const Prescribed> prescribed,
                         const InverseOptions& o)
    : options(o) {
  if (static_cast<int>(prescribed.size()) != m.dof) {
    std::string list;
    for (const auto& p : prescribed) list += (list.empty() ? "" : ", ") + p.coordinate;
    throw Error("'" + m.name + "' has " + std::to_string(m.dof) + " degree(s) of freedom but " +
                    std::to_string(prescribed.size()) + " coordinate(s) are prescribed" +
                    (list.empty() ? "" : " (" + list + ")"),
                m.name);
  }
  if (m.n_inputs() != m.dof) {
    std::string list;
    for (const auto& in : m.inputs) list += (list.empty() ? "" : ", ") + in.label;
    throw Error("inverse dynamics needs one actuator per degree of freedom: '" + m.name + "' has " +
                    std::to_string(m.dof) + " DOF and " + std::to_string(m.n_inputs()) +
                    " actuated input(s)" + (list.empty() ? "" : " (" + list + ")"),
                m.name);
  }
  if (m.n0 - m.m0 != m.dof)
    throw Error("inverse dynamics of '" + m.name +
                    "' needs positions determined by the prescribed "
                    "coordinates, but its position-level DOF (" +
                    std::to_string(m.n0 - m.m0) + ") differs from its velocity-level DOF (" +
                    std::to_string(m.dof) +
                    "): a coordinate or constraint given only at velocity level (non-holonomic) "
                    "leaves positions undetermined",
                m.name);
  check_inverse_options(m, o);
  colmap.assign(m.n0, 0);
  for (const auto& p : prescribed) {
    const int k = m.coordinate(p.coordinate);
    if (!p.motion)
      throw Error("prescribed coordinate '" + p.coordinate + "' has no motion", p.coordinate);
    if (colmap[k] < 0)
      throw Error("coordinate '" + p.coordinate + "' is prescribed twice", p.coordinate);
    colmap[k] = -1;
    p_index.push_back(k);
    p_motion.push_back(p.motion);
    p_labels.push_back(p.coordinate);
  }
  int nfree = 0;
  for (int& c : colmap) c = c < 0 ? -1 : nfree++;
  const int dof = m.dof, nu = m.n_inputs();
  q0 = m.q0;
  q1 = VectorXd::Zero(m.n1);
  a1 = VectorXd::Zero(m.n1);
  u = VectorXd::Zero(nu);
  lambda = VectorXd::Zero(m.m1);
  reactions = VectorXd::Zero(m.n_reactions());
  friction = friction_next = VectorXd::Zero(static_cast<int>(m.frictions.size()));
  local_base = VectorXd::Zero(m.frictions.empty() ? 0 : m.n_slots);
  s = s_dot = s_ddot = VectorXd::Zero(dof);
  psi = trial = VectorXd::Zero(m.m0);
  q0_trial = VectorXd::Zero(m.n0);
  b = c = VectorXd::Zero(m.m1);
  rhs = w = f = z = VectorXd::Zero(m.n1);
  local = local_a = VectorXd::Zero(m.n_slots);
  J = MatrixXd::Zero(m.m0, nfree);
  K = MatrixXd::Zero(m.n1, m.n1);
  B = input_matrix(m);
  S = MatrixXd::Zero(m.n1, dof);
  CtB = MatrixXd::Zero(dof, nu);
  Ctw = VectorXd::Zero(dof);
  row_residual = VectorXd::Zero(m.m1);
  // the fixed-pattern LUs factor densely (as before) within a factor 10 of the thresholds the
  // pivot ratio is compared with, so that singular configurations are told by the dense LU
  lu_pos = std::make_unique<detail::PatternLU>(nfree, 10 * o.singular_pivot_ratio);
  lu_K = std::make_unique<detail::PatternLU>(
      m.n1, 10 * std::max(o.singular_pivot_ratio, o.near_singular_pivot_ratio));
  lu_u = Eigen::PartialPivLU<MatrixXd>(dof);
  edge_force.assign(detail::merge_edge_layout(m, edge_offset), 0.0);
  // size the entry list with a dry run (the pattern is fixed)
  MatrixXd A(m.m1, m.n1);
  VectorXd bb(m.m1);
  A.setZero();
  detail::SlotRecordSink sink{A, m, entries};
  for (const auto& k : m.constraints) detail::velocity_rows(m, k, m.q0, o.t0, bb, sink);
  entries.reserve(entries.size() * 2 + 16);
  entries.clear();
  Ks = MatrixXd::Zero(m.n1, m.n1);
  col_scale = column_scaling(m);
  pos_scale = col_scale.head(m.n0);
  k_row = VectorXd::Ones(m.n1);
  q0_pred = VectorXd::Zero(m.n0);
  q0_prev = q1_prev = a1_prev = VectorXd::Zero(0);
  q0_prev = q0_good = VectorXd::Zero(m.n0);
  s_good = VectorXd::Zero(dof);
  q1_prev = VectorXd::Zero(m.n1);
  a1_prev = VectorXd::Zero(m.n1);
}

InverseData::~InverseData() = default;

}  // namespace mo2d
