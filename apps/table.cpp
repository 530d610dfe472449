// Short result tables on stdout.
#include "table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace mo2d::cli {

std::string shortest(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return {buf, end};
}

void print_inverse_table(const Model& model, const Trajectory& r, const InverseOptions& run) {
  std::printf(
      "  %d bodies, %d coordinates, %d quasi-velocities, %d DOF, %d samples over [%g, %g] s\n",
      static_cast<int>(model.bodies.size()), model.n0, model.n1, model.dof,
      static_cast<int>(r.time.size()), run.t0, run.t1);
  std::printf("  max constraint residual: position %.2e m, velocity %.2e, acceleration %.2e\n",
              r.residuals.col(0).maxCoeff(), r.residuals.col(1).maxCoeff(),
              r.residuals.col(2).maxCoeff());
  for (const auto& w : r.stats.warnings) std::printf("  warning: %s\n", w.c_str());
  std::printf("  CPU time %.3f ms (%.2f us per sample)\n", 1e3 * r.stats.cpu_seconds,
              1e6 * r.stats.cpu_seconds / static_cast<double>(r.time.size()));
}

void print_peaks_table(const Trajectory& r, const std::vector<Extreme>& extremes) {
  if (r.input_labels.empty()) return;
  std::printf("  %-24s %18s %14s %18s %14s\n", "input (peaks located)", "max", "at t [s]", "min",
              "at t [s]");
  for (const Extreme& e : extremes)
    if (std::find(r.input_labels.begin(), r.input_labels.end(), e.label) != r.input_labels.end())
      std::printf("  %-24s %18.11g %14.10f %18.11g %14.10f%s\n", e.label.c_str(), e.max, e.t_max,
                  e.min, e.t_min, e.located_max && e.located_min ? "" : "  (sampled)");
}

void print_tracking_table(const std::vector<TrackingError>& tracking) {
  if (tracking.empty()) return;
  std::printf("  %-24s %-16s %14s %10s %14s\n", "controller (input)", "coordinate", "max |x - r|",
              "at t [s]", "final x - r");
  for (const TrackingError& e : tracking)
    std::printf("  %-24s %-16s %14.6e %10.4f %14.6e\n", e.input.c_str(), e.coordinate.c_str(),
                std::abs(e.max_error), e.t_max, e.final_error);
}

void print_contact_events(const std::vector<ContactEvent>& events) {
  if (events.empty()) return;
  int count[7] = {0, 0, 0, 0, 0, 0, 0};  // by ContactEvent::Kind
  double lost = 0, last = -1;
  for (const ContactEvent& e : events) {
    ++count[static_cast<int>(e.kind)];
    if (e.kind == ContactEvent::Kind::impact && e.t != last) lost += e.energy_lost, last = e.t;
  }
  std::printf(
      "  contact events: %zu (%d impacts dissipating %.6g J; %d lift-offs; %d Zeno "
      "accumulations; %d onsets, %d exits",
      events.size(), count[2], lost, count[3], count[4], count[0], count[1]);
  if (count[5] + count[6] > 0) std::printf("; %d sticks, %d slips", count[5], count[6]);
  std::printf(")\n");
  std::printf("  %-16s %-9s %-16s %14s %14s %14s %14s\n", "t [s]", "event", "contact",
              "before [m/s]", "after [m/s]", "impulse [N s]", "lost [J]");
  for (size_t k = 0; k < events.size() && k < kListedContactEvents; ++k) {
    const ContactEvent& e = events[k];
    std::printf("  %-16.10g %-9s %-16s %14.6g %14.6g %14.6g %14.6g", e.t,
                contact_event_name(e.kind), e.contact.c_str(), e.speed, e.speed_after, e.impulse,
                e.energy_lost);
    if (e.kind == ContactEvent::Kind::zeno)
      std::printf("  accumulation at t = %.10g s: persistent contact", e.predicted_t);
    std::printf("\n");
  }
  if (events.size() > kListedContactEvents)
    std::printf("  ... %zu more (all in the JSON summary)\n", events.size() - kListedContactEvents);
}

void print_inverse_contacts(const std::vector<InverseContact>& contacts) {
  for (const InverseContact& c : contacts) {
    if (!c.held) {
      std::printf(
          "  contact %s: open at the start (gap %.6g m), left out; least gap %.6g m at t "
          "= %.10g s\n",
          c.name.c_str(), c.gap, c.min_gap, c.t_min_gap);
      continue;
    }
    std::printf("  contact %s: held closed, normal force %s: least %.10g N at t = %.10g s",
                c.name.c_str(), c.column.c_str(), c.min_force, c.t_min);
    if (c.pulls)
      std::printf("; negative from t = %.10g s: a preload of %.10g N prevents it", c.t_negative,
                  c.preload);
    std::printf("\n");
    if (c.pulls)
      std::fprintf(stderr,
                   "mo2d: warning: contact '%s': the prescribed motion needs a negative (pulling) "
                   "contact force from t = %.10g s (the contact would open: a follower lifts off); "
                   "least %.10g N at t = %.10g s; an extra force of %.10g N pressing it closed "
                   "(a spring's preload) prevents it\n",
                   c.name.c_str(), c.t_negative, c.min_force, c.t_min, c.preload);
  }
}

double energy_error(const Trajectory& r) {
  return energy_balance_error(r);
}

void print_forward_table(const Model& model, const Trajectory& r, const ForwardOptions& run) {
  std::printf(
      "  %d bodies, %d coordinates, %d quasi-velocities, %d DOF, %d samples over [%g, %g] s\n",
      static_cast<int>(model.bodies.size()), model.n0, model.n1, model.dof,
      static_cast<int>(r.time.size()), run.t0, r.stats.t_end);
  std::printf(
      "  integrator %s, formulation %s, %s linear algebra: %ld steps, %ld right-hand sides, %ld "
      "projections\n",
      r.stats.integrator.empty() ? to_string(run.integrator) : r.stats.integrator.c_str(),
      to_string(run.formulation), r.stats.sparse ? "sparse" : "dense", r.stats.steps,
      r.stats.rhs_evaluations, r.stats.projections);
  if (!r.stats.method.empty()) std::printf("  method: %s\n", r.stats.method.c_str());
  if (std::isnan(r.stats.estimated_error))
    std::printf("  estimated error: %s\n", r.stats.error_estimate.c_str());
  else
    std::printf(
        "  estimated error: %.2e of the mechanism's size, largest at t = %g s in '%s' (%s; %.3f ms "
        "CPU)\n",
        r.stats.estimated_error, r.stats.estimated_error_t,
        r.stats.estimated_error_variable.c_str(), r.stats.error_estimate.c_str(),
        1e3 * r.stats.estimate_cpu_seconds);
  std::printf("  max constraint residual: position %.2e m, velocity %.2e\n",
              r.residuals.col(0).maxCoeff(), r.residuals.col(1).maxCoeff());
  const Eigen::Index n = r.time.size() - 1;
  std::printf("  energy: kinetic %.6g J, potential %.6g J at the end; balance error %.2e J\n",
              r.kinetic[n], r.potential[n], energy_error(r));
  for (const auto& w : r.stats.warnings) std::printf("  warning: %s\n", w.c_str());
  std::printf("  CPU time %.3f ms\n", 1e3 * r.stats.cpu_seconds);
}

}  // namespace mo2d::cli
