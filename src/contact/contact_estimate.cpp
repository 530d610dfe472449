// The global error estimate of a contact run (ContactOptions::accuracy; the estimator of
// ForwardOptions::error_estimate, forward/error_estimate.cpp): a second contact run from the same
// initial state on the same output times at the tighter setting, the difference of the positions
// at the output times taken as the run's error. The positions are continuous through impacts (a
// velocity jump located dt later moves them by |dv| dt), so the comparison holds across events.
//
// The events are compared too: the same sequence (kind and contact, in order) in both runs, with
// the largest difference of their times in the estimate's text; or, where the sequences part (a
// Zeno accumulation closed after another number of impacts, an event that one run has and the
// other not), a warning naming the first event where they differ: what follows it depends on the
// integrator's tolerance.
#include <cmath>
#include <string>

#include "contact/contact_run.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

namespace {

std::string describe(const ContactEvent& e) {
  return std::string(contact_event_name(e.kind)) + " of '" + e.contact + "' at t = " + fmt(e.t) +
         " s";
}

// The events of a (the run) against b (the second run's): the text appended to the estimate, or
// a warning.
void compare_events(const std::vector<ContactEvent>& a, const std::vector<ContactEvent>& b,
                    Trajectory& r) {
  const size_t n = std::min(a.size(), b.size());
  double worst = 0;
  size_t at = 0;
  for (size_t k = 0; k < n; ++k) {
    if (a[k].kind != b[k].kind || a[k].contact != b[k].contact) {
      r.stats.warnings.push_back("the run's events depend on its tolerance: event " +
                                 std::to_string(k + 1) + " is the " + describe(a[k]) +
                                 " in the run and the " + describe(b[k]) +
                                 " in the error estimate's second run (" + r.stats.error_estimate +
                                 "); the events after it are not reliable at this accuracy");
      return;
    }
    const double dt = std::abs(a[k].t - b[k].t);
    if (!(dt <= worst)) worst = dt, at = k;
  }
  if (a.size() != b.size()) {
    const bool more = a.size() > b.size();
    r.stats.warnings.push_back(
        "the run's events depend on its tolerance: the run has " + std::to_string(a.size()) +
        " events, the error estimate's second run " + std::to_string(b.size()) + " (" +
        r.stats.error_estimate + "); the first of the difference: the " +
        describe(more ? a[n] : b[n]) + (more ? " in the run" : " in the second run"));
    return;
  }
  r.stats.error_estimate +=
      a.empty() ? "; no events in either run"
                : "; the same " + std::to_string(a.size()) + " events in both runs, their times " +
                      "within " + fmt(worst) + " s (largest: the " + describe(a[at]) + ")";
}

}  // namespace

void estimate_contact_error(const Model& m, const std::vector<ContactDef>& contacts,
                            const State& initial, const ContactOptions& options, ContactRun& run) {
  ForwardOptions asked = options.forward;
  asked.accuracy = options.accuracy;
  std::vector<ContactEvent> second;
  const bool estimated = estimate_global_error(m, asked, options.forward, run.trajectory,
                                               [&](const ForwardOptions& o) {
                                                 ContactOptions c = options;
                                                 c.forward = o;
                                                 c.accuracy = 0;
                                                 ContactRunner runner(m, contacts, c);
                                                 ContactRun r = runner.run(initial);
                                                 second = std::move(r.events);
                                                 return std::move(r.trajectory);
                                               });
  if (estimated) compare_events(run.events, second, run.trajectory);
}

}  // namespace mo2d::detail
