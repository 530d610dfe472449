// The contacts' forces at one evaluation (contact_forces.hpp).
#include "contact/contact_forces.hpp"

#include <Eigen/LU>
#include <cmath>

#include "contact/compliant.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {
namespace {

constexpr int kMaxContactRows = 2 * kMaxPersistent;  // a normal and a tangent row per contact
using RowMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxContactRows, kMaxContactRows>;
using RowVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxContactRows, 1>;

// x += N s with s minimizing sum_r D_r x_r^2 over the solutions x + N s of W x = rhs (N the null
// space of W): the weighted least-norm solution (contact_forces.hpp).
void least_weighted_rows(const RowMatrix& N, const RowVector& D, RowVector& x) {
  const RowMatrix ND = N.transpose() * D.asDiagonal();
  const RowVector s = Eigen::FullPivLU<RowMatrix>(ND * N).solve(-(ND * x));
  x += N * s;
}

}  // namespace

ContactForces::ContactForces(const Model& m, std::vector<CompiledContact> cs,
                             const ForwardOptions& o, double baumgarte_rate)
    : contacts(std::move(cs)), m_(m), w_(baumgarte_rate) {
  const size_t n = contacts.size();
  mode.assign(n, ContactMode::open);
  slide.assign(n, SlideMode::none);
  slip_sign.assign(n, 1.0);
  v0.assign(n, 0.0);
  lambda = normal = tangential = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  gaps_.resize(n);
  for (GapValue& g : gaps_) g.J = Eigen::VectorXd::Zero(m.n1);
  tangents_.resize(n);
  for (TangentValue& g : tangents_) g.J = Eigen::VectorXd::Zero(m.n1);
  active_.reserve(2 * n);
  probe_force_ = a0_ = Eigen::VectorXd::Zero(m.n1);
  bool rows = false;  // rigid contacts, or friction (a sticking compliant contact)
  for (const CompiledContact& c : contacts)
    rows |= c.def.law.kind == ContactLaw::Kind::rigid || c.def.law.friction > 0;
  if (!rows) return;
  ForwardOptions po = o;
  po.stop_when = nullptr;
  po.accuracy = 0;
  po.extra_forces = [this](double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                           Eigen::VectorXd& f) {
    f += probe_force_;
    return 0.0;
  };
  probe_ = std::make_unique<ForwardData>(m, po);
}

ContactForces::~ContactForces() = default;

const GapValue& ContactForces::gap(int i, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  gap_into(m_, contacts[static_cast<size_t>(i)], q0, q1, gaps_[static_cast<size_t>(i)]);
  return gaps_[static_cast<size_t>(i)];
}

const TangentValue& ContactForces::tangent(int i, const Eigen::VectorXd& q0,
                                           const Eigen::VectorXd& q1) {
  tangent_into(m_, contacts[static_cast<size_t>(i)], q0, q1, tangents_[static_cast<size_t>(i)]);
  return tangents_[static_cast<size_t>(i)];
}

// A compliant contact's law and, sliding, its friction -mu F s (at the last gap and tangent):
// adds them to f, returns their dissipated power.
double ContactForces::compliant_force(int i, Eigen::VectorXd& f) {
  const size_t k = static_cast<size_t>(i);
  const GapValue& g = gaps_[k];
  const CompliantForce F = lankarani_nikravesh(contacts[k].def.law, g.g, g.rate, v0[k]);
  f.noalias() += F.force * g.J;
  normal[i] = F.force;
  if (slide[k] != SlideMode::slip) return F.dissipation;
  const TangentValue& t = tangents_[k];
  const double Ft = -contacts[k].def.law.friction * F.force * slip_sign[k];
  f.noalias() += Ft * t.J;
  tangential[i] = Ft;
  return F.dissipation - Ft * t.rate;
}

double ContactForces::add(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                          Eigen::VectorXd& f) {
  double dissipated = 0;
  active_.clear();
  for (int i = 0; i < size(); ++i) {
    const size_t k = static_cast<size_t>(i);
    lambda[i] = normal[i] = tangential[i] = 0;
    if (mode[k] == ContactMode::open) continue;
    const GapValue& g = gap(i, q0, q1);
    if (!std::isfinite(g.g) || !std::isfinite(g.rate))
      throw Error("contact '" + contacts[k].def.name + "': its gap is not finite at t = " + fmt(t) +
                      " s (g = " + fmt(g.g) + " m, g' = " + fmt(g.rate) + " m/s)",
                  contacts[k].def.name, t);
    if (slide[k] != SlideMode::none) {
      const TangentValue& v = tangent(i, q0, q1);
      if (!std::isfinite(v.rate) || !std::isfinite(v.curvature))
        throw Error("contact '" + contacts[k].def.name +
                        "': its sliding rate is not finite at t = " + fmt(t) +
                        " s (v_t = " + fmt(v.rate) + " m/s)",
                    contacts[k].def.name, t);
    }
    if (mode[k] == ContactMode::persistent) active_.emplace_back(i, false);
    if (slide[k] == SlideMode::stick) active_.emplace_back(i, true);
  }
  if (!active_.empty()) return persistent(t, q0, q1, f);  // the compliant forces too
  for (int i = 0; i < size(); ++i)
    if (mode[static_cast<size_t>(i)] == ContactMode::compliant) dissipated += compliant_force(i, f);
  return dissipated;
}

