// The events of a contact run (contact_run.hpp): a compliant contact's onset and exit, a rigid
// impact (impact.hpp) with the Zeno test, a persistent contact's lift-off. Every event is in the
// run's events; impacts, Zeno accumulations and lift-offs also in its warnings (the first
// kListedEvents of them, then a count).
#include <algorithm>
#include <cmath>

#include "contact/contact_run.hpp"
#include "contact/impact.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {
namespace {

constexpr double kTouch = 1e3;   // contacts within kTouch tol_g of closing join an impact
constexpr double kSteady = 0.1;  // Zeno: the interval ratios agree within 10 %

}  // namespace

void ContactRunner::count_event(double t, const std::string& who) {
  if (static_cast<int>(events_.size()) > co_.max_events)
    throw Error("contact dynamics of '" + m_.name + "': more than " +
                    std::to_string(co_.max_events) + " contact events by t = " + fmt(t) +
                    " s (the last: contact '" + who + "'): the contacts chatter",
                who, t);
  if (t - last_event_ <= 1e-12 * std::max(1.0, std::abs(t))) {
    if (++same_instant_ > kContactChatter)
      throw Error("contact '" + who + "': " + std::to_string(same_instant_) +
                      " contact events at t = " + fmt(t) +
                      " s (the modes chatter at one instant): the contact problem has no "
                      "consistent mode there",
                  who, t);
  } else {
    same_instant_ = 0;
  }
  last_event_ = t;
  switched_ = true;
}

void ContactRunner::handle(State& s) {
  const size_t before = events_.size();  // a pin entering or leaving a slot (slot_set.hpp)
  const bool any_slot = slots_->handle(m_, s.t, s.q0, events_) > 0;
  for (size_t k = before; k < events_.size(); ++k) count_event(s.t, events_[k].contact);
  if (any_rows()) update_forces(s.t, s.q0, s.q1);  // the multipliers and sliding rates at s
  std::vector<int> closing, sliding;
  bool any = false;
  for (int i = 0; i < forces_->size(); ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!(normal_condition(i, s.q0) <= 0)) {
      if (slide_condition(i) <= 0) any = true, sliding.push_back(i);
      continue;
    }
    any = true;
    const GapValue& g = forces_->gap(i, s.q0, s.q1);
    count_event(s.t, name(i));
    if (mode(i) == ContactMode::compliant) {  // exit
      forces_->mode[k] = ContactMode::open;
      forces_->slide[k] = SlideMode::none;
      loosen(i, s.q0);
      events_.push_back({ContactEvent::Kind::exit, s.t, name(i), -g.rate, 0, 0, 0});
    } else if (mode(i) == ContactMode::persistent) {  // lift-off
      forces_->mode[k] = ContactMode::open;
      forces_->slide[k] = SlideMode::none;
      loosen(i, s.q0);
      events_.push_back({ContactEvent::Kind::lift_off, s.t, name(i), -g.rate, 0, 0, 0});
    } else if (law(i).kind == ContactLaw::Kind::compliant) {  // onset
      forces_->mode[k] = ContactMode::compliant;
      loosen(i, s.q0);
      forces_->v0[k] = -g.rate;
      start_sliding(s, i, true);
      events_.push_back({ContactEvent::Kind::onset, s.t, name(i), -g.rate, 0, 0, 0});
    } else {
      closing.push_back(i);
    }
  }
  // the root finding stopped where no condition is <= 0 (cannot happen): never loop
  if (!any && !any_slot)
    throw Error("contact dynamics of '" + m_.name + "': an event at t = " + fmt(s.t) +
                    " s that no contact's condition shows: internal error, please report it",
                m_.name, s.t);
  if (!closing.empty())
    impact(s, closing);
  else if (!sliding.empty())
    slide_events(s, sliding);
}

