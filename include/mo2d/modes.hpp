#pragma once
// Static equilibria, linearization and vibration modes (Orsino §4.5; docs/linearization.md).
//
// Independent coordinates. At a reference state (t, q0*, q1*) the state x = (z, w) holds
//   z = E0 q0   p coordinates of q0 chosen so that K0 = [Psi; E0] is regular (p = n0 - rank Psi),
//   w = E q1    dof quasi-velocities: the rates of those p coordinates first (so dz/dt = w.head(p)
//               exactly), then dof - p more where the velocity constraints leave rates with no
//               coordinate (one-node bodies' rotations, rolling), so that K = [A; E] is regular.
// E0 and E select labels (rows of the identity), chosen by column-pivoted QR on the tangent
// spaces (dimensionless columns, mo2d/kinematics.hpp) or given by the user. The map back is the
// chart q0(z): psi(q0) = 0 with E0 q0 = z (assemble), q1(z, w): [A(q0); E] q1 = [b; w]. Its
// tangent bases dq0/dz = K0^-1 [0; I] and dq1/dw = K^-1 [0; I] vary continuously with the state
// (the requirement of Proposition 4.4 on the orthogonal complement C): a raw SVD null space would
// not, and differences of it would be meaningless.
//
// Linearization: dx/dt = (w.head(p), E a1(t, q0(z), q1(z, w), u)), so, about x*,
//   G = [ 0   [I 0]                                       ]     H = [ 0        ]
//       [ E (da/dq0 dq0/dz + da/dq1 dq1/dz)  E da/dq1 dq1/dw ]         [ E da/du  ]
// with da/dq0, da/dq1 from acceleration_jacobian (mo2d/jacobian.hpp) and da/du = M-solve of B
// (ForwardData::B; the accelerations are affine in u). dq1/dz = K^-1 [db/dq0 - dA/dq0 q1; 0] dq0/dz
// vanishes at rest for scleronomic constraints. Outputs y = C x + D u for chosen labels.
#include <Eigen/Core>
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/model.hpp"

