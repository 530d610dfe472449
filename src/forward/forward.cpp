// Forward dynamics, public entry points: consistent initial state, the run (workspace and
// integrator chosen here; see forward_data.cpp, forward_rk.cpp, forward_cvode.cpp), replayed
// efforts.
#include "mo2d/forward.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "dynamics/chain.hpp"
#include "dynamics/slack.hpp"
#include "forward/forward_run.hpp"
#include "kinematics/sparse_kinematics.hpp"
#include "linalg/small_lu.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/quasi_steady.hpp"
#include "output/trajectory_labels.hpp"
#include "run/cpu_time.hpp"

namespace mo2d {

const char* to_string(Integrator i) {
  switch (i) {
    case Integrator::cvode_bdf:
      return "cvode_bdf";
    case Integrator::cvode_adams:
      return "cvode_adams";
    case Integrator::rk4:
      return "rk4";
    case Integrator::dopri5:
      return "dopri5";
    case Integrator::erk6:
      return "erk6";
    case Integrator::erk8:
      return "erk8";
    case Integrator::baumgarte:
      return "baumgarte";
  }
  return "?";
}
const char* to_string(Formulation f) {
  switch (f) {
    case Formulation::augmented_lagrangian:
      return "augmented_lagrangian";
    case Formulation::lagrange:
      return "lagrange";
    case Formulation::null_space:
      return "null_space";
  }
  return "?";
}

const char* to_string(ErrorEstimate e) {
  switch (e) {
    case ErrorEstimate::automatic:
      return "automatic";
    case ErrorEstimate::on:
      return "on";
    case ErrorEstimate::off:
      return "off";
  }
  return "?";
}

const char* to_string(LinearAlgebra a) {
  switch (a) {
    case LinearAlgebra::automatic:
      return "automatic";
    case LinearAlgebra::dense:
      return "dense";
    case LinearAlgebra::sparse:
      return "sparse";
  }
  return "?";
}

using detail::fmt;
using detail::Recorder;

void detail::check_finite_sample(const Model& m, const Trajectory& r, int k) {
  // (a row of a matrix with no columns, e.g. the efforts of a mechanism without inputs, would be
  // an offset from Eigen's null data pointer: such a row is finite)
  auto row_finite = [k](const MatrixXd& x) { return x.cols() == 0 || x.row(k).allFinite(); };
  if (row_finite(r.q0) && row_finite(r.q1) && row_finite(r.a1) && row_finite(r.efforts) &&
      row_finite(r.reactions) && row_finite(r.residuals) && std::isfinite(r.kinetic[k]) &&
      std::isfinite(r.potential[k]) && std::isfinite(r.input_work[k]) &&
      std::isfinite(r.load_work[k]) && std::isfinite(r.constraint_work[k]) &&
      std::isfinite(r.dissipated[k]))
    return;
  std::string names;
  int count = 0;
  auto add = [&](double v, const std::string& label) {
    if (!std::isfinite(v) && count++ < 3)
      names += (names.empty() ? "'" : ", '") + label + "' = " + fmt(v);
  };
  auto scan = [&](const MatrixXd& x, const std::vector<std::string>& labels, const char* suffix) {
    for (int j = 0; j < x.cols(); ++j) add(x(k, j), labels[j] + suffix);
  };
  scan(r.q0, r.coordinate_labels, "");
  scan(r.q1, r.rate_labels, "");
  scan(r.a1, r.rate_labels, ".dot");
  scan(r.efforts, r.input_labels, "");
  scan(r.reactions, r.reaction_labels, "");
  add(r.kinetic[k], "energy.kinetic");
  add(r.potential[k], "energy.potential");
  add(r.input_work[k], "work.inputs");
  add(r.load_work[k], "work.loads");
  add(r.constraint_work[k], "work.constraints");
  add(r.dissipated[k], "energy.dissipated");
  add(r.residuals(k, 0), "residual.position");
  add(r.residuals(k, 1), "residual.velocity");
  if (count == 0) return;
  throw Error("forward dynamics of '" + m.name + "': " + names + (count > 3 ? ", ..." : "") +
                  (count == 1 ? " is" : " are") + " not finite at t = " + fmt(r.time[k]) +
                  " s (first non-finite result: the integration diverged or a value overflowed)",
              names.substr(1, names.find('\'', 1) - 1), r.time[k]);
}

double kinetic_energy(const Model& m, const VectorXd& q1) {
  VectorXd local(m.n_slots), Mq(m.n1);
  body_inertia(m, q1, local);
  Mq.setZero();
  scatter_local(m, local, Mq);
  return 0.5 * q1.dot(Mq);
}

namespace {

// The given velocities cannot be imposed together at this configuration. Either the configuration
// is singular (A loses rank), or it is regular and the choice is: a given velocity is fixed by the
// constraints (its row of a null-space basis N of A vanishes: a pendulum lying horizontal cannot
// choose its bob's vx, which is 0), or the given ones are tied to each other. Names them, the
// value a fixed one must have, and a set of labels that can be given instead.
[[noreturn]] void throw_dependent_velocities(const Model& m, const InitialConditions& ic,
                                             const Eigen::Ref<const MatrixXd>& A, const VectorXd& b,
                                             double t0) {
  const std::string head = "initial state of '" + m.name + "': ";
  const std::string element = ic.velocities.empty() ? m.name : ic.velocities[0].first;
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(A);
  cod.setThreshold(1e-10);
  if (cod.rank() < m.m1)
    throw Error(head + "the configuration is singular (the velocity constraints lose rank)" +
                    " at t = " + fmt(t0) + " s: no choice of initial velocities is independent",
                element, t0);
  const MatrixXd At = A.transpose();
  Eigen::ColPivHouseholderQR<MatrixXd> qr(At);
  const MatrixXd Q = qr.householderQ();
  const MatrixXd N = Q.rightCols(m.n1 - m.m1);  // orthonormal basis of the admissible velocities
  const VectorXd particular = cod.solve(b);
  std::string fixed, given;
  for (const auto& [label, value] : ic.velocities) {
    given += (given.empty() ? "" : ", ") + label;
    const int k = m.rate(label);
    if (N.row(k).norm() < 1e-8)
      fixed += (fixed.empty() ? "" : ", ") + label + " (= " + fmt(particular[k]) + ")";
  }
  // a set of DOF labels that can be given: the pivots of a column-pivoted QR of N^T
  Eigen::ColPivHouseholderQR<MatrixXd> pick(N.transpose());
  std::string instead;
  for (int k = 0; k < m.dof; ++k)
    instead += (k ? ", " : "") + m.rate_labels[pick.colsPermutation().indices()[k]];
  if (!fixed.empty())
    throw Error(head + "the constraints fix " + fixed +
                    " at this configuration: not independent, it cannot be given as an initial "
                    "velocity (the configuration is regular); give instead e.g. " +
                    instead,
                element, t0);
  throw Error(head + "the velocities " + given +
                  " are tied to each other by the constraints at this configuration (not "
                  "independent; the configuration is regular); give instead e.g. " +
                  instead,
              element, t0);
}

// [A; E] q1 = [b; v]: the velocities given (E: their rows of the identity) and the constraints;
// LU with partial pivoting, its pivot ratio the singularity test.
VectorXd dense_velocities(const Model& m, const InitialConditions& ic, const VectorXd& q0,
                          double t0) {
  MatrixXd K = MatrixXd::Zero(m.n1, m.n1);
  VectorXd b(m.m1), rhs(m.n1);
  velocity_jacobian(m, q0, t0, K.topRows(m.m1), b);
  rhs.head(m.m1) = b;
  for (int k = 0; k < m.dof; ++k) {
    K(m.m1 + k, m.rate(ic.velocities[k].first)) = 1.0;
    rhs[m.m1 + k] = ic.velocities[k].second;
  }
  detail::SmallLU lu(m.n1);
  if (lu.compute(K) < 1e-10) throw_dependent_velocities(m, ic, K.topRows(m.m1), b, t0);
  lu.solve_in_place(rhs);
  return rhs;
}

// The same system sparse, by KLU (large models: kinematics/sparse_kinematics.hpp); the error
// path (dependent velocities) is the dense one.
VectorXd sparse_velocities(const Model& m, const InitialConditions& ic, const VectorXd& q0,
                           double t0) {
  detail::SparseRowsK A;
  VectorXd b(m.m1), rhs(m.n1), q1;
  detail::sparse_velocity_jacobian(m, q0, t0, A, b);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(A.nonZeros()) + m.dof);
  for (int i = 0; i < A.outerSize(); ++i)
    for (detail::SparseRowsK::InnerIterator it(A, i); it; ++it)
      t.emplace_back(i, static_cast<int>(it.col()), it.value());
  rhs.head(m.m1) = b;
  for (int k = 0; k < m.dof; ++k) {
    t.emplace_back(m.m1 + k, m.rate(ic.velocities[k].first), 1.0);
    rhs[m.m1 + k] = ic.velocities[k].second;
  }
  Eigen::SparseMatrix<double> K(m.n1, m.n1);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  if (detail::sparse_lu_solve(K, rhs, q1) < 1e-10) {
    MatrixXd Ad(m.m1, m.n1);
    velocity_jacobian(m, q0, t0, Ad, b);
    throw_dependent_velocities(m, ic, Ad, b, t0);
  }
  return q1;
}

}  // namespace

