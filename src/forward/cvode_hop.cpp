// cvode_bdf over a singular passage where its step collapses. Next to a singular configuration
// the accelerations are regularized (ForwardData): not a smooth function of the state at the
// scale of BDF's Newton iterations, so its error test or its Newton iteration can fail at every
// step size: four-bar chains of 11 to 40 loops collapsed to steps of 1e-8 ... 1e-35 s at their
// flat position (t = 0.72 s), and the double four-bar at rtol 1e-12, at some tolerances and not
// at others. Fixed-step rk4 steps over such instants (forward_rk.cpp: stages projected), so the
// passage is handed to rk4 at the step CVODE took before the collapse, from the last output time
// (forward_cvode.cpp: hop); CVODE restarts after it. The error over a hop is not controlled by
// rtol: the run's warning names the hops, their steps and the time they covered.
#include "forward/cvode_hop.hpp"

#include <algorithm>
#include <string>

#include "forward/forward_run.hpp"
#include "mo2d/quasi_steady.hpp"

namespace mo2d::detail {

bool can_hop(const Model& m, const ForwardOptions& o) {
  return !o.stop_when && !switches_chains(m) && !has_quasi_steady(m);
}

HopResult hop_over(const Model& m, const ForwardOptions& o, const State& from, double t_out,
                   double seconds_left, long steps_left, double step) {
  ForwardOptions h = o;
  h.t0 = from.t;
  h.t1 = t_out;
  h.samples = 2;
  h.integrator = Integrator::rk4;
  h.step = step;
  h.accuracy = 0;
  h.error_estimate = ErrorEstimate::off;
  h.max_seconds = o.max_seconds > 0 ? std::max(seconds_left, 1e-3) : 0;
  h.max_steps = static_cast<int>(std::max(1L, std::min<long>(steps_left, o.max_steps)));
  const Trajectory r = forward_run(m, from, h);
  const Eigen::Index e = r.time.size() - 1;
  HopResult out;
  out.state = {r.time[e], r.q0.row(e).transpose(), r.q1.row(e).transpose()};
  out.energies[kInputWork] = r.input_work[e] - r.input_work[0];
  out.energies[kLoadWork] = r.load_work[e] - r.load_work[0];
  out.energies[kConstraintWork] = r.constraint_work[e] - r.constraint_work[0];
  out.energies[kDissipated] = r.dissipated[e] - r.dissipated[0];
  out.steps = r.stats.steps;
  return out;
}

}  // namespace mo2d::detail