namespace mo2d {

// The settings of linearize() and linearize_along(): the independent coordinates, the outputs and
// the forward-dynamics settings whose accelerations are linearized (Orsino 2016 Proposition 4.4).
struct LinearizeOptions {
  // Independent coordinates (q0 labels, p of them) and the further independent quasi-velocities
  // (q1 labels, dof - p); empty: chosen by pivoting. Given: checked (Error naming them).
  std::vector<std::string> coordinates{};
  std::vector<std::string> velocities{};
  // Outputs y: coordinate labels, quasi-velocity labels, or derived quantities (Model::quantities:
  // body angles, joint angles and rates, spring lengths, named points "tip.x" ...).
  std::vector<std::string> outputs{};
  // Efforts (one law per input; feedback laws make G the closed loop), formulation, penalty.
  ForwardOptions forward{};
  // linearize_along: the smallest StateSpace::conditioning accepted along the reference (below
  // it the fixed coordinates stop parametrizing the motion well: an Error naming the time).
  double min_conditioning = 1e-3;
};

// The linear model dx/dt = G x + H u, y = C x + D u about a reference, with its labels.
struct StateSpace {
  // time of the reference (s)
  double t = 0;
  Eigen::VectorXd q0, q1, u;  // the reference state and efforts (u: the laws' values there)
  int p = 0, dof = 0;         // position and velocity coordinates: x = (z, w), n = p + dof
  std::vector<int> coordinate_vars, velocity_vars;  // z_i = q0[coordinate_vars[i]], w likewise
  std::vector<std::string> states;                  // p coordinate labels, then dof rate labels
  // labels of the inputs u (Model::inputs) and of the outputs y (LinearizeOptions::outputs)
  std::vector<std::string> inputs, outputs;
  Eigen::MatrixXd G, H, C, D;  // n x n, n x nu, ny x n, ny x nu
  Eigen::VectorXd drift;       // n: dx/dt at the reference (0 at an equilibrium)
  Eigen::MatrixXd dq0_dz;      // n0 x p: tangent basis of the positions (the chart's derivative)
  Eigen::MatrixXd dq1_dw;      // n1 x dof: basis of the velocities (C of Theorem 2.8)
  Eigen::MatrixXd dq1_dz;      // n1 x p: the velocities' change with the position at fixed w
  std::string approximate;     // what was differenced (acceleration_jacobian's note and ours)
  // How well the selected coordinates and quasi-velocities parametrize the state here: the
  // smaller of the smallest singular values of the selected rows of orthonormal bases of the two
  // tangent spaces (dimensionless columns): 1 ideal, 0 where the chart is singular.
  double conditioning = 1;
  // The number of states n = p + dof.
  int n() const { return p + dof; }
};

// Linearization about (reference.t, reference.q0, reference.q1); the state must be consistent
// (psi = 0, A q1 = b). Throws Error for a singular configuration, bad labels, non-finite values.
StateSpace linearize(const Model& m, const State& reference, const LinearizeOptions& o = {});

// The configuration q0(z) of the chart of ss: positions assembled with the independent
// coordinates at ss's values plus dz (Error if there is none, naming the coordinates).
Eigen::VectorXd chart_positions(const Model& m, const StateSpace& ss, const Eigen::VectorXd& dz);

// The consistent state of ss's chart at x* + dx (dx: n = p + dof): positions q0(z* + dz), then
// velocities from [A(q0); E] q1 = [b; w* + dw]. Error if there is none (naming the coordinates).
State chart_state(const Model& m, const StateSpace& ss, const Eigen::VectorXd& dx);
// The independent state x = (E0 q0, E q1) of a state s in ss's coordinates.
Eigen::VectorXd independent_state(const StateSpace& ss, const State& s);

// Linearization along a reference motion (Proposition 4.4 about a reference trajectory): one
// StateSpace per state, all in the SAME independent coordinates (o's, or, among the choices of
// the pivoting at each state, the one whose worst conditioning over the reference is the best;
// the further quasi-velocities by pivoting at the first state), so that dx/dt = G(t) x + H(t) u can
// be integrated along it (the transition matrix: dPhi/dt = G(t) Phi). Coordinates are never
// switched on the way: where they stop parametrizing the motion (conditioning below
// o.min_conditioning, or K0 = [Psi; E0], K = [A; E] singular) it throws Error naming the time, the
// coordinates and better ones there.
std::vector<StateSpace> linearize_along(const Model& m, const std::vector<State>& reference,
                                        const LinearizeOptions& o = {});
// Along a run's samples: a forward run with o.forward.efforts the laws it ran with (checked: the
// efforts and accelerations at each sample must be the run's, else Error), an inverse run with
// its efforts held at their sampled values.
std::vector<StateSpace> linearize_along(const Model& m, const Trajectory& reference,
                                        const LinearizeOptions& o = {});

// The settings of static_equilibrium().
struct EquilibriumOptions {
  double t = 0;              // time of the loads and laws
  double tolerance = 1e-10;  // on |E a1|, relative to |g| (or to the start's, without gravity)
  int max_iterations = 50;   // Newton iterations
  double max_step = 0.25;    // largest step, as a fraction of Model::scale (dimensionless)
  // the coordinates and the forward settings of the linearization at the equilibrium
  LinearizeOptions linearize{};
};

// The result of static_equilibrium(): the state at rest, its convergence, the linearization there
// and the reduced stiffness and mass.
struct Equilibrium {
  State state;          // q1 = 0
  int iterations = 0;   // Newton iterations
  double residual = 0;  // |E a1| at the end (m/s^2, rad/s^2 mixed)
  double moved = 0;     // largest coordinate change from the start
  StateSpace linear;    // the linearization there
  // Reduced stiffness Kr = -Mr G21 (p x p, with p == dof), Mr = dq1/dw^T M dq1/dw: the Hessian of
  // the potential in the coordinates z for conservative loads (symmetric then).
  Eigen::MatrixXd stiffness, reduced_mass;
  Eigen::VectorXd stiffness_eigenvalues;  // of (Kr + Kr^T) / 2, ascending
  double asymmetry = 0;                   // |Kr - Kr^T| / |Kr| (follower loads, feedback)
  std::string stability;                  // "stable", "unstable", "neutral"
};

// Newton on E a1(q0(z), 0) = 0 (the reduced equations at rest) from the configuration q0_guess
// (assembled first), with a backtracking line search on |a1| and steps bounded by max_step (the
// coordinates z chosen again at every iterate unless given): the equilibrium of the branch
// nearest the start. Throws Error (the residual, the iterations)
// where it does not converge, e.g. a mechanism without equilibrium (the ring and disc).
Equilibrium static_equilibrium(const Model& m, const Eigen::VectorXd& q0_guess,
                               const EquilibriumOptions& o = {});

// The efforts (one per input) that hold the configuration q0 at rest at time t: the least-squares
// solution of C^T (f + B u) = 0 (C = dq1/dw); `residual` is |C^T (f + B u)| left (N, N m). Throws
// Error when the inputs cannot hold the pose (the residual above 1e-9 of |C^T f|). Friction is not
// counted (static friction is indeterminate).
Eigen::VectorXd holding_efforts(const Model& m, const Eigen::VectorXd& q0, double t = 0,
                                double* residual = nullptr);

// One eigenvalue of G (for a complex pair, the one with positive imaginary part).
struct Mode {
  // lambda (1/s)
  std::complex<double> eigenvalue;
  double omega_n = 0;        // |lambda| (rad/s)
  double omega_d = 0;        // |Im lambda| (rad/s)
  double hz = 0;             // omega_n / (2 pi): the natural frequency in Hz
  double damping_ratio = 1;  // -Re lambda / |lambda| (1 for a real negative, -1 real positive)
  bool oscillatory = false;  // Im lambda != 0
  bool rigid = false;        // |lambda| ~ 0: a rigid-body or drift motion
  Eigen::VectorXcd x;        // eigenvector in the states (n)
  Eigen::VectorXd dz;        // real position shape (p), phase-aligned, max |component| = 1
  Eigen::VectorXd dq0;       // dq0/dz dz: every coordinate of q0 (every node) for that shape
};
// The budgets of vibration_modes: the eigenvectors of G are dense (n x n, time as n^3), so a G
// whose eigenproblem needs more than max_memory bytes, or more than max_seconds at a fast
// machine's rate, is refused before the work starts (Error "max_memory", BudgetExhausted).
struct ModesOptions {
  double max_seconds = kDefaultMaxSeconds;  // wall-clock budget (s)
  double max_memory = kDefaultMaxMemory;    // bytes the dense eigenproblem may allocate
};
// The modes of ss, oscillatory ones by ascending omega_n first, then the real ones.
std::vector<Mode> vibration_modes(const StateSpace& ss, const ModesOptions& o = {});
// Node displacements of a mode scaled so that the largest node moves by `amplitude` (m): (label
// "body.node", dx, dy) for every node of every body (ground excluded).
struct NodeShape {
  // "body.node"
  std::string label;
  // displacement of the node (m)
  double dx = 0, dy = 0;
};
// The NodeShape of every node of every body for `mode`, scaled so that the largest moves by
// `amplitude` (m).
std::vector<NodeShape> mode_node_shapes(const Model& m, const Mode& mode, double amplitude);
// dz of a mode scaled so that the largest node displacement is `amplitude` (m).
Eigen::VectorXd mode_step(const Model& m, const Mode& mode, double amplitude);

// Export: one matrix ('G', 'H', 'C' or 'D') as CSV, a header "<name>,<column labels...>" then one
// row per row label; and JSON {states, inputs, outputs, G, H, C, D, reference, drift, modes}.
// Numbers with 17 significant digits; non-finite entries are refused (Error naming the entry).
std::string state_space_csv(const StateSpace& ss, char matrix);
std::string state_space_json(const StateSpace& ss, const std::vector<Mode>& modes);
// Along a reference (linearize_along): CSV, one row per time and row label, "t,<matrix>,<column
// labels...>"; JSON {states, inputs, outputs, samples: [{t, conditioning, reference, G, H, C, D,
// drift, modes}]}. The labels must be the same at every sample (Error otherwise).
std::string state_space_along_csv(const std::vector<StateSpace>& along, char matrix);
std::string state_space_along_json(const std::vector<StateSpace>& along);

}  // namespace mo2d
