// The contacts' forces at one evaluation (contact_forces.hpp).
#include "contact/contact_forces.hpp"

#include <Eigen/LU>

#include "contact/compliant.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

ContactForces::ContactForces(const Model& m, std::vector<CompiledContact> cs,
                             const ForwardOptions& o, double baumgarte_rate)
    : contacts(std::move(cs)), m_(m), w_(baumgarte_rate) {
  const size_t n = contacts.size();
  mode.assign(n, ContactMode::open);
  v0.assign(n, 0.0);
  lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  gaps_.resize(n);
  for (GapValue& g : gaps_) g.J = Eigen::VectorXd::Zero(m.n1);
  active_.reserve(n);
  probe_force_ = a0_ = Eigen::VectorXd::Zero(m.n1);
  bool rigid = false;
  for (const CompiledContact& c : contacts) rigid |= c.def.law.kind == ContactLaw::Kind::rigid;
  if (!rigid) return;
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

double ContactForces::add(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                          Eigen::VectorXd& f) {
  double dissipated = 0;
  active_.clear();
  for (int i = 0; i < size(); ++i) {
    const size_t k = static_cast<size_t>(i);
    lambda[i] = 0;
    if (mode[k] == ContactMode::open) continue;
    const GapValue& g = gap(i, q0, q1);
    if (!std::isfinite(g.g) || !std::isfinite(g.rate))
      throw Error("contact '" + contacts[k].def.name + "': its gap is not finite at t = " + fmt(t) +
                      " s (g = " + fmt(g.g) + " m, g' = " + fmt(g.rate) + " m/s)",
                  contacts[k].def.name, t);
    if (mode[k] == ContactMode::persistent) {
      active_.push_back(i);
      continue;
    }
    const CompliantForce F = lankarani_nikravesh(contacts[k].def.law, g.g, g.rate, v0[k]);
    f.noalias() += F.force * g.J;
    dissipated += F.dissipation;
  }
  if (!active_.empty()) persistent(t, q0, q1, f);
  return dissipated;
}

void ContactForces::persistent(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                               Eigen::VectorXd& f) {
  using Small =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPersistent, kMaxPersistent>;
  using SmallV = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxPersistent, 1>;
  const int k = static_cast<int>(active_.size());
  // the other forces: the probe computes the model's own again; the compliant contacts' are its
  // extra force
  probe_force_.setZero();
  for (int i = 0; i < size(); ++i)
    if (mode[static_cast<size_t>(i)] == ContactMode::compliant) {
      const GapValue& g = gaps_[static_cast<size_t>(i)];
      probe_force_.noalias() += lankarani_nikravesh(contacts[static_cast<size_t>(i)].def.law, g.g,
                                                    g.rate, v0[static_cast<size_t>(i)])
                                    .force *
                                g.J;
    }
  probe_->accelerations(t, q0, q1, false);
  a0_ = probe_->a;
  Small W(k, k);
  SmallV rhs(k);
  for (int r = 0; r < k; ++r) {
    const GapValue& g = gaps_[static_cast<size_t>(active_[static_cast<size_t>(r)])];
    rhs[r] = -(g.J.dot(a0_) + g.curvature) - 2 * w_ * g.rate - w_ * w_ * g.g;
  }
  for (int c = 0; c < k; ++c) {
    const GapValue& gc = gaps_[static_cast<size_t>(active_[static_cast<size_t>(c)])];
    probe_force_ += gc.J;
    probe_->accelerations(t, q0, q1, false);
    probe_force_ -= gc.J;
    for (int r = 0; r < k; ++r)
      W(r, c) = gaps_[static_cast<size_t>(active_[static_cast<size_t>(r)])].J.dot(probe_->a - a0_);
  }
  const SmallV x = Eigen::FullPivLU<Small>(W).solve(rhs);
  for (int r = 0; r < k; ++r) {
    const int i = active_[static_cast<size_t>(r)];
    lambda[i] = x[r];
    f.noalias() += x[r] * gaps_[static_cast<size_t>(i)].J;
  }
}

}  // namespace mo2d::detail
