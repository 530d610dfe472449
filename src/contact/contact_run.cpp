// The event-driven contact run: legs between events (contact_run.hpp), and contact_dynamics.
#include "contact/contact_run.hpp"

#include <algorithm>
#include <cmath>

#include "forward/chain_log.hpp"
#include "mo2d/error.hpp"
#include "mo2d/quasi_steady.hpp"
#include "run/format.hpp"
#include "run/time_grid.hpp"

namespace mo2d::detail {

ContactRunner::ContactRunner(const Model& m, const std::vector<ContactDef>& defs,
                             const ContactOptions& o)
    : m_(m), co_(o), inner_(o.forward) {
  if (inner_.stop_when || inner_.extra_forces)
    throw Error("contact dynamics of '" + m.name +
                    "': the forward options' stop_when and extra_forces are the contact stage's "
                    "own (leave them empty)",
                m.name);
  if (inner_.accuracy > 0)
    throw Error("contact dynamics of '" + m.name +
                    "': name an integrator and its tolerances (an accuracy asked for chooses the "
                    "method at the initial state, before any contact closes)",
                m.name);
  if (inner_.integrator == Integrator::cvode_adams || inner_.integrator == Integrator::baumgarte)
    throw Error(
        "contact dynamics of '" + m.name + "': the integrator " + to_string(inner_.integrator) +
            " does not project on the constraints: use dopri5, erk6, erk8, rk4 or cvode_bdf",
        m.name);
  if (switches_chains(m) || has_quasi_steady(m))
    throw Error("contact dynamics of '" + m.name +
                    "': inextensible or quasi-steady elements are not supported with contacts yet",
                m.name);
  inner_.error_estimate = ErrorEstimate::off;
  scale_ = m.scale > 0 ? m.scale : 1.0;
  tol_g_ = kContactGapTolerance * scale_;
  zeno_time_ = o.zeno_time > 0 ? o.zeno_time : 1e-5 * (inner_.t1 - inner_.t0);
  std::vector<CompiledContact> cs;
  for (size_t k = 0; k < defs.size(); ++k) {
    for (size_t j = 0; j < k; ++j)
      if (defs[j].name == defs[k].name)
        throw Error("contact '" + defs[k].name + "' is defined twice", defs[k].name);
    compile_contacts(m, defs[k], cs);
  }
  forces_ = std::make_unique<ContactForces>(m, std::move(cs), inner_, o.baumgarte_rate);
  slots_ = std::make_unique<SlotRegions>(forces_->contacts);
  const size_t n = forces_->contacts.size();
  impacts_.resize(n);
  step_end_.assign(n, {NAN, NAN, NAN});
  excursion_warned_.assign(n, false);
  slack_.assign(n, 0.0);
  slack_t_.assign(n, 0.0);
  unslack_.assign(n, 0);
  scratch_f_ = Eigen::VectorXd::Zero(m.n1);
}

double ContactRunner::normal_condition(int i, const Eigen::VectorXd& q0) {
  switch (mode(i)) {
    case ContactMode::open:
      return (gap_only(m_, forces_->contacts[static_cast<size_t>(i)], q0) +
              slack_[static_cast<size_t>(i)]) /
             scale_;
    case ContactMode::compliant:
      return (slack_[static_cast<size_t>(i)] -
              gap_only(m_, forces_->contacts[static_cast<size_t>(i)], q0)) /
             scale_;
    case ContactMode::persistent:
      break;
  }
  return forces_->lambda[i] / std::max(lambda_ref_, 1e-300);
}

double ContactRunner::condition(int i, double t, const Eigen::VectorXd& q0,
                                const Eigen::VectorXd& q1) {
  (void)t;
  (void)q1;
  return std::min(normal_condition(i, q0), slide_condition(i));
}

double ContactRunner::event(double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  if (any_rows()) update_forces(t, q0, q1);  // the multipliers and sliding rates at this state
  if (t > last_step_t_) check_excursion(t, q0, q1);
  double c = slots_->condition(m_, q0) / scale_;
  for (int i = 0; i < forces_->size(); ++i) c = std::min(c, condition(i, t, q0, q1));
  return c;
}

// A call at a time later than any before is a step's end (the root finding's tries lie inside
// the last step): an open contact whose gap is positive at both ends of a step but whose cubic
// Hermite interpolant from (g, g') at the ends dips below -tol_g may have closed and opened again
// inside the step, unseen by the events. Warned once per contact, with the time.
void ContactRunner::check_excursion(double t, const Eigen::VectorXd& q0,
                                    const Eigen::VectorXd& q1) {
  const double t0 = last_step_t_;
  last_step_t_ = t;
  slots_->step_end(m_, q0);
  for (int i = 0; i < forces_->size(); ++i) {
    const size_t k = static_cast<size_t>(i);
    const GapValue& g = forces_->gap(i, q0, q1);
    const std::array<double, 3> before = step_end_[k];
    step_end_[k] = {t, g.g, g.rate};
    if (unslack_[k]) slack_[k] = 0, unslack_[k] = 0;  // the step before was taken: no root in it
    if ((mode(i) == ContactMode::open && g.g > 0) || (mode(i) == ContactMode::compliant && g.g < 0))
      unslack_[k] = slack_[k] > 0;
    if (forces_->slide[k] == SlideMode::slip &&
        forces_->slip_sign[k] * forces_->tangent(i, q0, q1).rate > 0)
      slack_t_[k] = 0;
    if (mode(i) != ContactMode::open || excursion_warned_[k] || !(before[0] == t0)) continue;
    const double h = t - t0;
    if (!(before[2] < 0 && g.rate > 0 && before[1] > 0 && g.g > 0)) continue;
    double lowest = 1e300;
    for (int j = 1; j < 16; ++j) {  // the cubic Hermite interpolant on a grid of the step
      const double s = j / 16.0;
      const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
      const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
      lowest =
          std::min(lowest, h00 * before[1] + h10 * h * before[2] + h01 * g.g + h11 * h * g.rate);
    }
    if (lowest < -tol_g_) {
      excursion_warned_[k] = true;
      out_.stats.warnings.push_back(
          "contact '" + name(i) + "': its gap may have closed and opened again inside the step " +
          fmt(t0) + " to " + fmt(t) + " s (interpolated low " + fmt(lowest) +
          " m), unseen by the events (a grazing contact): use a tighter tolerance or a shorter "
          "step");
    }
  }
}

// A contact's Error without a time (a gap that could not be evaluated: a profile's closest point
// not found) again with the time t; one with a time as it is.
namespace {
[[noreturn]] void rethrow_contact_error_at(const Error& e, double t) {
  if (!std::isnan(e.time())) throw e;
  throw Error(std::string(e.what()) + " at t = " + fmt(t) + " s", e.element(), t);
}
}  // namespace

Trajectory ContactRunner::leg(const State& s, double t1, int samples) {
  ForwardOptions o = inner_;
  const long steps_left = static_cast<long>(inner_.max_steps) - out_.stats.steps;
  if (steps_left < 1)
    throw Error("contact dynamics of '" + m_.name + "': the run's step budget (max_steps " +
                    std::to_string(inner_.max_steps) + ") ran out at t = " + fmt(s.t) +
                    " s after " + std::to_string(events_.size()) + " contact events",
                "max_steps", s.t);
  o.max_steps = static_cast<int>(steps_left);
  o.t0 = s.t;
  o.t1 = t1;
  o.samples = samples;
  ContactForces* f = forces_.get();
  o.extra_forces = [f](double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                       Eigen::VectorXd& out) {
    try {
      return f->add(t, q0, q1, out);
    } catch (const Error& e) {
      rethrow_contact_error_at(e, t);
    }
  };
  o.stop_when = [this](double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
    try {
      return event(t, q0, q1);
    } catch (const Error& e) {
      rethrow_contact_error_at(e, t);
    }
  };
  last_step_t_ = -1e300;
  std::fill(unslack_.begin(), unslack_.end(), 0);
  slots_->leg_start();
  return forward_run(m_, s, o);
}

ContactRun ContactRunner::run(const State& initial) {
  const int N = inner_.samples;
  out_ = switching_trajectory(m_, N);
  State s = initial;
  s.t = inner_.t0;
  slots_->start(m_, s.q0);
  for (int i = 0; i < forces_->size(); ++i) {
    const double g = gap_only(m_, forces_->contacts[static_cast<size_t>(i)], s.q0);
    if (!std::isfinite(g) || g < -tol_g_)
      throw Error("contact '" + name(i) + "' starts penetrating: its gap is " + fmt(g) +
                      " m at t = " + fmt(s.t) + " s (at most " + fmt(tol_g_) + " allowed)",
                  name(i), s.t);
  }
  // a rigid contact at rest on its surface at the start (|g| <= tol_g, |g'| <= zeno_speed: a
  // follower on its cam, a block on the floor) starts persistent where its multiplier pushes
  // (settle), else open; without this it started open and took an impact at (nearly) no speed
  std::vector<int> resting;
  for (int i = 0; i < forces_->size(); ++i) {
    const GapValue& g = forces_->gap(i, s.q0, s.q1);
    if (law(i).kind == ContactLaw::Kind::rigid && std::abs(g.g) <= tol_g_ &&
        std::abs(g.rate) <= co_.zeno_speed) {
      loosen(i, s.q0);
      resting.push_back(i);
    }
  }
  settle(s, resting);
  const double h = (inner_.t1 - inner_.t0) / (N - 1);
  auto grid = [&](int k) { return sample_time(inner_.t0, inner_.t1, N, k); };
  while (filled_ < N) {
    if (!(event(s.t, s.q0, s.q1) > 0)) {  // a mode that does not hold from its start
      handle(s);
      continue;
    }
    auto near = [&](int k) {
      return k >= 0 && std::abs(s.t - grid(k)) <=
                           std::max(1e-9 * h, 1e3 * kTimeResolution * std::max(1.0, std::abs(s.t)));
    };
    Trajectory r;
    if (near(filled_)) {
      s.t = grid(filled_);
      r = leg(s, inner_.t1, N - filled_);
    } else if (near(filled_ - 1)) {
      s.t = grid(filled_ - 1);
      if (switched_) --filled_;  // an event at this output time: its sample again, after it
      r = leg(s, inner_.t1, N - filled_ + (switched_ ? 0 : 1));
    } else {
      r = leg(s, grid(filled_), 2);
    }
    append_leg(out_, filled_, r, inner_, off_);
    switched_ = false;
    const Eigen::Index e = r.time.size() - 1;
    s.t = r.time[e];
    s.q0 = r.q0.row(e).transpose();
    s.q1 = r.q1.row(e).transpose();
    if (r.stats.stopped_by_event) handle(s);
  }
  if (switched_) rewrite_last(s);
  check_energy_balance(m_, out_);
  return {std::move(out_), std::move(events_)};
}

// An event at the last output time: its sample after the event (the velocities and energies).
void ContactRunner::rewrite_last(const State& s) {
  const Eigen::Index k = inner_.samples - 1;
  out_.q0.row(k) = s.q0.transpose();
  out_.q1.row(k) = s.q1.transpose();
  out_.kinetic[k] = kinetic_energy(m_, s.q1);
  out_.dissipated[k] = off_[kDissipated];
  out_.constraint_work[k] = off_[kConstraintWork];  // a driven constraint's impulses
}

}  // namespace mo2d::detail

namespace mo2d {

const char* contact_event_name(ContactEvent::Kind kind) {
  switch (kind) {
    case ContactEvent::Kind::onset:
      return "onset";
    case ContactEvent::Kind::exit:
      return "exit";
    case ContactEvent::Kind::impact:
      return "impact";
    case ContactEvent::Kind::lift_off:
      return "lift_off";
    case ContactEvent::Kind::enter:
      return "enter";
    case ContactEvent::Kind::leave:
      return "leave";
    case ContactEvent::Kind::zeno:
      return "zeno";
    case ContactEvent::Kind::stick:
      return "stick";
    case ContactEvent::Kind::slip:
      break;
  }
  return "slip";
}

ContactRun contact_dynamics(const Model& m, const std::vector<ContactDef>& contacts,
                            const State& initial, const ContactOptions& options) {
  if (contacts.empty())
    throw Error("contact dynamics of '" + m.name + "': no contacts (use forward_dynamics)", m.name);
  detail::ContactRunner runner(m, contacts, options);
  ContactRun run = runner.run(initial);
  detail::estimate_contact_error(m, contacts, initial, options, run);
  return run;
}

}  // namespace mo2d