State consistent_state(const Model& m, const InitialConditions& ic, double t0) {
  VectorXd q0 = m.q0;
  std::vector<int> fixed;
  for (const auto& [label, value] : ic.positions) {
    const int k = m.coordinate(label);
    if (!std::isfinite(value)) throw Error("initial value of '" + label + "' is not finite", label);
    if (std::find(fixed.begin(), fixed.end(), k) != fixed.end())
      throw Error("initial position of '" + label + "' is given twice", label);
    q0[k] = value;
    fixed.push_back(k);
  }
  State s;
  s.t = t0;
  // switching chains: assembled in the modes of their spans' lengths (a slack chain stays slack);
  // the velocities with the taut spans' rows, a slack chain's upper span's (its rate 0: m.dof)
  std::optional<Model> modes;
  if (detail::switches_chains(m)) {
    detail::ChainStart c = detail::chain_start(m, q0, t0, fixed, 1e-13);
    s.q0 = std::move(c.q0);
    for (int& k : c.spans) k = std::max(k, 0);
    modes.emplace(detail::chain_mode_model(m, c.spans));
  } else {
    s.q0 = assemble(m, q0, t0, fixed, 1e-13);
  }
  const Model& vm = modes ? *modes : m;
  if (static_cast<int>(ic.velocities.size()) != m.dof) {
    std::string list;
    for (const auto& [l, v] : ic.velocities) list += (list.empty() ? "" : ", ") + l;
    throw Error("initial state of '" + m.name + "': " + std::to_string(m.dof) +
                    " independent velocities are needed, " + std::to_string(ic.velocities.size()) +
                    " given" + (list.empty() ? "" : " (" + list + ")"),
                m.name, t0);
  }
  for (const auto& [label, value] : ic.velocities) {
    if (!std::isfinite(value)) throw Error("initial velocity '" + label + "' is not finite", label);
    m.rate(label);  // an unknown label: its error, in the order given
  }
  s.q1 = detail::sparse_kinematics(vm) ? sparse_velocities(vm, ic, s.q0, t0)
                                       : dense_velocities(vm, ic, s.q0, t0);
  return s;
}

