#pragma once
// Forward dynamics: integrate the motion of a Model under loads and input efforts.
//
// The state is (q0, q1). The accelerations a1 = d/dt q1 solve, at each evaluation,
//   M a1 = f + B u - A^T lambda,   A a1 = c        (index-1 form of eq. 4.1 with multipliers)
// in one of three formulations:
//  - augmented Lagrangian (default): (M + alpha A^T A) a = f + B u - A^T lambda* + alpha A^T c,
//    lambda* += alpha (A a - c), a few iterations; the matrix stays positive definite when A
//    loses rank, so the run goes through singular configurations;
//  - Lagrange: the square system [M A^T; A 0] (fails where A loses rank);
//  - null space: C^T M a = C^T (f + B u), A a = c with C = K^-1 [0; I], K = [A; E] and E the
//    independent quasi-velocities chosen by pivoting (re-chosen when K gets ill-conditioned).
// After each step the state is projected back on psi(q0) = 0 and A q1 = b (minimum-norm
// Gauss-Newton, regularized), so constraint drift stays at the solver tolerance.
// The workspace of these evaluations, and forward_accelerations (one evaluation at a given state):
// mo2d/forward_data.hpp.
#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/budget.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// The integrator of forward dynamics (docs/performance.md compares them).
enum class Integrator {
  cvode_bdf,    // SUNDIALS CVODE, BDF (orders 1-5), Newton + dense LU, projection each step
  cvode_adams,  // SUNDIALS CVODE, Adams-Moulton (orders 1-12), fixed-point iteration, no projection
                // (CVODE projects only BDF): stops at a near-singular configuration
  rk4,          // classical Runge-Kutta, fixed step, projection each step
  dopri5,       // Dormand-Prince 5(4), adaptive step (rtol, atol), projection each step
  erk6,  // Verner 6(5), 8 stages (SUNDIALS ARKODE's table), adaptive step, projection each step
  erk8,  // Fehlberg 8(7), 13 stages (SUNDIALS ARKODE's table), adaptive step, projection each step
  baumgarte,  // Mo2DPack-compatible: RK4, velocity constraints stabilized by Baumgarte, no
              // projection
};
// How the accelerations a1 and multipliers lambda of [M A^T; A 0][a1; lambda] = [f + B u; c]
// are solved: the augmented-Lagrangian iteration (Bayo and Garcia de Jalon; H = M + alpha A^T A,
// src/forward/alf_iterate.hpp), the KKT system itself (lagrange), or the null space
// (K = [A; E] with E selecting dof independent variables, Orsino 2016 Theorem 2.8's C).
enum class Formulation { augmented_lagrangian, lagrange, null_space };
// The matrices of the accelerations, the projection and the reactions (docs/performance.md,
// "Sparse engine"): dense (Schur complement with the constant M^-1, dense Cholesky and LU: the
// fastest for small mechanisms), or sparse (constraint rows, mass matrix and the
// augmented-Lagrangian matrix M + alpha A^T N^2 A as sparse matrices whose pattern is analysed
// once, refactorized per evaluation: cost linear in the size of a chain). automatic: sparse where
// it is available (the augmented Lagrangian with rk4, dopri5 or baumgarte) and the mechanism has
// n1 + m1 >= kSparseCrossover variables and velocity rows, else dense.
enum class LinearAlgebra { automatic, dense, sparse };
// n1 + m1 (variables and velocity rows) from which LinearAlgebra::automatic uses sparse matrices.
inline constexpr int kSparseCrossover = 40;

// The option's name as written in scenes and on the command line ("cvode_bdf", ...).
const char* to_string(Integrator i);
const char* to_string(Formulation f);
const char* to_string(LinearAlgebra a);

