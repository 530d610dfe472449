// Coulomb friction's events in a contact run (contact_run.hpp; the forces: contact_forces.hpp):
// a closed contact with friction slides (slip, sign s) or sticks; slip ends where v_t crosses 0
// (stick if the sticking force fits in the cone, else sliding back), stick ends where the
// tangential force reaches the cone's edge mu N (slip against that force).
#include <algorithm>
#include <cmath>

#include "contact/contact_run.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

double ContactRunner::slide_condition(int i) const {
  const size_t k = static_cast<size_t>(i);
  switch (forces_->slide[k]) {
    case SlideMode::none:
      break;
    case SlideMode::slip:
      return (forces_->slip_sign[k] * forces_->last_tangent(i).rate + slack_t_[k]) / scale_;
    case SlideMode::stick: {
      const double cone = law(i).friction * forces_->normal[i], Ft = forces_->tangential[i];
      return (cone - std::abs(Ft)) / std::max(cone + std::abs(Ft), 1e-300);
    }
  }
  return 1e300;
}

bool ContactRunner::any_rows() const {
  for (int i = 0; i < forces_->size(); ++i)
    if (mode(i) == ContactMode::persistent ||
        forces_->slide[static_cast<size_t>(i)] != SlideMode::none)
      return true;
  return false;
}

void ContactRunner::update_forces(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  scratch_f_.setZero();
  forces_->add(t, q0, q1, scratch_f_);
  lambda_ref_ = std::max(lambda_ref_, forces_->lambda.cwiseAbs().maxCoeff());
}

// Contact i has just closed (a compliant onset, or held persistent): it slides in the direction
// of v_t, or, at (nearly) no sliding speed (|v_t| <= zeno_speed), it tries to stick
// (release_one checks the cone). A compliant contact at its onset has no normal force yet: it
// slides (in v_t's direction, forward at v_t = 0), and sticks where v_t crosses 0.
void ContactRunner::start_sliding(const State& s, int i, bool compliant_onset) {
  const size_t k = static_cast<size_t>(i);
  forces_->slide[k] = SlideMode::none;
  if (!forces_->rough(i)) return;
  const double vt = forces_->tangent(i, s.q0, s.q1).rate;
  if (!compliant_onset && std::abs(vt) <= co_.zeno_speed) {
    forces_->slide[k] = SlideMode::stick;
    return;
  }
  forces_->slide[k] = SlideMode::slip;
  forces_->slip_sign[k] = vt >= 0 ? 1.0 : -1.0;
  loosen_slip(i);
}

// Among `candidates`: the persistent contact whose normal multiplier pulls most is released
// (open), or else the sticking one furthest outside its cone slips against its tangential force;
// true if one changed (the forces are evaluated at s first).
bool ContactRunner::release_one(const std::vector<int>& candidates, const State& s) {
  update_forces(s.t, s.q0, s.q1);
  int worst = -1, outside = -1;
  double excess = 0;
  for (int i : candidates) {
    const size_t k = static_cast<size_t>(i);
    if (mode(i) == ContactMode::persistent && forces_->lambda[i] <= 0 &&
        (worst < 0 || forces_->lambda[i] < forces_->lambda[worst]))
      worst = i;
    if (forces_->slide[k] != SlideMode::stick) continue;
    const double over = std::abs(forces_->tangential[i]) - law(i).friction * forces_->normal[i];
    if (over >= 0 && (outside < 0 || over > excess)) outside = i, excess = over;
  }
  if (worst >= 0) {
    forces_->mode[static_cast<size_t>(worst)] = ContactMode::open;
    forces_->slide[static_cast<size_t>(worst)] = SlideMode::none;
    return true;
  }
  if (outside < 0) return false;
  const size_t k = static_cast<size_t>(outside);
  forces_->slide[k] = SlideMode::slip;
  forces_->slip_sign[k] = forces_->tangential[outside] > 0 ? -1.0 : 1.0;
  loosen_slip(outside);
  return true;
}

// The sliding events at s: contacts whose slip reached v_t = 0 (with every other sliding contact
// at |v_t| <= zeno_speed: a body's corners stop together) try to stick; contacts whose sticking
// force reached the cone's edge slip against it. Each contact whose mode changed is an event
// (stick or slip).
void ContactRunner::slide_events(State& s, const std::vector<int>& which) {
  std::vector<int> changed;
  bool stopping = false;
  for (int i : which) {
    const size_t k = static_cast<size_t>(i);
    if (forces_->slide[k] == SlideMode::slip) {
      stopping = true;
      continue;
    }
    forces_->slide[k] = SlideMode::slip;  // the cone's edge: slip against the tangential force
    forces_->slip_sign[k] = forces_->tangential[i] > 0 ? -1.0 : 1.0;
    loosen_slip(i);
    changed.push_back(i);
  }
  std::vector<int> trying;
  if (stopping)
    for (int i = 0; i < forces_->size(); ++i) {
      const size_t k = static_cast<size_t>(i);
      if (forces_->slide[k] != SlideMode::slip ||
          std::find(changed.begin(), changed.end(), i) != changed.end())
        continue;
      const bool crossed = std::find(which.begin(), which.end(), i) != which.end();
      if (crossed || std::abs(forces_->last_tangent(i).rate) <= co_.zeno_speed) {
        forces_->slide[k] = SlideMode::stick;
        trying.push_back(i);
      }
    }
  while (release_one(trying, s)) {
  }
  changed.insert(changed.end(), trying.begin(), trying.end());
  for (int i : changed) {
    count_event(s.t, name(i));
    const bool stick = forces_->slide[static_cast<size_t>(i)] == SlideMode::stick;
    events_.push_back(
        {stick ? ContactEvent::Kind::stick : ContactEvent::Kind::slip, s.t, name(i), 0, 0, 0, 0});
  }
}

}  // namespace mo2d::detail