namespace {

bool fixed_step(Integrator i) {
  return i == Integrator::rk4 || i == Integrator::baumgarte;
}

// Dense matrices of the forward workspace (mo2d/forward_data.hpp) and of CVODE's BDF (Jacobian and
// its saved copy), and the recorded results: bytes, estimated from the sizes.
double forward_memory_bytes(const Model& m, const ForwardOptions& o) {
  const double n0 = m.n0, n1 = m.n1, m0 = m.m0, m1 = m.m1;
  // the sparse path: the mass matrix is built column by column (n1 values at a time) and the
  // factors of a chain are O(n); 64 entries per variable and row is a generous bound
  double dense = uses_sparse(m, o) ? 64 * (n0 + n1 + m0 + m1)
                                   : 8 * n1 * n1 + 2 * (n1 + m1) * (n1 + m1) + 4 * m1 * n1 +
                                         3 * m1 * m1 + 3 * n0 * n0 + m0 * n0;
  if (o.integrator == Integrator::cvode_bdf) dense += 2 * (n0 + n1 + 2) * (n0 + n1 + 2);
  const double columns = n0 + 3 * n1 + m.n_inputs() + m.n_reactions() + 7;
  return 8 * (dense + static_cast<double>(o.samples) * columns);
}

}  // namespace