// Whether forward_dynamics estimates the run's global error a posteriori (RunStats::
// estimated_error; src/forward/error_estimate.cpp): automatic = when an accuracy is asked for
// (ForwardOptions::accuracy > 0), on = always, off = never. The estimate is a second run of the
// same method at tighter settings (tolerances / 16, a fixed step halved) on the same output
// times; it costs 0.9 to 1.3 times the run's CPU (erk8 on the shipped scenes), about 2 times for
// rk4, on top of the run (docs/performance.md, "Issue 30").
enum class ErrorEstimate { automatic, on, off };
const char* to_string(ErrorEstimate e);

// A consistent state (positions on psi = 0, velocities on A q1 = b).
struct State {
  // time (s)
  double t = 0;
  // positions q0 (m, or rad for angle coordinates) and quasi-velocities q1 (m/s, rad/s), in Model
  // order
  VectorXd q0, q1;
};

// Initial state from the model's (approximate) configuration: coordinates listed in `positions`
// are held at the given values while the others are assembled (Newton, nearest branch); the
// quasi-velocities listed in `velocities` are imposed and the others solved from A q1 = b.
// Exactly dof velocities must be given and they must be independent. Throws Error otherwise.
struct InitialConditions {
  std::vector<std::pair<std::string, double>> positions;   // coordinate label -> value
  std::vector<std::pair<std::string, double>> velocities;  // quasi-velocity label -> value
};
// The State at t0 (s) for the initial conditions `ic` of model `m` (see InitialConditions).
State consistent_state(const Model& m, const InitialConditions& ic, double t0 = 0);

// One effort law per input; assignable from time functions (what efforts_from_inverse returns).
struct EffortLaws : std::vector<Law> {
  using std::vector<Law>::vector;
  EffortLaws() = default;
  // One time law per input (efforts in N m or N against t in s).
  EffortLaws(const std::vector<std::function<double(double)>>& fns)  // NOLINT: implicit on purpose
      : std::vector<Law>(fns.begin(), fns.end()) {}
};