// The active rows' multipliers (contact_forces.hpp); adds their forces and the compliant contacts'
// to f, returns the dissipated power of the compliant laws and of friction.
double ContactForces::persistent(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                                 Eigen::VectorXd& f) {
  const int k = static_cast<int>(active_.size());
  if (k > kMaxContactRows)
    throw Error("contact '" + contacts[static_cast<size_t>(active_[0].first)].def.name +
                    "': " + std::to_string(k) + " active contact rows at t = " + fmt(t) +
                    " s (at most " + std::to_string(kMaxContactRows) + ")",
                contacts[static_cast<size_t>(active_[0].first)].def.name, t);
  // the other forces: the probe computes the model's own again; the compliant contacts' are its
  // extra force
  double dissipated = 0;
  probe_force_.setZero();
  for (int i = 0; i < size(); ++i)
    if (mode[static_cast<size_t>(i)] == ContactMode::compliant)
      dissipated += compliant_force(i, probe_force_);
  f += probe_force_;
  probe_->accelerations(t, q0, q1, false);
  a0_ = probe_->a;
  // row r's Jacobian and bias, and the force of a unit multiplier of column c
  auto row_J = [&](int r) -> const Eigen::VectorXd& {
    const auto [i, tangent] = active_[static_cast<size_t>(r)];
    return tangent ? tangents_[static_cast<size_t>(i)].J : gaps_[static_cast<size_t>(i)].J;
  };
  auto add_column = [&](int c, double x, Eigen::VectorXd& out) {
    const auto [i, tangent] = active_[static_cast<size_t>(c)];
    const size_t ii = static_cast<size_t>(i);
    if (tangent) {
      out.noalias() += x * tangents_[ii].J;
      return;
    }
    out.noalias() += x * gaps_[ii].J;
    if (slide[ii] == SlideMode::slip)
      out.noalias() -= contacts[ii].def.law.friction * slip_sign[ii] * x * tangents_[ii].J;
  };
  RowMatrix W(k, k);
  RowVector rhs(k);
  for (int r = 0; r < k; ++r) {
    const auto [i, tangent] = active_[static_cast<size_t>(r)];
    if (tangent) {
      const TangentValue& v = tangents_[static_cast<size_t>(i)];
      rhs[r] = -(v.J.dot(a0_) + v.curvature) - w_ * v.rate;
    } else {
      const GapValue& g = gaps_[static_cast<size_t>(i)];
      rhs[r] = -(g.J.dot(a0_) + g.curvature) - 2 * w_ * g.rate - w_ * w_ * g.g;
    }
  }
  for (int c = 0; c < k; ++c) {
    add_column(c, 1.0, probe_force_);
    probe_->accelerations(t, q0, q1, false);
    add_column(c, -1.0, probe_force_);
    for (int r = 0; r < k; ++r) W(r, c) = row_J(r).dot(probe_->a - a0_);
  }
  Eigen::FullPivLU<RowMatrix> lu(W);
  lu.setThreshold(1e-10);
  RowVector x = lu.solve(rhs);
  if (lu.rank() < k) {  // equal rows (contact_forces.hpp): the least weighted solution
    const RowMatrix N = lu.kernel();
    const double ref = std::max(x.cwiseAbs().maxCoeff(), 1e-300);
    RowVector D = RowVector::Constant(k, 1.0 / ref);
    least_weighted_rows(N, D, x);
    for (int r = 0; r < k; ++r) {
      const auto [i, tangent] = active_[static_cast<size_t>(r)];
      if (!tangent) continue;
      double N_i = normal[i];  // compliant: its law's force; persistent: its multiplier
      for (int c = 0; c < k; ++c)
        if (active_[static_cast<size_t>(c)] == std::make_pair(i, false)) N_i = x[c];
      D[r] = 1.0 / std::max(contacts[static_cast<size_t>(i)].def.law.friction * N_i, 1e-9 * ref);
    }
    least_weighted_rows(N, D, x);
  }
  for (int c = 0; c < k; ++c) {
    const auto [i, tangent] = active_[static_cast<size_t>(c)];
    const size_t ii = static_cast<size_t>(i);
    add_column(c, x[c], f);
    if (tangent) {
      tangential[i] = x[c];
      dissipated -= x[c] * tangents_[ii].rate;
      continue;
    }
    lambda[i] = normal[i] = x[c];
    if (slide[ii] == SlideMode::slip) {
      tangential[i] = -contacts[ii].def.law.friction * slip_sign[ii] * x[c];
      dissipated -= tangential[i] * tangents_[ii].rate;
    }
  }
  return dissipated;
}

}  // namespace mo2d::detail