void check_forward_options(const Model& m, const ForwardOptions& o) {
  const char* run = "forward dynamics";
  if (!(o.samples >= 2))
    throw Error("forward dynamics: samples must be >= 2 (got " + std::to_string(o.samples) + ")",
                "samples");
  auto order = [&] {
    return Error("forward dynamics: need t0 < t1 (t0 = " + fmt(o.t0) + ", t1 = " + fmt(o.t1) + ")",
                 "t1");
  };
  if (o.t1 < o.t0) throw order();
  check_time_grid(run, o.t0, o.t1, o.samples);  // t1 == t0 by rounding: unresolved samples
  if (!(o.t1 > o.t0)) throw order();
  (void)options_for_accuracy(m, o);  // refuses an accuracy out of its bounds
  if (!(o.max_steps > 0))
    throw Error("forward dynamics: max_steps must be > 0 (got " + std::to_string(o.max_steps) + ")",
                "max_steps");
  if (std::isnan(o.max_seconds))
    throw Error("forward dynamics: max_seconds is not a number", "max_seconds");
  if (fixed_step(o.integrator)) {
    if (!(o.step > 0 && std::isfinite(o.step)))
      throw Error("forward dynamics: the fixed step must be positive (got " + fmt(o.step) + ")",
                  "step");
    // the steps end on the output times: at least one per output interval
    const double needed = std::max((o.t1 - o.t0) / o.step, static_cast<double>(o.samples - 1));
    if (!(needed <= o.max_steps))
      throw Error("forward dynamics: step " + fmt(o.step) + " s over [" + fmt(o.t0) + ", " +
                      fmt(o.t1) + "] s needs " + fmt(needed) +
                      " steps, more than max_steps = " + std::to_string(o.max_steps) +
                      ": use a longer step (or raise max_steps, or use dopri5 or cvode_bdf)",
                  "step");
    const double tmax = std::max(std::abs(o.t0), std::abs(o.t1));
    if (!(o.step >= kTimeResolution * tmax))
      throw Error("forward dynamics: step " + fmt(o.step) +
                      " s is below the time resolution near t = " + fmt(tmax) + " s (at least " +
                      fmt(kTimeResolution * tmax) + " s): use a t0 closer to 0",
                  "t0");
  }
  if ((o.integrator == Integrator::cvode_bdf || o.integrator == Integrator::cvode_adams ||
       o.integrator == Integrator::dopri5 || o.integrator == Integrator::erk6 ||
       o.integrator == Integrator::erk8) &&
      !(o.rtol > 0 && o.atol > 0 && std::isfinite(o.rtol) && std::isfinite(o.atol)))
    throw Error("forward dynamics: tolerances must be positive (rtol " + fmt(o.rtol) + ", atol " +
                    fmt(o.atol) + ")",
                "rtol");
  if (static_cast<int>(o.efforts.size()) > m.n_inputs())
    throw Error("forward dynamics: more efforts (" + std::to_string(o.efforts.size()) +
                    ") than inputs (" + std::to_string(m.n_inputs()) + ")",
                m.name);
  check_magnitudes(m);
  check_memory("forward dynamics of '" + m.name + "' (" + to_string(o.integrator) + ", " +
                   std::to_string(o.samples) + " samples)",
               forward_memory_bytes(m, o), o.max_memory, model_sizes(m), "max_memory");
}

