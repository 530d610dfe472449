#pragma once
// Inverse dynamics (Orsino §4.4, Theorem 4.3): prescribe as many coordinates as the mechanism has
// degrees of freedom; at each sample solve positions exactly (Newton), then velocities and
// accelerations ([A; E] q1 = [b; s_dot], [A; E] a1 = [c; s_ddot]), then the efforts u from
// C^T (M a1 - f - B u) = 0 with C = K^-1 [0; I] the orthogonal complement whose independent
// variables are the prescribed coordinates (eq. 2.29), and the constraint multipliers / joint
// reactions.
#include <Eigen/Core>
#include <Eigen/LU>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mo2d/budget.hpp"
#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

namespace detail {
class PatternLU;   // fixed-pattern LU of the small systems of one sample (linalg/pattern_lu.hpp)
struct SlotEntry;  // an entry of A owned by a body slot, for the reactions (src/dynamics/)
}  // namespace detail

using Eigen::MatrixXd;
using Eigen::VectorXd;

// A prescribed coordinate: s(t) evaluated on Jet(t, 1, 0) gives s, s_dot, s_ddot exactly.
struct Prescribed {
  std::string coordinate;  // coordinate label, e.g. "crank.angle", "slider.P.x", "slide.q"
  // s(t): the coordinate's value (m or rad) as a function of time, evaluated on Jets
  std::function<Jet(Jet t)> motion;
};

// How the orthogonal complement C of the velocity rows A is formed for the efforts (Orsino 2016
// eq. 2.28-2.29 and Theorem 2.10; docs/equations.md, "Inverse dynamics").
enum class ComplementMethod {
  prescribed,  // C = K^-1 [0; I] from the factorization of K = [A; E] (default, fastest)
  recursive,   // S = R C built over the subsystem tree (Theorem 2.10)
};

// The settings of inverse_dynamics(): sample times, Newton's tolerance, singularity and branch
// tests, friction iteration and budgets.
struct InverseOptions {
  // first and last sample time (s)
  double t0 = 0, t1 = 1;
  // number of samples, equally spaced over [t0, t1]
  int samples = 501;
  double position_tolerance = 1e-12;  // |psi|_inf, relative to Model::scale
  // Newton iterations allowed per sample for the positions
  int max_newton_iterations = 30;
  // Singularity tests, on the dimensionless K = [N A D; E] (D: column_scaling of the model, N:
  // unit rows; mo2d/kinematics.hpp), so independent of units and size:
  double singular_pivot_ratio = 1e-10;  // min/max |pivot| of K below which a sample is singular
  // a run of samples whose pivot ratio dips below this is reported once, at its smallest value
  double near_singular_pivot_ratio = 1e-3;
  // the positions found at a sample differ from their prediction from the last sample's
  // velocities and accelerations by more than this fraction of the predicted motion: reported
  // (a switch of assembly mode, or a singular passage the samples do not resolve)
  double branch_jump = 0.5;
  ComplementMethod complement = ComplementMethod::prescribed;
  // Joint friction (FrictionDef): the fixed-point iteration of the friction and the reactions per
  // sample stops when no friction changes by more than this fraction of itself; a sample that
  // needs more than max_friction_iterations is an error naming the friction and the time.
  double friction_tolerance = 1e-12;
  int max_friction_iterations = 200;
  // Budgets (mo2d/budget.hpp): wall-clock seconds of the run (<= 0 or inf: none), the memory of
  // its dense matrices and results (bytes, estimated before allocating), a progress monitor
  // called about every monitor_interval seconds.
  double max_seconds = kDefaultMaxSeconds;
  double max_memory = kDefaultMaxMemory;
  // progress monitor (time reached, samples done), called about every monitor_interval seconds
  std::function<void(const RunProgress&)> monitor{};
  // wall-clock seconds between monitor calls
  double monitor_interval = 1.0;
};

// Throws Error (element: the option's name, "t0", "t1", "samples", "max_memory", ...) when the
// options cannot give a correct run of m: a time grid double precision does not resolve (t0 =
// 1e17 with samples 0.01 s apart), sizes above max_memory. InverseData's constructor calls it.
void check_inverse_options(const Model& m, const InverseOptions& options);

// Workspace of one inverse-dynamics run (Pinocchio's Data): everything the per-sample loop
// needs is allocated here once.
struct InverseData {
  // The workspace of model `m` (it must outlive it) for the prescribed motions `prescribed` (one
  // per degree of freedom); checks the options (check_inverse_options).
  InverseData(const Model& m, std::span<const Prescribed> prescribed, const InverseOptions& o = {});
  ~InverseData();
  InverseData(const InverseData&) = delete;
  InverseData& operator=(const InverseData&) = delete;

  // the options, copied
  InverseOptions options;
  std::vector<int> p_index;  // prescribed coordinate indices
  // the prescribed motions s(t) and their coordinate labels, in the order of p_index
  std::vector<std::function<Jet(Jet)>> p_motion;
  std::vector<std::string> p_labels;

