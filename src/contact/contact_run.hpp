#pragma once
// The event-driven contact run (internal to src/contact/): legs of forward dynamics between
// events (contact_run.cpp), each with the contacts' forces as ForwardOptions::extra_forces and
// their mode conditions as ForwardOptions::stop_when; the events themselves (contact_events.cpp).
//
// Each contact has a condition, positive inside its mode and located by the root finding:
//   open:        g + slack           (closing: a compliant onset or a rigid impact)
//   compliant:   -g + slack          (the exit)
//   persistent:  lambda / lambda_ref (the lift-off: the multiplier reaches 0)
// and with friction, while closed (contact_friction.cpp):
//   slip:        (s v_t + slack_t) / scale   (v_t crosses 0: stick, or sliding back)
//   stick:       (mu N - |lambda_t|) / lambda_ref   (the cone's edge: slip starts)
// The root finding returns the state just past the root (the condition's sign changed: g a hair
// below 0 at an impact, by about |g'| 1e-13 t; or exactly 0). slack is 0, except right after an
// event of the contact: then |g| (1 + 16 eps) + 1e-300, until the gap is strictly inside the new
// mode at a step's end (g > 0 open, g < 0 compliant), so that every mode starts with its
// condition > 0 and a contact leaving does not close again at once. Not more: a ball whose
// bounces are shorter than one step never shows g > 0 at a step's end, and its next impact is
// located at g = -slack, deeper by any floor added at every bounce, gaining m g floor from
// gravity each time (with a floor of 2e-11 m the Zeno ball of tests/contact/rigid_test.cpp
// settled into bounces of 3.5e-6 s that gained what they lost; with 2.8e-12 m its accumulation
// time came out 2.2e-7 s late). tol_g = kContactGapTolerance * Model::scale bounds the initial
// penetration and the excursions between step ends.
#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_forces.hpp"
#include "contact/slot_set.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/contact.hpp"

namespace mo2d::detail {

inline constexpr double kContactGapTolerance = 1e-10;  // relative to Model::scale
inline constexpr int kContactChatter = 8;  // events at one instant before the run is refused

// The global error estimate of a contact run into run.trajectory.stats, when options ask for it
// (ContactOptions::accuracy; contact_estimate.cpp).
void estimate_contact_error(const Model& m, const std::vector<ContactDef>& contacts,
                            const State& initial, const ContactOptions& options, ContactRun& run);

class ContactRunner {
 public:
  ContactRunner(const Model& m, const std::vector<ContactDef>& defs, const ContactOptions& o);
  ContactRun run(const State& initial);

 private:
  const Model& m_;
  const ContactOptions& co_;
  ForwardOptions inner_;
  std::unique_ptr<ContactForces> forces_;
  std::unique_ptr<SlotRegions> slots_;  // the pins in slots (slot_set.hpp)
  double scale_ = 1, tol_g_ = 0, lambda_ref_ = 0;
  double zeno_time_ = 0;  // ContactOptions::zeno_time, or its default
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
  // per contact: the open condition's offset (see the file's description), and whether it goes
  // back to 0 at the next step's end: a step end where the gap is strictly inside its mode may
  // still hold another contact's root, whose search evaluates the condition again at the step's
  // start, where it needs its slack (a lip hit of mechanisms/geneva.yaml found the root at the
  // start of the step, at the impact just handled, again and again)
  std::vector<double> slack_;
  std::vector<char> unslack_;
  // (g from gap_only, which the condition evaluates: gap_into's Jets round differently)
  void loosen(int i, const Eigen::VectorXd& q0) {
    const double g = gap_only(m_, forces_->contacts[static_cast<size_t>(i)], q0);
    slack_[static_cast<size_t>(i)] =
        std::abs(g) * (1 + 16 * std::numeric_limits<double>::epsilon()) + 1e-300;
  }
  Eigen::VectorXd scratch_f_;
  // per contact: the slip condition's offset, |v_t| (1 + 16 eps) right after its slip started,
  // until s v_t > 0 at a step's end
  std::vector<double> slack_t_;
  void loosen_slip(int i) {
    slack_t_[static_cast<size_t>(i)] = std::abs(forces_->last_tangent(i).rate) *
                                           (1 + 16 * std::numeric_limits<double>::epsilon()) +
                                       1e-300;
  }

  const std::string& name(int i) const {
    return forces_->contacts[static_cast<size_t>(i)].def.name;
  }
  const ContactLaw& law(int i) const { return forces_->contacts[static_cast<size_t>(i)].def.law; }
  ContactMode mode(int i) const { return forces_->mode[static_cast<size_t>(i)]; }
  double condition(int i, double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  double normal_condition(int i, const Eigen::VectorXd& q0);
  // contact_friction.cpp
  double slide_condition(int i) const;
  bool any_rows() const;  // a persistent or sticking contact: the forces' multipliers needed
  void update_forces(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1);
  void start_sliding(const State& s, int i, bool compliant_onset);
  bool release_one(const std::vector<int>& candidates, const State& s);
  void slide_events(State& s, const std::vector<int>& which);
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