Trajectory detail::forward_run(const Model& m, const State& initial, const ForwardOptions& options,
                               ForwardOptions* chosen) {
  check_forward_options(m, options_for_accuracy(m, options));
  if (m.n1 == 0)  // nothing to integrate (a scene without bodies, or every body fixed)
    throw Error("forward dynamics of '" + m.name +
                    "': the mechanism has no moving parts (no quasi-velocities)",
                m.name);
  if (initial.q0.size() != m.n0 || initial.q1.size() != m.n1)
    throw Error("forward dynamics: the initial state does not match the model's variables", m.name);
  State at_t0 = initial;
  at_t0.t = options.t0;
  const double start = detail::cpu_seconds();  // the run's CPU time includes the choice
  // the integrator for an accuracy asked for: explicit unless stiff at the initial state
  const MethodChoice choice = choose_method(m, at_t0, options);
  const ForwardOptions& o = choice.options;
  if (options.accuracy > 0) check_forward_options(m, o);  // the method chosen
  if (chosen != nullptr) *chosen = o;
  if (detail::switches_chains(m)) {  // legs between span switches, each with the chosen method
    Trajectory r = detail::forward_chain_switching(m, initial, o);
    r.stats.integrator = to_string(o.integrator);
    r.stats.method = choice.reason;
    return r;
  }
  ForwardData d(m, o);
  d.stats.sparse = d.sparse_engine() != nullptr;
  d.stats.integrator = to_string(o.integrator);
  d.stats.method = choice.reason;
  Trajectory r = detail::labelled_trajectory(m, RunKind::forward);
  const int N = o.samples;
  r.efforts = MatrixXd::Zero(N, m.n_inputs());
  r.reactions = MatrixXd::Zero(N, m.n_reactions());
  r.time = VectorXd::Zero(N);
  r.q0 = MatrixXd::Zero(N, m.n0);
  r.q1 = MatrixXd::Zero(N, m.n1);
  r.a1 = MatrixXd::Zero(N, m.n1);
  r.kinetic = r.potential = r.input_work = r.load_work = r.constraint_work = r.dissipated =
      VectorXd::Zero(N);
  r.residuals = MatrixXd::Zero(N, 2);
  Recorder rec{m, r, d};
  State s0 = initial;
  s0.t = o.t0;
  const detail::QuasiSteadyRun held(m);  // resets the held lengths however the run ends
  if (has_quasi_steady(m)) detail::start_quasi_steady(d, s0.t, s0.q0, s0.q1);
  switch (o.integrator) {
    case Integrator::rk4:
    case Integrator::dopri5:
    case Integrator::erk6:
    case Integrator::erk8:
    case Integrator::baumgarte:
      detail::run_explicit_rk(m, d, s0, o, rec);
      break;
    case Integrator::cvode_bdf:
    case Integrator::cvode_adams:
      detail::run_cvode(m, d, s0, o, rec);
      break;
  }
  rec.finish();
  d.stats.cpu_seconds = detail::cpu_seconds() - start;
  // trim to the recorded samples (an event may stop early)
  const int used = rec.k;
  r.time.conservativeResize(used);
  r.q0.conservativeResize(used, Eigen::NoChange);
  r.q1.conservativeResize(used, Eigen::NoChange);
  r.a1.conservativeResize(used, Eigen::NoChange);
  r.kinetic.conservativeResize(used);
  r.potential.conservativeResize(used);
  r.input_work.conservativeResize(used);
  r.load_work.conservativeResize(used);
  r.constraint_work.conservativeResize(used);
  r.dissipated.conservativeResize(used);
  r.residuals.conservativeResize(used, Eigen::NoChange);
  r.efforts.conservativeResize(used, Eigen::NoChange);
  r.reactions.conservativeResize(used, Eigen::NoChange);
  r.stats = d.stats;
  detail::reduced_spring_slack(m, r, r.stats.warnings);
  return r;
}