  // results of the last sample (written by inverse_dynamics_sample)
  double t = 0;
  VectorXd q0, q1, a1;  // coordinates, quasi-velocities, quasi-accelerations
  VectorXd u;           // efforts, one per input (Model::inputs)
  VectorXd lambda;      // multipliers of the velocity rows (M a1 = f + B u - A^T lambda)
  VectorXd reactions;   // Model::reactions
  VectorXd friction;    // Model::frictions: their values (N, N m), consistent with the reactions
  int friction_iterations = 0;  // fixed-point iterations of the last sample (0: no friction)
  // residuals of the last sample: |psi|_inf, |A q1 - b|_inf, |A a1 - c|_inf (SI units of the rows)
  double residual_position = 0, residual_velocity = 0, residual_acceleration = 0;
  // Newton iterations of the positions at the last sample
  int newton_iterations = 0;
  double pivot_ratio = 0;  // min/max |pivot| of the LU of the dimensionless K (a cheap
                           // conditioning indicator)
  // Singular passages and branch jumps found so far (time, prescribed values, variables), in the
  // order found; inverse_dynamics() copies them to Trajectory::stats.warnings.
  std::vector<std::string> warnings;

  // workspace
  std::vector<int> colmap;  // coordinate -> free column (-1 prescribed)
  // scratch vectors and matrices of the per-sample solve (src/inverse/; not part of the results)
  VectorXd s, s_dot, s_ddot, psi, trial, q0_trial, b, c, rhs, w, f, local, local_a, z, Ctw;
  VectorXd row_residual;
  MatrixXd J, K, B, CtB;
  MatrixXd Ks;  // dimensionless K = diag(k_row) K diag(col_scale) (formed for the messages)
  VectorXd col_scale, k_row;    // column_scaling of the model; row scaling of K
  VectorXd pos_scale, q0_pred;  // its first n0 entries (dimensionless q0 / pos_scale); prediction
  // sign of det K at the last two samples (a change: a singular configuration passed)
  int det_sign = 0, det_sign_prev = 0;
  bool near_singular = false;  // inside a run of samples below near_singular_pivot_ratio
  // smallest pivot ratio in the current near-singular run, and its time (s)
  double near_min = 1, near_t = 0;
  std::string near_what;  // prescribed values and variables at the smallest pivot ratio
  MatrixXd S;  // orthogonal complement C (n1 x dof) used for the efforts of the last sample
  std::unique_ptr<detail::PatternLU> lu_pos, lu_K;  // positions (free coordinates), K = [A; E]
  // LU of the effort equations C^T B u = C^T (M a1 - f) (C^T f = 0 of Orsino 2016 eq. 4.1,
  // Theorem 4.3)
  Eigen::PartialPivLU<MatrixXd> lu_u;
  std::vector<double> edge_force;  // per merge edge: 2 (node) or 1 (rotation) values
  // first entry of each merge edge in edge_force
  std::vector<int> edge_offset;
  std::vector<detail::SlotEntry> entries;  // A entries attributed to body slots (reactions)
  VectorXd friction_next, local_base;      // friction iteration: next values; M a - f, local
  // the previous sample (time, positions, rates, accelerations), for the prediction of the next
  bool has_previous = false;
  double t_prev = 0;
  VectorXd q0_prev, q1_prev, a1_prev;
  VectorXd q0_good, s_good;  // last solved configuration and its prescribed values
};

// Solve one sample at time t (no heap allocation). Throws Error (with the time) at a singular
// configuration, when the positions cannot be solved, or when a result is not finite (naming the
// variable).
void inverse_dynamics_sample(const Model& m, InverseData& d, double t);
// After the last sample: reports a run of near-singular samples still open (inverse_dynamics
// calls it; needed only when calling inverse_dynamics_sample directly).
void finish_inverse_warnings(InverseData& d);

// Whole run: options.samples equally spaced samples in [t0, t1]. The Trajectory (kind inverse)
// holds every sample's solution and residuals (position, velocity, acceleration); stats: the CPU
// time and the singular configurations passed or approached, and the jumps between assembly modes,
// with the time and the variables (see InverseOptions).
Trajectory inverse_dynamics(const Model& m, std::span<const Prescribed> prescribed,
                            const InverseOptions& options);

// A second formulation, for validation: Lagrange multipliers on the unreduced model
// (Reduction::none: every joint is a constraint row). At each sample the kinematics are solved
// as in inverse_dynamics, then accelerations, multipliers and efforts together from
//   [ M  A^T  -B ] [a1    ]   [ f      ]
//   [ A  0     0 ] [lambda] = [ c      ]
//   [ E  0     0 ] [u     ]   [ s_ddot ]
// so M a1 = f + B u - A^T lambda. Reactions are read from lambda directly.
Trajectory inverse_dynamics_lagrange(const Model& m, std::span<const Prescribed> prescribed,
                                     const InverseOptions& options);

// Orthogonal complement S of A (n1 x dof, A S = 0) built recursively over the subsystem tree:
// S = R C, R = blockdiag(I, S_children), C = null(A_external R) (Theorem 2.10).
MatrixXd recursive_complement(const Model& m, const Eigen::Ref<const MatrixXd>& A);

}  // namespace mo2d
