#pragma once
// A slot in the contact stage (internal to src/contact/; the maths: slot.hpp): its checks, its
// three parts' gaps, and SlotRegions, the run's state of which pins are inside their slots, with
// the condition the root finding watches and the switch at the mouth.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/contact_set.hpp"

namespace mo2d::detail {

// Throws Error naming the contact for a bad width (<= 2 radius, not finite) or a == b.
void check_slot(const ContactDef& c);
// Throws Error naming the contact for a slot whose ends are not on one body (or both on the
// ground) or whose length is not more than the pin's radius.
void check_slot_points(const Model& m, const CompiledContact& c);
// The gap of a slot's part c (slot.hpp) into out (as gap_into), and the gap alone.
void slot_gap_into(const Model& m, const CompiledContact& c,
                   const Eigen::Ref<const Eigen::VectorXd>& q0,
                   const Eigen::Ref<const Eigen::VectorXd>& q1, GapValue& out);
double slot_gap_only(const Model& m, const CompiledContact& c,
                     const Eigen::Ref<const Eigen::VectorXd>& q0);

// The slots among a run's contacts (each three consecutive parts, left first) and whether each
// pin is inside. The condition of a slot, positive in its current region (slot.hpp):
//   inside   min(L - s, w/2 - |l|, s) + slack,   outside   max(s - L, |l| - w/2, -s) + slack,
// with a slack as the contacts' (contact_run.hpp): |condition| (1 + 16 eps) right after a switch,
// 0 again once the condition is positive at a step's end.
class SlotRegions {
 public:
  explicit SlotRegions(std::vector<CompiledContact>& contacts);
  // each pin's region at q0 (the run's start)
  void start(const Model& m, const Eigen::VectorXd& q0);
  // the least condition at q0 (m); 1e300 without slots
  double condition(const Model& m, const Eigen::VectorXd& q0) const;
  // at a step's end: the slack of a slot strictly inside its region there is 0 from the next step
  // end on (as the contacts', contact_run.hpp); at a leg's start, none pending
  void step_end(const Model& m, const Eigen::VectorXd& q0);
  void leg_start() {
    for (Slot& s : slots_) s.unslack = false;
  }
  // switches the slots whose condition is <= 0 at (t, q0), each an `enter` or `leave` event
  // appended to `events`; the number switched. Throws Error naming the slot and the time where a
  // pin crosses a side other than the mouth.
  int handle(const Model& m, double t, const Eigen::VectorXd& q0,
             std::vector<ContactEvent>& events);

 private:
  struct Slot {
    size_t first = 0;  // its left wall's index in the contacts
    std::string name;
    double slack = 0;
    bool unslack = false;
  };
  std::vector<CompiledContact>& cs_;
  std::vector<Slot> slots_;
  // the condition without the slack at q0, and the side it is nearest (0 mouth, 1 wall, 2 end)
  double raw(const Model& m, const Slot& s, const Eigen::VectorXd& q0, int& side) const;
};

}  // namespace mo2d::detail