Trajectory forward_dynamics(const Model& m, const State& initial, const ForwardOptions& options) {
  return detail::meet_accuracy(m, initial, options,
                               detail::checked_run(m, initial, options, options));
}

std::vector<std::function<double(double)>> efforts_from_inverse(const Model& m,
                                                                std::vector<Prescribed> prescribed,
                                                                const InverseOptions& options) {
  // Each instant is solved from the last one (inverse_dynamics_sample: Newton from the prediction
  // of the last sample's velocities and accelerations). Asked at a time far from the last (a run
  // started again from an earlier state, as locate_extremes does), that prediction is far off and
  // Newton can land on another assembly mode: the crank-rocker's torque at 0.2 s asked after
  // 1.0 s came out -0.401 N m instead of -0.635. So a jump longer than the options' sample spacing
  // walks there in steps of that spacing.
  struct Shared {
    Model model;
    std::vector<Prescribed> prescribed;
    InverseData data;
    double t = NAN, spacing = INFINITY;
    Shared(const Model& mm, std::vector<Prescribed> p, const InverseOptions& o)
        : model(mm), prescribed(std::move(p)), data(model, prescribed, o) {
      if (o.samples >= 2 && o.t1 > o.t0) spacing = (o.t1 - o.t0) / (o.samples - 1);
    }
    double effort(int k, double t_) {
      if (!(t_ == t)) {
        if (std::isfinite(t) && std::abs(t_ - t) > spacing && std::abs(t_ - t) < 1e6 * spacing)
          for (double s = t; std::abs(t_ - s) > spacing;) {
            s += std::copysign(spacing, t_ - s);
            inverse_dynamics_sample(model, data, s);
          }
        inverse_dynamics_sample(model, data, t_);
        t = t_;
      }
      return data.u[k];
    }
  };
  auto shared = std::make_shared<Shared>(m, std::move(prescribed), options);
  std::vector<std::function<double(double)>> out;
  out.reserve(m.n_inputs());
  for (int k = 0; k < m.n_inputs(); ++k)
    out.push_back([shared, k](double t) { return shared->effort(k, t); });
  return out;
}

std::vector<std::function<double(double)>> efforts_from_samples(const Trajectory& r) {
  std::vector<std::function<double(double)>> out;
  const int n = static_cast<int>(r.time.size());
  if (n < 2) throw Error("efforts_from_samples: need at least two samples", "samples");
  for (int k = 0; k < r.efforts.cols(); ++k) {
    auto t = std::make_shared<VectorXd>(r.time);
    auto u = std::make_shared<VectorXd>(r.efforts.col(k));
    auto du = std::make_shared<VectorXd>(n);
    for (int i = 0; i < n; ++i) {
      const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
      (*du)[i] = ((*u)[b] - (*u)[a]) / ((*t)[b] - (*t)[a]);
    }
    out.push_back([t, u, du, n](double x) {
      if (x <= (*t)[0]) return (*u)[0];
      if (x >= (*t)[n - 1]) return (*u)[n - 1];
      const int i = static_cast<int>(std::upper_bound(t->data(), t->data() + n, x) - t->data()) - 1;
      const double h = (*t)[i + 1] - (*t)[i], s = (x - (*t)[i]) / h;
      const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
      const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
      return h00 * (*u)[i] + h10 * h * (*du)[i] + h01 * (*u)[i + 1] + h11 * h * (*du)[i + 1];
    });
  }
  return out;
}

}  // namespace mo2d
