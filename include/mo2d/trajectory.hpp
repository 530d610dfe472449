#pragma once
// Trajectory: the result of a run, inverse (inverse_dynamics, inverse_dynamics_lagrange) or forward
// (forward_dynamics), one row per sample. Both runs fill the same columns (time, coordinates,
// quasi-velocities and their derivatives, efforts, joint reactions, constraint residuals) and are
// read with the same lookups; a forward run adds the energies and the integrator's statistics.
// write_csv (mo2d/csv.hpp) writes one as a CSV whose header is the labels of its columns.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace mo2d {

// The kind of a run: inverse or forward dynamics.
enum class RunKind { inverse, forward };
// "inverse" or "forward".
const char* to_string(RunKind k);

// Statistics of a run. cpu_seconds and warnings for both kinds; the rest for forward runs only
// (zero, or their initial values, for an inverse run).
struct RunStats {
  // CPU time of the run (s)
  double cpu_seconds = 0;
  // Singular configurations passed or approached, jumps between assembly modes (inverse), drift
  // of an integrator that does not project (forward): each with the time and the variables.
  std::vector<std::string> warnings;
  // forward runs: the integrator's counters
  long steps = 0, rhs_evaluations = 0, factorizations = 0, projections = 0, error_test_failures = 0;
  long solver_iterations = 0;        // augmented Lagrangian iterations, summed over evaluations
  long regularized_evaluations = 0;  // evaluations near a singular configuration (regularized)
  long stepped_over = 0;             // steps redone to avoid evaluating inside a singular instant
  bool stopped_by_event = false;     // ForwardOptions::stop_when changed sign
  double t_end = 0;                  // time reached
  double min_pivot_ratio = 1;        // smallest (sigma_min / sigma_max)^2 of A seen at output times
  double max_drift = 0;              // largest position drift at output times (see drift_tolerance)
  bool sparse = false;               // forward runs: the sparse linear algebra was used
  // forward runs: the integrator that ran, and when it was chosen for an accuracy
  // (ForwardOptions::accuracy, choose_method) the choice and its reason
  std::string integrator{}, method{};
  // forward runs: the a-posteriori estimate of the global error (ForwardOptions::error_estimate,
  // src/forward/error_estimate.cpp): the largest difference of a position coordinate at the
  // output times from a second run at tighter settings, relative to the mechanism's size
  // (Model::scale; a rotation as the arc of its body's size: the measure of
  // ForwardOptions::accuracy), with its time (s) and coordinate; NaN: not estimated.
  double estimated_error = std::numeric_limits<double>::quiet_NaN();
  double estimated_error_t = 0;
  std::string estimated_error_variable{};
  // how the estimate was made (the second run's settings) or why there is none
  std::string error_estimate{};
  double estimate_cpu_seconds = 0;  // CPU time of the second run (s; not in cpu_seconds)
};

// The result of a run (inverse_dynamics or forward_dynamics), one row per sample: the state,
// efforts, reactions, residuals, energies, requested outputs and statistics. Units SI (m, rad, s,
// N, N m, J).
struct Trajectory {
  // inverse or forward dynamics
  RunKind kind = RunKind::inverse;
  // Column labels: Model::coordinate_labels (q0), Model::rate_labels (q1, a1; a1's are written
  // label + ".dot"), Model::input_labels() (efforts), Model::reaction_labels() (reactions), and
  // residual_labels: "residual.position", "residual.velocity" (+ "residual.acceleration" for an
  // inverse run).
  std::vector<std::string> coordinate_labels, rate_labels, input_labels, reaction_labels,
      residual_labels;
  Eigen::VectorXd time;        // samples
  Eigen::MatrixXd q0, q1, a1;  // samples x n0 / n1 / n1: coordinates, quasi-velocities, their rates
  Eigen::MatrixXd efforts;     // samples x inputs: the efforts found (inverse) or applied (forward)
  // samples x reactions (Model::reactions). Forward runs: from least-squares multipliers (not
  // unique where the constraint Jacobian loses rank).
  Eigen::MatrixXd reactions;
  Eigen::MatrixXd residuals;  // samples x residual_labels: inf norms of psi, A q1 - b[, A a1 - c]

  // Energies (J), forward runs only (size 0 for an inverse run): kinetic, potential (gravity with
  // datum y = 0, springs), and the terms integrated along the run from t0: the work of the inputs
  // (B u . q1), of the applied forces and torques, of time-dependent constraints, and the energy
  // dissipated by the dampers (>= 0). energy_balance (mo2d/forward.hpp) combines them.
  Eigen::VectorXd kinetic, potential, input_work, load_work, constraint_work, dissipated;
  // Whether the energies are recorded (forward runs).
  bool has_energies() const { return kind == RunKind::forward; }

  // Columns added on request after the run (add_output_columns, mo2d/output_columns.hpp): loads'
  // values and powers, named points, centres of mass. None unless asked for.
  std::vector<std::string> output_labels;
  Eigen::MatrixXd outputs;  // samples x output_labels

  // statistics of the run
  RunStats stats;

  // Column of a label in q0 (coordinate), q1 and a1 (quasi-velocity), efforts (input, e.g.
  // "crank.torque") and reactions ("elbow.Fx"). Throws Error naming the label (with the closest
  // one) if it is not a column.
  int column(const std::string& coordinate_label) const;
  int rate_column(const std::string& rate_label) const;
  int effort(const std::string& input_label) const;
  int reaction(const std::string& reaction_label) const;
  int output(const std::string& output_label) const;  // column of outputs ("gas.power")
};

}  // namespace mo2d
