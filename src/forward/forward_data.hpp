#pragma once
// Internal to the forward-dynamics implementation: the workspace of one run (accelerations,
// projection, reactions), the output recorder, and the integrator drivers (one file each).
#include <Eigen/Cholesky>
#include <cmath>
#include <string>
#include <vector>

#include "mo2d/detail/reactions.hpp"
#include "mo2d/detail/small_lu.hpp"
#include "mo2d/forward.hpp"
#include "run/run_budget.hpp"

namespace mo2d::detail {

std::string fmt(double v);  // 6 significant digits, for messages

// y = (J J^T + eps * max(1, max diag(J J^T)) I)^-1 J x: the least-squares multipliers of
// J^T y = x, regularized where J loses rank (eps relative to the largest diagonal entry).
VectorXd regularized_normal_solve(const MatrixXd& J, const VectorXd& x, double eps);

// Workspace of one forward run.
struct ForwardData {
  const Model& m;
  const ForwardOptions& o;
  MatrixXd M, M0, W0, B, A, Psi, H, KKT, K, S, CtMC;
  VectorXd b, c, f, Bu, u, lambda, rhs, a, psi, tmp0, tmp1, local, ap, red, dq0, dq1, r1;
  Eigen::LLT<MatrixXd> llt_H, llt_G0, llt_G1;
  detail::SmallLU lu_kkt, lu_K;
  std::vector<detail::SlotEntry> entries;  // reactions: A entries attributed to body slots
  std::vector<double> edge_force;
  std::vector<int> edge_offset;
  VectorXd reactions, la, w, lam_ls;
  Eigen::LLT<MatrixXd> llt_red;
  std::vector<int> independent;  // null space: independent quasi-velocities
  double alpha = 0;
  ForwardStats stats;
  double last_pivot = 1;
  double accel_residual = 0;  // relative residual of the last augmented-Lagrangian iteration
  bool accel_ok = true;       // the last accelerations are accurate (not regularized away)
  VectorXd kkt_x;
  MatrixXd An, G1, Minv, AMinv;
  // Dimensionless rows and columns (see column_scaling in mo2d/kinematics.hpp): col_scale d (n1)
  // and pos_scale (its first n0 entries) are fixed by the model; row_scale N (m1) makes the rows of
  // A diag(d) unit at each evaluation (row_scale_of). Every conditioning test, the penalty
  // (alpha N^2 in place of alpha) and the convergence tests are made on N A diag(d), so they do
  // not depend on units or on the size of the mechanism.
  VectorXd row_scale, col_scale, pos_scale, pos_row_scale;
  bool has_Minv = false;  // M positive definite: direct solves by the Schur complement
  Eigen::LLT<MatrixXd> llt_G;
  detail::SmallLU lu_G1;
  // The direct solve is used where row_conditioning() >= kDirectAccept (sigma ratio >= 0.1);
  // the augmented-Lagrangian result is accurate below the relative residual kAlfAccept.
  static constexpr double kDirectAccept = 1e-2, kKktAccept = 1e-14, kAlfAccept = 1e-8;

  ForwardData(const Model& model, const ForwardOptions& opt);

  void inputs(double t);

  double solve_kkt();
  double solve_schur();
  double row_conditioning();
  void row_scale_of(const MatrixXd& J, const VectorXd& d, VectorXd& out) const;
  const MatrixXd& H_of(double penalty);

  void choose_independent(const VectorXd& q0, double t);

  // the integrator projects the state on the constraint manifolds (all but cvode_adams, baumgarte)
  bool projects() const {
    return o.integrator != Integrator::cvode_adams && o.integrator != Integrator::baumgarte;
  }
  // smallest conditioning seen in the evaluations (row_conditioning or the Schur ratio) and where
  double eval_min_ratio = INFINITY, eval_min_t = 0;
  VectorXd eval_min_q0;
  double note_conditioning(double t, const VectorXd& q0, double ratio);

  // a1 = accelerations at (t, q0, q1). With baumgarte, A a = c - alpha (A q1 - b).
  void accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte);

  // Project q0 on psi = 0 and q1 on A q1 = b, mass-orthogonally and regularized by the
  // augmented-Lagrangian penalty (Bayo, Cuadrado): (W + alpha J^T N^2 J) dx = -alpha J^T N^2 r,
  // iterated (N: the dimensionless row scaling). Positions: solve_positions (NewtonStep::damped,
  // kinematics/solve_positions.hpp); velocities: the same correction, a linear problem, here.
  // In regular directions each iteration divides the residual by ~alpha sigma^2 / m (~1e7); in a
  // direction where the Jacobian loses rank (sigma -> 0) the correction vanishes instead of
  // blowing up as 1/sigma, so a state near a singular position is not thrown onto another branch.
  void project(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel);

  // Reactions of a recorded state with accelerations `a` (least-squares multipliers of
  // A^T lambda = B u - (M a - f); regularized where A loses rank).
  void compute_reactions(double t, const VectorXd& q0, const VectorXd& q1);

  double pivot_indicator(double t, const VectorXd& q0);
};

// The energy terms integrated along the run, carried as extra states after (q0, q1) under the
// same error control and stages as the state (so that the balance holds to integration accuracy).
enum EnergyTerm { kInputWork, kLoadWork, kConstraintWork, kDissipated, kEnergyTerms };
// Their rates (powers, W) at (t, q0, q1), right after d.accelerations(t, q0, q1, .) there.
void energy_rates(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1, double* rates);

struct Recorder {
  const Model& m;
  ForwardResult& r;
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
void check_finite_sample(const Model& m, const ForwardResult& r, int k);

// Integrator drivers: integrate from s0 to o.t1, recording every output time.
void run_explicit_rk(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
                     Recorder& rec);
void run_cvode(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
               Recorder& rec);

// The budget of a forward run (max_steps, max_seconds, progress monitor) with the hint its
// error gives besides the budget (integrator, tolerances, step).
detail::RunBudget::Settings forward_budget(const Model& m, const ForwardOptions& o,
                                           std::string hint);

}  // namespace mo2d::detail
