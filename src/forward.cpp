// Forward dynamics, public entry points: consistent initial state, the run (workspace and
// integrator chosen here; see forward_data.cpp, forward_rk.cpp, forward_cvode.cpp), replayed
// efforts.
#include "mo2d/forward.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "cpu_time.hpp"
#include "forward_data.hpp"
#include "mo2d/detail/small_lu.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/suggest.hpp"

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

using detail::fmt;
using detail::ForwardData;
using detail::Recorder;

double kinetic_energy(const Model& m, const VectorXd& q1) {
  VectorXd local(m.n_slots), Mq(m.n1);
  body_inertia(m, q1, local);
  Mq.setZero();
  scatter_local(m, local, Mq);
  return 0.5 * q1.dot(Mq);
}

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
  s.q0 = assemble(m, q0, t0, fixed, 1e-13);
  if (static_cast<int>(ic.velocities.size()) != m.dof) {
    std::string list;
    for (const auto& [l, v] : ic.velocities) list += (list.empty() ? "" : ", ") + l;
    throw Error("initial state of '" + m.name + "': " + std::to_string(m.dof) +
                    " independent velocities are needed, " + std::to_string(ic.velocities.size()) +
                    " given" + (list.empty() ? "" : " (" + list + ")"),
                m.name, t0);
  }
  MatrixXd K = MatrixXd::Zero(m.n1, m.n1);
  VectorXd b(m.m1), rhs(m.n1);
  velocity_jacobian(m, s.q0, t0, K.topRows(m.m1), b);
  rhs.head(m.m1) = b;
  for (int k = 0; k < m.dof; ++k) {
    const auto& [label, value] = ic.velocities[k];
    if (!std::isfinite(value)) throw Error("initial velocity '" + label + "' is not finite", label);
    K(m.m1 + k, m.rate(label)) = 1.0;
    rhs[m.m1 + k] = value;
  }
  detail::SmallLU lu(m.n1);
  if (lu.compute(K) < 1e-10) {
    std::string list;
    for (const auto& [l, v] : ic.velocities) list += (list.empty() ? "" : ", ") + l;
    throw Error("initial state of '" + m.name + "': the velocities " + list +
                    " are not independent at this configuration (singular start)",
                ic.velocities.empty() ? m.name : ic.velocities[0].first, t0);
  }
  s.q1 = rhs;
  lu.solve_in_place(s.q1);
  return s;
}

ForwardResult forward_dynamics(const Model& m, const State& initial, const ForwardOptions& o) {
  if (!(o.samples >= 2) || !std::isfinite(o.t0) || !std::isfinite(o.t1) || !(o.t1 > o.t0))
    throw Error("forward dynamics: need samples >= 2 and finite t0 < t1", "options");
  if ((o.integrator == Integrator::rk4 || o.integrator == Integrator::baumgarte) &&
      !(o.step > 0 && std::isfinite(o.step)))
    throw Error("forward dynamics: the fixed step must be positive (got " + fmt(o.step) + ")",
                "step");
  if ((o.integrator == Integrator::cvode_bdf || o.integrator == Integrator::cvode_adams ||
       o.integrator == Integrator::dopri5) &&
      !(o.rtol > 0 && o.atol > 0))
    throw Error("forward dynamics: tolerances must be positive", "rtol");
  if (initial.q0.size() != m.n0 || initial.q1.size() != m.n1)
    throw Error("forward dynamics: the initial state does not match the model's variables", m.name);
  if (static_cast<int>(o.efforts.size()) > m.n_inputs())
    throw Error("forward dynamics: more efforts (" + std::to_string(o.efforts.size()) +
                    ") than inputs (" + std::to_string(m.n_inputs()) + ")",
                m.name);
  ForwardData d(m, o);
  ForwardResult r;
  r.coordinate_labels = m.coordinate_labels;
  r.rate_labels = m.rate_labels;
  r.input_labels = m.input_labels();
  r.reaction_labels = m.reaction_labels();
  const int N = o.samples;
  r.efforts = MatrixXd::Zero(N, m.n_inputs());
  r.reactions = MatrixXd::Zero(N, m.n_reactions());
  r.time = VectorXd::Zero(N);
  r.q0 = MatrixXd::Zero(N, m.n0);
  r.q1 = MatrixXd::Zero(N, m.n1);
  r.a1 = MatrixXd::Zero(N, m.n1);
  r.kinetic = r.potential = r.input_work = r.dissipated = VectorXd::Zero(N);
  r.residuals = MatrixXd::Zero(N, 2);
  Recorder rec{m, r, d};
  const double start = detail::cpu_seconds();
  State s0 = initial;
  s0.t = o.t0;
  switch (o.integrator) {
    case Integrator::rk4:
    case Integrator::dopri5:
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
  r.dissipated.conservativeResize(used);
  r.residuals.conservativeResize(used, Eigen::NoChange);
  r.efforts.conservativeResize(used, Eigen::NoChange);
  r.reactions.conservativeResize(used, Eigen::NoChange);
  r.stats = d.stats;
  return r;
}

std::vector<std::function<double(double)>> efforts_from_inverse(const Model& m,
                                                                std::vector<Prescribed> prescribed,
                                                                const InverseOptions& options) {
  struct Shared {
    Model model;
    std::vector<Prescribed> prescribed;
    InverseData data;
    double t = NAN;
    Shared(const Model& mm, std::vector<Prescribed> p, const InverseOptions& o)
        : model(mm), prescribed(std::move(p)), data(model, prescribed, o) {}
    double effort(int k, double t_) {
      if (!(t_ == t)) {
        inverse_dynamics_sample(model, data, t_);
        t = t_;
      }
      return data.u[k];
    }
  };
  auto shared = std::make_shared<Shared>(m, std::move(prescribed), options);
  std::vector<std::function<double(double)>> out;
  for (int k = 0; k < m.n_inputs(); ++k)
    out.push_back([shared, k](double t) { return shared->effort(k, t); });
  return out;
}

std::vector<std::function<double(double)>> efforts_from_samples(const InverseResult& r) {
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

int ForwardResult::column(const std::string& l) const {
  return label_index(coordinate_labels, l, "coordinate");
}
int ForwardResult::reaction(const std::string& l) const {
  return label_index(reaction_labels, l, "reaction");
}
int ForwardResult::rate_column(const std::string& l) const {
  return label_index(rate_labels, l, "quasi-velocity");
}

}  // namespace mo2d
