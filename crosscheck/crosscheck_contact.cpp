// Contact cross-check (issue 35, item 4): mo2d's event-driven contact run (contact_dynamics) and
// Box2D with the contacts' shapes (box2d_contacts.cpp) integrate the same motion from the same
// state; centres of mass and angles are compared at instants on Box2D steps, and each contact's
// impacts one by one: time, approach speed, separation speed.
//
// Box2D's impacts are read from its own state with mo2d's gap function (contact/contact_set.hpp,
// as the loads are: docs/crosscheck.md, "Shared code"): the k-th impact of a contact is its k-th
// closing, the gap g > 0 at the end of one step and <= 0 at the end of the next, at the time where
// the straight line between the two values crosses 0, after at least min_impact_steps / 2 open
// step ends (Box2D's flights may be shorter than mo2d's by its error); its approach speed is -g' at
// the step before (the last open state), its separation speed g' at the first step after with g' >
// 0 (the step whose impulse turned it back).
#include <algorithm>
#include <cmath>

#include "box2d_world.hpp"
#include "contact/contact_set.hpp"
#include "crosscheck_budget.hpp"
#include "mo2d/contact.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

using crosscheck_detail::Box2DWorld;

// One contact's closings in Box2D's run.
struct Box2DImpacts {
  detail::CompiledContact contact;
  GapValue gap{};
  double last_g = 0, last_rate = 0, last_t = 0;
  int open_steps = 0;            // consecutive step ends with g > 0
  bool waiting_rebound = false;  // a closing whose separation speed is not read yet
  std::vector<double> t{}, speed{}, after{};
  double deepest = 0;  // most negative g (m)
};

// A closing after at least min_open open step ends is an impact (Box2D's resting contacts open
// and close by a fraction of b2_linearSlop from one step to the next: not impacts).
void watch(const Model& m, const Box2DWorld& w, double t, int min_open, Box2DImpacts& c) {
  detail::gap_into(m, c.contact, w.q0, w.q1, c.gap);
  const double g = c.gap.g, rate = c.gap.rate;
  c.deepest = std::fmin(c.deepest, g);
  const int open = c.open_steps;
  c.open_steps = g > 0 ? c.open_steps + 1 : 0;
  if (c.last_g > 0 && g <= 0 && open >= min_open) {
    c.t.push_back(c.last_t + (t - c.last_t) * c.last_g / (c.last_g - g));
    c.speed.push_back(-c.last_rate);
    c.after.push_back(0);
    c.waiting_rebound = true;
  } else if (c.waiting_rebound && rate > 0) {
    c.after.back() = rate;
    c.waiting_rebound = false;
  }
  c.last_g = g;
  c.last_rate = rate;
  c.last_t = t;
}

}  // namespace

