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
//
// Coulomb friction (mu > 0, docs/contact.md "Friction"; the tangent: tangent.hpp) adds to a closed
// contact (persistent or compliant) a sliding mode:
//   slip (sign s, v_t s > 0): the force -mu N s along J_t^T, N the normal force: for a compliant
//     contact its law's F, a known force; for a persistent one the multiplier lambda_n, so its
//     column is J_n - mu s J_t (the friction a load on the normal multiplier);
//   stick (v_t = 0 held): one more active row, dv_t/dt = J_t a + bias = 0, with the multiplier
//     lambda_t along J_t^T, watched against the cone |lambda_t| <= mu N.
// Two contacts of one body sticking on one line (a block's corners) give equal tangent rows: W is
// singular and the split of the tangential force between them is statically indeterminate; the
// solution taken is the one of least sum lambda_t^2 / (mu N) (each contact's share proportional
// to its normal force when the rows are equal), whose cone test is the whole body's.
// Friction's power, F_t v_t <= 0, is dissipated (returned by add).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "contact/contact_set.hpp"
#include "mo2d/forward_data.hpp"

namespace mo2d::detail {

inline constexpr int kMaxPersistent = 8;

enum class ContactMode { open, compliant, persistent };
// The sliding mode of a closed contact with friction (none: frictionless or open).
enum class SlideMode { none, stick, slip };

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
  std::vector<SlideMode> slide;   // per contact
  std::vector<double> slip_sign;  // per sliding contact: s = +1 or -1
  Eigen::VectorXd normal;         // per contact: its normal force N (compliant or persistent)
  Eigen::VectorXd tangential;     // per contact: its tangential force (stick: lambda_t) (N)

  // Adds the contacts' generalized forces at (t, q0, q1) to f; returns their dissipated power.
  double add(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, Eigen::VectorXd& f);
  // The gap of contact i at the last add (or gap()).
  const GapValue& last_gap(int i) const { return gaps_[static_cast<size_t>(i)]; }
  const GapValue& gap(int i, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  const TangentValue& last_tangent(int i) const { return tangents_[static_cast<size_t>(i)]; }
  const TangentValue& tangent(int i, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  bool rough(int i) const { return contacts[static_cast<size_t>(i)].def.law.friction > 0; }
  int size() const { return static_cast<int>(contacts.size()); }

 private:
  const Model& m_;
  double w_ = 0;
  std::vector<GapValue> gaps_;
  std::vector<TangentValue> tangents_;
  // the active rows of an evaluation: contact, and normal (false) or tangent (true)
  std::vector<std::pair<int, bool>> active_;
  std::unique_ptr<ForwardData> probe_;
  Eigen::VectorXd probe_force_, a0_;
  double persistent(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                    Eigen::VectorXd& f);
  double compliant_force(int i, Eigen::VectorXd& f);
};

}  // namespace mo2d::detail
