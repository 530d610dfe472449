#pragma once
// The event-driven contact run (internal to src/contact/): legs of forward dynamics between
// events (contact_run.cpp), each with the contacts' forces as ForwardOptions::extra_forces and
// their mode conditions as ForwardOptions::stop_when; the events themselves (contact_events.cpp).
//
// Each contact has a condition, positive inside its mode and located by the root finding:
//   open:        g + tol_g           (closing: a compliant onset or a rigid impact; right after an
//                                    impact or a lift-off, g + slack until g > 0 again)
//   compliant:   tol_g - g           (the exit)
//   persistent:  lambda / lambda_ref (the lift-off: the multiplier reaches 0)
// with tol_g = kGapTolerance * Model::scale: a rigid contact penetrates by at most tol_g at an
// impact (then the velocities jump), a compliant one opens and closes tol_g past g = 0.
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_forces.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/contact.hpp"

namespace mo2d::detail {

inline constexpr double kGapTolerance = 1e-10;  // relative to Model::scale
inline constexpr int kChatter = 8;              // events at one instant before the run is refused

class ContactRunner {
 public:
  ContactRunner(const Model& m, const std::vector<ContactDef>& defs, const ContactOptions& o);
  ContactRun run(const State& initial);

 private:
  const Model& m_;
  const ContactOptions& co_;
  ForwardOptions inner_;
  std::unique_ptr<ContactForces> forces_;
  double scale_ = 1, tol_g_ = 0, lambda_ref_ = 0;
  Trajectory out_;
  std::vector<ContactEvent> events_;
  int filled_ = 0, same_instant_ = 0;
  double off_[kEnergyTerms] = {0, 0, 0, 0};
  double last_event_ = -1e300;
  bool switched_ = false;
  // per contact: its last four impact times, and the last step end's (t, g, g') for the check of
  // an excursion between step ends (open contacts)
  std::vector<std::vector<double>> impacts_;
  std::vector<std::array<double, 3>> step_end_;
  double last_step_t_ = -1e300;
  std::vector<bool> excursion_warned_;
  // per contact: the open condition's offset, tol_g, or after an impact or a lift-off located a
  // hair past -tol_g (the root finding's far end) a little more, until the gap is positive again
  std::vector<double> slack_;
  void loosen(int i, double g) { slack_[static_cast<size_t>(i)] = tol_g_ + 2 * std::max(0.0, -g); }
  Eigen::VectorXd scratch_f_;

  const std::string& name(int i) const { return forces_->contacts[static_cast<size_t>(i)].def.name; }
  const ContactLaw& law(int i) const { return forces_->contacts[static_cast<size_t>(i)].def.law; }
  ContactMode mode(int i) const { return forces_->mode[static_cast<size_t>(i)]; }
  double condition(int i, double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  double event(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  void check_excursion(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  Trajectory leg(const State& s, double t1, int samples);
  // contact_events.cpp
  void handle(State& s);
  void impact(State& s, const std::vector<int>& closing);
  void settle(State& s, std::vector<int> candidates);
  bool zeno(int i, double t, double& predicted);
  void count_event(double t, const std::string& who);
  void rewrite_last(const State& s);
};

}  // namespace mo2d::detail