// The settings of forward_dynamics(): time span, output samples, integrator and tolerances,
// budgets, input efforts, checks and monitors.
struct ForwardOptions {
  // start and end time of the run (s)
  double t0 = 0, t1 = 1;
  int samples = 101;  // output times, equally spaced in [t0, t1] (dense output)
  // the integrator (ignored when accuracy > 0)
  Integrator integrator = Integrator::cvode_bdf;
  // the equations of the accelerations
  Formulation formulation = Formulation::augmented_lagrangian;
  double rtol = 1e-8, atol = 1e-10;  // CVODE and dopri5 tolerances (atol in SI units)
  double step = 1e-3;  // fixed step (rk4, baumgarte); shortened so that steps end on output times
  // > 0: the accuracy asked for, the error of the positions relative to the mechanism's size
  // (Model::scale) that the run should reach; forward_dynamics then picks the integrator and its
  // tolerances (options_for_accuracy) and integrator, rtol, atol and step are not used. 0: the
  // integrator and tolerances above. In [kMinAccuracy, kMaxAccuracy].
  double accuracy = 0;
  // the a-posteriori estimate of the global error (ErrorEstimate above); where it exceeds
  // `accuracy`, the run warns with the estimate, its time and its coordinate
  ErrorEstimate error_estimate = ErrorEstimate::automatic;
  double baumgarte_alpha = 20.0;  // 1/s, velocity-constraint feedback of the baumgarte mode
  double penalty = 0;             // augmented Lagrangian alpha (0: chosen from the mass scale)
  LinearAlgebra linear_algebra = LinearAlgebra::automatic;  // dense or sparse matrices (above)
  // cvode_bdf's Newton matrix from the exact derivatives of the accelerations (mo2d/jacobian.hpp);
  // false: CVODE's difference quotients of the right-hand side (for comparison)
  bool exact_jacobian = true;
  // Budgets (mo2d/budget.hpp): accepted steps over the whole run (all integrators; a fixed-step
  // run needing more is refused before it starts) and wall-clock seconds (<= 0 or inf: none).
  // When one runs out, forward_dynamics throws an Error naming the time reached and the steps.
  int max_steps = kDefaultMaxSteps;
  double max_seconds = kDefaultMaxSeconds;
  // Dense-matrix and result memory the run may allocate (bytes, estimated before allocating).
  double max_memory = kDefaultMaxMemory;
  // Input efforts, one law per Model::inputs entry (missing or empty = zero): a function of time
  // (open loop), or of time and the state (mo2d/law.hpp: a feedback law, e.g. pd_control).
  EffortLaws efforts{};
  // Generalized forces of a stage above forward dynamics (contact, mo2d/contact.hpp) at every
  // evaluation: the function adds its forces (n1, N or N m per quasi-velocity) to `f` and returns
  // the part of their power that they dissipate (W, >= 0). Their power f . q1 plus that part is
  // counted in work.loads and that part in energy.dissipated, so the energy balance covers them.
  // It must not allocate (it runs per evaluation). cvode_bdf takes CVODE's difference quotients
  // for its Newton matrix when it is set (the exact Jacobian does not know these forces).
  std::function<double(double t, const VectorXd& q0, const VectorXd& q1, VectorXd& f)>
      extra_forces{};
  // Stop early when this function of the state changes sign (root finding between steps).
  std::function<double(double t, const VectorXd& q0, const VectorXd& q1)> stop_when{};
  // Warn where (sigma_min / sigma_max)^2 of the dimensionless constraint Jacobian (columns scaled
  // by column_scaling, unit rows; mo2d/kinematics.hpp) is below this
  // at output times: 1e-4 is sigma ratio 1e-2, about 2 ms from a singular instant of the double
  // four-bar. One warning per run of such output times, at the smallest ratio, naming the
  // constraints that become dependent and the motion they leave undetermined. Independent of
  // units and of the mechanism's size.
  double singular_warning = 1e-4;
  // Largest position-constraint drift at an output time, relative to the mechanism's size (each
  // row in dimensionless form): beyond it the run stops with an error naming the time and the
  // worst row (the state has left the constraint manifold, and may have left its branch); for
  // cvode_adams and baumgarte, which do not project, a warning (their drift follows the
  // tolerance or step).
  double drift_tolerance = 1e-6;
  // Called at every output time with that time (e.g. a progress bar); not part of the dynamics.
  std::function<void(double t)> progress{};
  // Called about every monitor_interval seconds of wall time from inside the integration (also
  // between output times): time reached, steps, step size, whether the step size collapsed.
  std::function<void(const RunProgress&)> monitor{};
  // wall-clock seconds between calls of monitor
  double monitor_interval = 1.0;
};

// The bounds of ForwardOptions::accuracy (src/forward/accuracy.cpp: the range calibrated; below
// it, the regularized accelerations next to singular configurations and round-off limit what the
// integrators reach).
// smallest and largest value of ForwardOptions::accuracy (relative position error)
extern const double kMinAccuracy, kMaxAccuracy;

// o with the integrator and tolerances chosen for o.accuracy on m (unchanged if o.accuracy is 0,
// Error "accuracy" if it is out of its bounds): the
// cheapest setting that reached the accuracy on the calibration scenes (docs/performance.md,
// "Accuracy asked for"). A calibration, not a guarantee: the error of a run grows with its
// duration and with the mechanism's sensitivity, so check a critical run with a tighter accuracy.
ForwardOptions options_for_accuracy(const Model& m, ForwardOptions o);

// The accuracy a scene's forward run asks for when it names no method (no run.integrator, rtol,
// atol, step or accuracy; `mo2d forward` without those flags): docs/scene-format.md.
inline constexpr double kDefaultAccuracy = 1e-6;