ContactCrosscheck crosscheck_contacts(const Model& reference_in,
                                      const std::vector<ContactDef>& reference_contacts,
                                      const Model& model_in,
                                      const std::vector<ContactDef>& contacts, const State& initial,
                                      double t1, const CrosscheckOptions& check, int samples,
                                      const ContactOptions& run) {
  using namespace crosscheck_detail;
  std::vector<std::string> notes, reference_notes;
  const Model model = with_inertia_floor(model_in, check.zero_inertia_fraction, notes);
  const Model reference =
      with_inertia_floor(reference_in, check.zero_inertia_fraction, reference_notes);
  const std::string what = "Box2D contact cross-check of '" + model.name + "'";
  if (reference.n0 != model.n0 || reference.bodies.size() != model.bodies.size() ||
      reference_contacts.size() != contacts.size())
    throw Error(what +
                    ": the reference model must have the simulated model's variables and "
                    "contacts",
                model.name);
  if (!(check.step > 0) || samples < 2 || !(t1 > initial.t))
    throw Error(what + ": need step > 0, samples >= 2 and t1 > t0", model.name);
  check_result_memory(what, model.name, samples, 3, check);
  ContactCrosscheck r;
  ForwardCrosscheck& f = r.motion;
  f.notes = notes;
  f.mechanism = model.name;
  // the translation first: a refusal names the element before any run
  Box2DWorld w = build_box2d_world(model, initial.q0, initial.q1, check, false);
  add_contact_shapes(model, w, contacts, check);
  const double h = check.step;
  // samples on step ends, stride steps apart, up to t1 (within a stride): more samples than asked
  // when the run is not a multiple of (samples - 1) steps, fewer when it has fewer steps
  const double stride_wanted =
      std::fmax(1, std::floor((t1 - initial.t) / h / (samples - 1) + 1e-9));
  check_box2d_steps(what, model.name, (t1 - initial.t) / h, h, check);
  const int stride = static_cast<int>(stride_wanted);
  samples = std::max(2, static_cast<int>(std::floor((t1 - initial.t) / (stride * h) + 1e-9)) + 1);
  check_result_memory(what, model.name, samples, 3, check);
  const int min_open = std::max(1, check.min_impact_steps / 2);
  f.step = h;
  f.steps = stride * (samples - 1);
  ContactOptions o = run;
  o.forward.t0 = initial.t;
  o.forward.t1 = initial.t + f.steps * h;
  o.forward.samples = samples;
  const ContactRun ref = contact_dynamics(reference, reference_contacts, initial, o);
  r.events = ref.events;
  const Trajectory& tr = ref.trajectory;
  if (tr.time.size() != samples)
    throw Error(what + ": mo2d's run returned " + std::to_string(tr.time.size()) +
                    " samples, not " + std::to_string(samples),
                model.name);
  detail::RunBudget budget(box2d_budget(what, model.name, initial.t, o.forward.t1, check));

  std::vector<Box2DImpacts> watched;
  for (const ContactDef& c : contacts) {
    Box2DImpacts b{.contact = detail::compile_contact(model, c)};
    b.gap.J = Eigen::VectorXd::Zero(model.n1);
    watched.push_back(std::move(b));
  }
  read_box2d_state(model, w, 0.0);
  for (Box2DImpacts& c : watched) watch(model, w, initial.t, min_open, c);
  f.time = tr.time;
  f.position_error = Eigen::VectorXd::Zero(samples);
  f.angle_error = Eigen::VectorXd::Zero(samples);
  f.energy_difference = Eigen::VectorXd::Zero(samples);
  f.kinetic_peak = tr.kinetic.size() ? tr.kinetic.maxCoeff() : 0.0;
  for (int s = 0; s < samples; ++s) {
    if (s > 0)
      for (int n = 0; n < stride; ++n) {
        const int step = (s - 1) * stride + n;
        budget.check(initial.t + step * h, step, h);
        apply_loads(model, w, initial.t + step * h, h);
        w.world->Step(static_cast<float>(h), check.velocity_iterations, check.position_iterations);
        read_box2d_state(model, w, 0.0);  // h = 0: no coordinate integrated twice
        for (Box2DImpacts& c : watched) watch(model, w, initial.t + (step + 1) * h, min_open, c);
      }
    const Eigen::VectorXd q0 = tr.q0.row(s).transpose();
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      const b2Vec2 c = w.bodies[b].body->GetPosition();
      const double dp = (Vec2(c.x, c.y) - com_position(model.bodies[b], q0)).norm();
      f.position_error[s] = std::fmax(f.position_error[s], dp);
      if (w.bodies[b].oriented && w.bodies[b].rotates) {
        const double da = wrap_angle(w.bodies[b].body->GetAngle() -
                                     box2d_angle(model, w, static_cast<int>(b), q0));
        f.angle_error[s] = std::fmax(f.angle_error[s], std::fabs(da));
      }
    }
    f.energy_difference[s] = kinetic_energy(model, w.q1) + potential_energy(model, w.q0) -
                             tr.kinetic[s] - tr.potential[s];
  }
  f.max_position_error = f.position_error.maxCoeff();
  f.max_angle_error = f.angle_error.maxCoeff();
  f.final_position_error = f.position_error[samples - 1];
  f.final_angle_error = f.angle_error[samples - 1];
  f.relative_position_error = f.max_position_error / model.scale;

  // the impacts, contact by contact, in order, while mo2d's impacts are resolvable by Box2D's
  // step: the interval since the contact's previous event at least min_impact_steps steps
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Box2DImpacts& b = watched[k];
    r.box2d_impacts += static_cast<int>(b.t.size());
    r.deepest_penetration = std::fmin(r.deepest_penetration, b.deepest);
    double previous = initial.t, previous_box2d = initial.t;
    size_t index = 0;
    bool resolvable = true;
    for (const ContactEvent& e : ref.events) {
      if (e.contact != contacts[k].name) continue;
      if (e.kind != ContactEvent::Kind::impact) {
        previous = e.t;
        previous_box2d = e.t;  // Box2D's lift-off is not read: from mo2d's
        if (e.kind == ContactEvent::Kind::zeno) resolvable = false;
        continue;
      }
      ++r.mo2d_impacts;
      resolvable = resolvable && e.t - previous >= check.min_impact_steps * h;
      const double previous_mo2d_impact = previous;
      previous = e.t;
      if (!resolvable) continue;
      ImpactComparison c{.contact = e.contact, .index = static_cast<int>(index)};
      c.t_mo2d = e.t;
      c.speed_mo2d = e.speed;
      c.after_mo2d = e.speed_after;
      c.interval_mo2d = e.t - previous_mo2d_impact;
      if (index < b.t.size()) {
        c.t_box2d = b.t[index];
        c.speed_box2d = b.speed[index];
        c.after_box2d = b.after[index];
        c.interval_box2d = b.t[index] - previous_box2d;
        previous_box2d = b.t[index];
        c.found = true;
      }
      ++index;
      r.impacts.push_back(c);
    }
  }
  double speed_ref = 0;
  for (const ImpactComparison& c : r.impacts) speed_ref = std::fmax(speed_ref, c.speed_mo2d);
  r.speed_scale = speed_ref;
  for (const ImpactComparison& c : r.impacts) {
    if (!c.found) {
      r.missing = true;
      continue;
    }
    r.max_time_error = std::fmax(r.max_time_error, std::fabs(c.t_box2d - c.t_mo2d));
    r.max_interval_error =
        std::fmax(r.max_interval_error, std::fabs(c.interval_box2d - c.interval_mo2d) / h);
    if (speed_ref > 0) {
      r.max_speed_error =
          std::fmax(r.max_speed_error, std::fabs(c.speed_box2d - c.speed_mo2d) / speed_ref);
      r.max_rebound_error =
          std::fmax(r.max_rebound_error, std::fabs(c.after_box2d - c.after_mo2d) / speed_ref);
    }
  }
  return r;
}

bool contact_agrees(const ContactCrosscheck& r, const ContactTolerances& tol) {
  return !r.missing && r.motion.relative_position_error <= tol.position &&
         r.max_interval_error <= tol.interval_steps && r.max_speed_error <= tol.speed &&
         r.max_rebound_error <= tol.speed;
}

}  // namespace mo2d