// The rigid contacts at s that join the impact of `closing`: those within kTouch tol_g of
// closing (simultaneous up to the root finding's accuracy) and the persistent ones.
void ContactRunner::impact(State& s, const std::vector<int>& closing) {
  std::vector<int> set;
  for (int i = 0; i < forces_->size(); ++i) {
    if (law(i).kind != ContactLaw::Kind::rigid) continue;
    const bool in =
        std::find(closing.begin(), closing.end(), i) != closing.end() ||
        mode(i) == ContactMode::persistent ||
        gap_only(m_, forces_->contacts[static_cast<size_t>(i)], s.q0) <= kTouch * tol_g_;
    if (in) set.push_back(i);
  }
  const int k = static_cast<int>(set.size());
  Eigen::MatrixXd J(k, m_.n1);
  Eigen::VectorXd rate(k), e(k);
  std::vector<double> predicted(static_cast<size_t>(k), 0.0);
  std::vector<int> candidates;
  std::string names;
  for (int r = 0; r < k; ++r) {
    const int i = set[static_cast<size_t>(r)];
    const GapValue& g = forces_->gap(i, s.q0, s.q1);
    J.row(r) = g.J.transpose();
    rate[r] = g.rate;
    loosen(i, s.q0);
    names += (names.empty() ? "'" : ", '") + name(i) + "'";
    e[r] = law(i).restitution;
    // a persistent contact stays closed; one that accumulates impacts (Zeno) or arrives at
    // (nearly) no speed closes for good: perfectly inelastic
    bool stays = mode(i) == ContactMode::persistent;
    if (!stays && rate[r] < 0) {
      impacts_[static_cast<size_t>(i)].push_back(s.t);
      stays = -rate[r] <= co_.zeno_speed || zeno(i, s.t, predicted[static_cast<size_t>(r)]);
    }
    if (stays) e[r] = 0, candidates.push_back(i);
  }
  ImpactFriction fr{Eigen::MatrixXd::Zero(k, m_.n1), Eigen::VectorXd::Zero(k),
                    Eigen::VectorXd::Zero(k)};
  for (int r = 0; r < k; ++r) {
    const int i = set[static_cast<size_t>(r)];
    if (!forces_->rough(i)) continue;
    const TangentValue& v = forces_->tangent(i, s.q0, s.q1);
    fr.J.row(r) = v.J.transpose();
    fr.rate[r] = v.rate;
    fr.mu[r] = law(i).friction;
  }
  const ImpactResult res = newton_impact(m_, s.t, s.q0, s.q1, J, rate, e, names, &fr);
  s.q1 = res.q1;
  off_[kDissipated] += res.energy_lost;
  off_[kConstraintWork] += res.constraint_work;  // a driven constraint's impulses (impact.hpp)
  // a perfectly inelastic contact that pushed leaves at no speed: it stays (held persistent)
  for (int r = 0; r < k; ++r) {
    const int i = set[static_cast<size_t>(r)];
    if (e[r] == 0 && res.impulse[r] > 0 && mode(i) != ContactMode::persistent &&
        std::find(candidates.begin(), candidates.end(), i) == candidates.end())
      candidates.push_back(i);
  }
  // a candidate that the impact left separating (another contact's impulse lifted it) stays
  // open; a persistent one lifts off (after the impacts in the events)
  std::vector<int> lifted;
  std::erase_if(candidates, [&](int i) {
    const auto r = std::find(set.begin(), set.end(), i) - set.begin();
    if (!(res.rate[r] > co_.zeno_speed)) return false;
    if (mode(i) == ContactMode::persistent) lifted.push_back(static_cast<int>(r));
    return true;
  });
  for (int r = 0; r < k; ++r) {
    const int i = set[static_cast<size_t>(r)];
    if (mode(i) == ContactMode::persistent || (!(res.impulse[r] > 0) && rate[r] >= 0)) continue;
    events_.push_back({ContactEvent::Kind::impact, s.t, name(i), -rate[r], res.impulse[r],
                       res.energy_lost, 0, res.rate[r]});
    if (predicted[static_cast<size_t>(r)] > 0)
      events_.push_back({ContactEvent::Kind::zeno, s.t, name(i), -rate[r], 0, 0,
                         predicted[static_cast<size_t>(r)]});
  }
  for (int r : lifted) {
    const size_t i = static_cast<size_t>(set[static_cast<size_t>(r)]);
    forces_->mode[i] = ContactMode::open;
    forces_->slide[i] = SlideMode::none;
    events_.push_back({ContactEvent::Kind::lift_off, s.t, name(static_cast<int>(i)), -rate[r], 0, 0,
                       0, res.rate[r]});
  }
  settle(s, candidates);
}

// Zeno: the last three intervals between contact i's impacts shrink by a steady ratio r < 1 and
// the rest of the geometric series, dt r / (1 - r), is below zeno_time (its default: 1e-5 of the
// run's duration); `predicted` = its sum,
// the accumulation time.
bool ContactRunner::zeno(int i, double t, double& predicted) {
  const std::vector<double>& T = impacts_[static_cast<size_t>(i)];
  const size_t n = T.size();
  if (n < 4) return false;
  const double d1 = T[n - 3] - T[n - 4], d2 = T[n - 2] - T[n - 3], d3 = T[n - 1] - T[n - 2];
  if (!(d1 > 0 && d2 > 0 && d3 > 0)) return false;
  const double r1 = d2 / d1, r2 = d3 / d2;
  if (!(r2 < 1 && std::abs(r2 - r1) <= kSteady * r1)) return false;
  const double rest = d3 * r2 / (1 - r2);
  if (!(rest < zeno_time_)) return false;
  predicted = t + rest;
  return true;
}

// The contacts `candidates` (after an impact that left them at rest on their surfaces: g'+ = 0)
// held closed as persistent contacts, those whose multipliers are negative released (the most
// negative first, until all that stay push).
void ContactRunner::settle(State& s, std::vector<int> candidates) {
  if (candidates.empty()) return;
  if (static_cast<int>(candidates.size()) > kMaxPersistent)
    throw Error("contact '" + name(candidates[0]) + "': more than " +
                    std::to_string(kMaxPersistent) + " persistent contacts at t = " + fmt(s.t) +
                    " s",
                name(candidates[0]), s.t);
  for (int i : candidates) {
    forces_->mode[static_cast<size_t>(i)] = ContactMode::persistent;
    start_sliding(s, i, false);
  }
  while (release_one(candidates, s)) {
  }
  for (int i : candidates)
    if (forces_->mode[static_cast<size_t>(i)] == ContactMode::persistent)
      lambda_ref_ = std::max(lambda_ref_, std::abs(forces_->lambda[i]));
}

}  // namespace mo2d::detail