// The method forward_dynamics runs for o.accuracy > 0 from the state s, and why
// (src/forward/method_choice.cpp). Stiffness test: |lambda|max, the spectral radius of the
// Jacobian of the right-hand side d(q0, q1)/dt at s (power iteration on finite differences of
// the accelerations, a few dozen evaluations), against the step erk8 (rtol = accuracy / 1000)
// needs for the accuracy at every accuracy (issue 30): an explicit method is stable for steps
// h <= kStabilityBound / |lambda|max, so over T = t1 - t0 it needs |lambda|max T / kStabilityBound
// steps for stability and T / h_accuracy for the accuracy. When the first exceeds
// kStiffRatio times the second (the explicit method would crawl at its stability limit, or rk4's
// fixed step would diverge), the mechanism is stiff there and cvode_bdf runs with
// rtol = atol = accuracy / 1000; otherwise the explicit method of options_for_accuracy, except
// that below 1e-8 a mechanism faster than rk4's calibration (|lambda|max > 4 /s) runs erk8.
struct MethodChoice {
  ForwardOptions options{};      // o with the integrator and tolerances chosen
  double spectral_radius = NAN;  // |lambda|max at s (1/s); NaN: not estimated
  double stability_steps = 0;    // |lambda|max T / kStabilityBound
  double accuracy_steps = 0;     // T / h_accuracy of the explicit method
  bool stiff = false;            // stability_steps > kStiffRatio accuracy_steps: cvode_bdf chosen
  std::string reason{};          // "accuracy 1e-06, not stiff (|lambda|max T = 31 ...): dopri5 ..."
};
// The stability limit |lambda|max h of the explicit methods (about 2.5 to 3.3 on the real axis
// for rk4, dopri5 and the higher orders: the smallest, rounded down).
inline constexpr double kStabilityBound = 2.5;
// How many times more steps than the accuracy needs make a mechanism stiff.
inline constexpr double kStiffRatio = 4;
// The method for o.accuracy at the state s, with its reason (above); o unchanged when
// o.accuracy is 0 (the integrator named).
MethodChoice choose_method(const Model& m, const State& s, const ForwardOptions& o);

// Throws Error (element: the option's name, "t0", "t1", "samples", "step", "max_steps", ...)
// when the options cannot give a correct run of m: a time grid double precision does not
// resolve, a fixed step needing more than max_steps steps, sizes above max_memory, non-positive
// tolerances or budgets. forward_dynamics calls it first.
void check_forward_options(const Model& m, const ForwardOptions& options);

// The run, recorded at every output time as a Trajectory (kind forward): the state, its rates,
// the efforts applied, the reactions (from least-squares multipliers, not unique where the
// constraint Jacobian loses rank), the residuals |psi|_inf and |A q1 - b|_inf, the energies, and
// the integrator's statistics (RunStats). Every recorded value is finite: the first non-finite one
// throws an Error naming the time and the variable (the integration diverged or a value
// overflowed).
Trajectory forward_dynamics(const Model& m, const State& initial, const ForwardOptions& options);

// Efforts replayed from inverse dynamics, one function per input: `exact` solves the inverse
// problem at the requested instant (no interpolation error; from the last instant asked, walking
// in steps of the options' sample spacing to an instant farther away, so that the positions stay
// on their assembly mode); `from_samples` interpolates a sampled result with cubic Hermite splines
// (slopes from centred differences), so its accuracy depends on the sampling.
std::vector<std::function<double(double)>> efforts_from_inverse(const Model& m,
                                                                std::vector<Prescribed> prescribed,
                                                                const InverseOptions& options = {});
// Efforts interpolated from the samples of an inverse-dynamics run `r` (cubic Hermite; see above),
// one function of t (s) per input, in N m or N.
std::vector<std::function<double(double)>> efforts_from_samples(const Trajectory& r);

// Energy balance of a run at every sample: K + V - (K + V)(t0) - W_inputs - W_loads
// - W_constraints + D (J). Every term is integrated along the run or evaluated from the state, so
// on a correct run it stays at the integration error; energy_balance_error is its max |.|.
// Throws Error for a trajectory without energies (an inverse run).
VectorXd energy_balance(const Trajectory& r);
double energy_balance_error(const Trajectory& r);

// Kinetic energy 1/2 q1^T M q1 (potential_energy and damping_power: mo2d/dynamics.hpp).
double kinetic_energy(const Model& m, const VectorXd& q1);

}  // namespace mo2d
