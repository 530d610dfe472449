#pragma once
// The forces of the contacts at one evaluation (internal to src/contact/), the function the
// forward run calls as ForwardOptions::extra_forces: the compliant contacts' laws (compliant.hpp)
// while they are closed, and the multipliers of the persistent rigid contacts.
//
// A persistent contact i is an active constraint at the acceleration level,
//   g_i'' = J_i a + J_i' q1 = -2 w g_i' - w^2 g_i     (w the Baumgarte rate, 0 by default),
// with its multiplier lambda_i >= 0 along J_i^T. The accelerations are linear in the forces, so
// with a0 the accelerations under the other forces (the model's formulation: a probe workspace
// whose extra force is set here) and a_j those under J_j^T added,
//   W lambda = rhs,  W_ij = J_i (a_j - a0),  rhs_i = -(J_i a0 + J_i' q1) - 2 w g_i' - w^2 g_i,
// k + 1 evaluations of the probe for k persistent contacts (at most kMaxPersistent).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "contact/contact_set.hpp"
#include "mo2d/forward_data.hpp"

namespace mo2d::detail {

inline constexpr int kMaxPersistent = 8;

enum class ContactMode { open, compliant, persistent };

class ContactForces {
 public:
  ContactForces(const Model& m, std::vector<CompiledContact> contacts, const ForwardOptions& o,
                double baumgarte_rate);
  ContactForces(const ContactForces&) = delete;
  ContactForces& operator=(const ContactForces&) = delete;
  ~ContactForces();

  std::vector<CompiledContact> contacts;
  std::vector<ContactMode> mode;  // per contact
  std::vector<double> v0;         // per compliant contact: its approach speed at the onset (m/s)
  Eigen::VectorXd lambda;         // per contact: the persistent multiplier (N), else 0

  // Adds the contacts' generalized forces at (t, q0, q1) to f; returns their dissipated power.
  double add(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, Eigen::VectorXd& f);
  // The gap of contact i at the last add (or gap()).
  const GapValue& last_gap(int i) const { return gaps_[static_cast<size_t>(i)]; }
  const GapValue& gap(int i, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  int size() const { return static_cast<int>(contacts.size()); }

 private:
  const Model& m_;
  double w_ = 0;
  std::vector<GapValue> gaps_;
  std::vector<int> active_;  // the persistent contacts of an evaluation
  std::unique_ptr<ForwardData> probe_;
  Eigen::VectorXd probe_force_, a0_;
  void persistent(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                  Eigen::VectorXd& f);
};

}  // namespace mo2d::detail
