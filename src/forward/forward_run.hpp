#pragma once
// Internal to the forward-dynamics implementation: what a run needs besides its workspace
// (ForwardData, mo2d/forward_data.hpp): the energy terms integrated with the state, the output
// recorder (recorder.cpp), and the integrator drivers (forward_rk.cpp, forward_cvode.cpp).
#include <functional>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/jacobian.hpp"
#include "run/format.hpp"
#include "run/run_budget.hpp"

namespace mo2d::detail {

// y = (J J^T + eps * max(1, max diag(J J^T)) I)^-1 J x: the least-squares multipliers of
// J^T y = x, regularized where J loses rank (eps relative to the largest diagonal entry).
VectorXd regularized_normal_solve(const MatrixXd& J, const VectorXd& x, double eps);

// The energy terms integrated along the run, carried as extra states after (q0, q1) under the
// same error control and stages as the state (so that the balance holds to integration accuracy).
enum EnergyTerm { kInputWork, kLoadWork, kConstraintWork, kDissipated, kEnergyTerms };
// Their rates (powers, W) at (t, q0, q1), right after d.accelerations(t, q0, q1, .) there.
void energy_rates(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1, double* rates);

// The rows of the energy terms `terms` (in order) of the run's Jacobian: d rate / d (q0, q1),
// rows terms.size() x (n0 + n1), at the state of the last acceleration_jacobian(d, t, q0, q1, J).
void energy_rate_jacobian(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1,
                          const AccelerationJacobian& J, const std::vector<int>& terms,
                          MatrixXd& rows);

struct Recorder {
  const Model& m;
  Trajectory& r;
  ForwardData& d;
  int k = 0;
  // a run of output times below o.singular_warning, reported once at its smallest pivot ratio
  bool near = false;
  double near_min = 1, near_t = 0, near_first = 0, near_last = 0;
  std::string near_what{};
  bool drift_reported = false;
  // energies: the kEnergyTerms integrated terms at t
  void record(double t, const VectorXd& q0, const VectorXd& q1, const double* energies);
  void finish();  // after the last output time: reports what is still open
 private:
  void flush_near();
  void check_unprojected();
  void check_drift(double t, const VectorXd& q0);
};

// Throws Error naming the first non-finite value of recorded sample k and its time (forward.cpp).
void check_finite_sample(const Model& m, const Trajectory& r, int k);
// A warning in r.stats if the run's energy balance is off by more than 1 % of its energy scale.
void check_energy_balance(const Model& m, Trajectory& r);
// forward_dynamics without the check of the energy balance and the error estimate: a leg of the
// span switching, whose run checks the balance of all its legs together, and the second run of
// the estimate. chosen: where given, the options that ran (the method chosen for an accuracy).
Trajectory forward_run(const Model& m, const State& initial, const ForwardOptions& options,
                       ForwardOptions* chosen = nullptr);
// The a-posteriori estimate of r's global error (ForwardOptions::error_estimate;
// error_estimate.cpp) into r.stats, with a warning where it exceeds the accuracy asked for: `asked`
// the options of the run, `ran` the options that ran (forward_run's `chosen`).
void estimate_global_error(const Model& m, const State& initial, const ForwardOptions& asked,
                           const ForwardOptions& ran, Trajectory& r);
// The run of a second, tighter, setting (the estimate's reference), from the same initial state
// on the same output times: forward_run, or a run with contacts (contact_estimate.cpp).
using SecondRun = std::function<Trajectory(const ForwardOptions&)>;
// The same, with the second run made by second_run; true when the second run ran and r.stats
// holds the estimate.
bool estimate_global_error(const Model& m, const ForwardOptions& asked, const ForwardOptions& ran,
                           Trajectory& r, const SecondRun& second_run);
// forward_run of o with the checks of a whole run: its energy balance and, against the accuracy
// `asked` for, its error estimate (forward_dynamics, and each retry of meet_accuracy).
Trajectory checked_run(const Model& m, const State& initial, const ForwardOptions& asked,
                       const ForwardOptions& o);
// r, or a rerun at a tighter accuracy where r's estimated error exceeds the accuracy asked for
// (meet_accuracy.cpp: at most three retries, within the wall-time budget).
Trajectory meet_accuracy(const Model& m, const State& initial, const ForwardOptions& asked,
                         Trajectory r);

// Integrator drivers: integrate from s0 to o.t1, recording every output time.
void run_explicit_rk(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
                     Recorder& rec);
void run_cvode(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
               Recorder& rec);

// Inextensible chains (chain_switching.cpp): whether m has one whose spans forward_dynamics
// switches (not a model of one mode), and that run: segments of one span mode each, located by
// the stop condition, the switches and impacts reported in the run's warnings.
bool switches_chains(const Model& m);
Trajectory forward_chain_switching(const Model& m, const State& initial, const ForwardOptions& o);

// The budget of a forward run (max_steps, max_seconds, progress monitor) with the hint its
// error gives besides the budget (integrator, tolerances, step), and the cause of a collapse of
// the step size named from d (collapse_cause).
// terms: the EnergyTerms carried in the state after (q0, q1), in order.
detail::RunBudget::Settings forward_budget(const Model& m, ForwardData& d, const ForwardOptions& o,
                                           std::string hint, std::vector<int> terms);

// Why the step size collapsed at (t, y = (q0, q1, the energy terms `terms`)) (collapse_cause.cpp):
// a blow-up (kinetic energy beyond 1e6 x the mechanism's energy scale, naming the fastest
// quasi-velocity: driven by a law when the loads' and inputs' work supplied it, else an
// instability of the integrator on a stiff element), a singular position (the constraint
// Jacobian's pivot ratio below 1e-2, naming the dependent rows), or a stiff or non-smooth law;
// each with what helps. "" if y is null.
std::string collapse_cause(ForwardData& d, double t, const double* y,
                           const std::vector<int>& terms);

}  // namespace mo2d::detail
