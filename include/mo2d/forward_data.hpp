#pragma once
// The workspace of forward dynamics (Pinocchio's Data, MuJoCo's mjData): every matrix and vector
// that one evaluation of the accelerations, one projection or the reactions of one state need,
// allocated once by the constructor, so that the integrators' evaluations allocate nothing.
// forward_dynamics() builds one per run; forward_accelerations(model, data, t, q0, q1, efforts)
// is one evaluation on its own (Pinocchio's aba, MuJoCo's mj_forward).
//
// Sizes: n0 coordinates, n1 quasi-velocities, m0 position rows, m1 velocity rows (Model), nu
// inputs, nr reactions, dof degrees of freedom, slots = Model::n_slots (body-local slots of all
// bodies). "Written by" names the stage that writes a field:
//   init         the constructor (constant through the run)
//   evaluation   the accelerations at (t, q0, q1) (ForwardData::accelerations,
//   forward_accelerations):
//                velocity rows A, b, c; loads f; inputs u, B u; then the formulation of the options
//                (Schur or KKT direct solve, augmented Lagrangian, null space; forward.hpp)
//   projection   the projection of a state on psi = 0 and A q1 = b after each step (project)
//   reactions    the reactions of a recorded state (compute_reactions)
// Equations: M a1 = f + B u - A^T lambda, A a1 = c (eq. 4.1, index-1 form); reactions as in
// src/dynamics/reactions.hpp.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

namespace detail {
class SmallLU;          // dense LU of the small systems of one evaluation (src/linalg/small_lu.hpp)
class SparseEngine;     // the sparse path's matrices and factorizations
                        // (src/forward/sparse_engine.hpp)
class StructuredSchur;  // the Schur complement along A's pattern (src/linalg/structured_schur.hpp)
struct SlotEntry;       // an entry of A owned by a body slot, for the reactions (src/dynamics/)
}  // namespace detail

struct ForwardData {
  // The model must outlive the workspace; the options are copied (formulation, integrator,
  // penalty, Baumgarte feedback, the effort functions of forward_dynamics).
  explicit ForwardData(const Model& model, const ForwardOptions& options = {});
  ~ForwardData();
  ForwardData(const ForwardData&) = delete;
  ForwardData& operator=(const ForwardData&) = delete;

  // the model the workspace was built for (it must outlive the workspace)
  const Model& m;
  // the options, copied at construction
  const ForwardOptions o;

  // With sparse linear algebra (ForwardOptions::linear_algebra, uses_sparse) the dense matrices
  // below (M, Minv, A, Psi, An, G1, KKT, H, K, S, CtMC, M0, W0) stay empty: their sparse
  // counterparts live in the engine (sparse_engine()), the vectors are the same.

  // ---- constant (written by init) --------------------------------------------------------------
  MatrixXd M;             // n1 x n1: reduced mass matrix (eq. 5.25-5.27)
  MatrixXd Minv;          // n1 x n1: M^-1 when has_Minv (else empty)
  bool has_Minv = false;  // M positive definite, not nearly singular: direct solves by Schur
  MatrixXd B;             // n1 x nu: input matrix (generalized force per unit effort)
  // n0 x n0: metric of the position projection: M's coordinate block plus 1e-6 of the mass scale
  // (dimensionless) on the diagonal, so that massless nodes and extra coordinates are held too
  MatrixXd M0;
  double alpha = 0;  // augmented-Lagrangian penalty (ForwardOptions::penalty, or 1e7 mass scale)
  // Dimensionless columns (column_scaling, mo2d/kinematics.hpp): col_scale d (n1; 1 for lengths,
  // 1 / size for a rotation) and pos_scale, its first n0 entries. Every conditioning test, the
  // penalty (alpha N^2 in place of alpha) and the convergence tests are made on N A diag(d), so
  // they do not depend on units or on the size of the mechanism.
  VectorXd col_scale, pos_scale;
  std::vector<int> edge_offset;  // per Model::merge_edges entry: offset of its forces in edge_force

  // ---- one evaluation (written by evaluation) --------------------------------------------------
  MatrixXd A;  // m1 x n1: velocity constraint Jacobian, A q1 = b
  VectorXd b;  // m1: right-hand side of A q1 = b
  VectorXd c;  // m1: A a1 = c (minus alpha_B (A q1 - b) with Baumgarte's feedback)
  VectorXd f;  // n1: applied generalized forces (gravity, forces, torques, springs, dampers)
  // n1: the part of f from ForwardOptions::extra_forces, and the power it dissipates (W)
  VectorXd f_extra;
  double extra_dissipation = 0;
  VectorXd u;                            // nu: efforts at t, one per Model::inputs entry
  std::vector<CompiledLaw> effort_laws;  // nu: ForwardOptions::efforts compiled (empty: 0)
  VectorXd Bu;                           // n1: B u
  VectorXd rhs;                          // n1: f + B u
  VectorXd a;                            // n1: THE RESULT, the accelerations a1 = d/dt q1
  VectorXd lambda;     // m1: multipliers, M a = f + B u - A^T lambda (warm start of the next one)
  VectorXd local;      // slots: body-local applied forces before their sum into f (eq. 5.27)
  VectorXd row_scale;  // m1: N, 1 / |row i of A diag(d)|: unit dimensionless rows
  // Direct solve by the Schur complement (has_Minv): N A M^-1 A^T N lambda_n = N A M^-1 rhs - N c
  // along the pattern of A (src/linalg/structured_schur.hpp), r1 (m1) -> lambda_n. The
  // conditioning test without M^-1 (row_conditioning) writes An = N A D and G1 = An An^T; H_of
  // writes An = N A.
  MatrixXd An, G1;
  VectorXd r1;  // m1: Schur right-hand side / multipliers (also the projection's A q1 - b)
  // KKT formulation (and the direct solve without M^-1): KKT = [M A^T; A 0] ((n1 + m1)^2, LU),
  // kkt_x = [a; lambda] (n1 + m1)
  MatrixXd KKT;
  VectorXd kkt_x;
  // Augmented Lagrangian: H = M + alpha A^T N^2 A (n1 x n1, Cholesky llt_H); tmp0 (n1) the force
  // residual f + B u - M a - A^T lambda, then the step; tmp1 (n1) A^T lambda; ap.head(m1) the
  // constraint residual N^2 (c - A a).
  MatrixXd H;
  Eigen::LLT<MatrixXd> llt_H;
  VectorXd tmp0, tmp1;
  double accel_residual = 0;  // relative residual of the last augmented-Lagrangian iteration
  bool accel_ok = true;       // the last accelerations are accurate (not regularized away)
  // Null space: K = [A; E] (n1 x n1, LU), E the rows of the independent quasi-velocities
  // `independent` (dof indices, re-chosen when K gets ill-conditioned); S = C = K^-1 [0; I]
  // (n1 x dof); ap = a_p = K^-1 [c; 0] (n1); CtMC = C^T M C (dof x dof, Cholesky llt_red);
  // red (dof) = C^T (f + B u - M a_p), then the independent accelerations x: a = a_p + C x.
  MatrixXd K, S, CtMC;
  VectorXd ap, red;
  Eigen::LLT<MatrixXd> llt_red;
  std::vector<int> independent;
  // smallest conditioning of the evaluations (row_conditioning or the Schur ratio), its time and
  // coordinates: an integrator that does not project stops there (forward_run.hpp, Recorder)
  double eval_min_ratio = INFINITY, eval_min_t = 0;
  VectorXd eval_min_q0;
  // the conditioning of the last evaluation (INFINITY where the formulation does not estimate it)
  double eval_ratio = INFINITY;

  // ---- projection (written by projection) ------------------------------------------------------
  VectorXd psi;            // m0: position residual psi(q0, t)
  MatrixXd Psi;            // m0 x n0: position Jacobian, rows made unit (pos_row_scale)
  VectorXd pos_row_scale;  // m0: 1 / |row i of Psi diag(pos_scale)|
  MatrixXd W0;             // n0 x n0: M0 + alpha Psi^T Psi (Cholesky llt_G0)
  VectorXd dq0;            // n0: position correction, W0 dq0 = -alpha Psi^T psi
  VectorXd dq1;            // n1: velocity correction, H dq1 = -alpha A^T N^2 (A q1 - b)
  Eigen::LLT<MatrixXd> llt_G0, llt_G1;  // of W0 and of H (velocity projection)

  // ---- reactions of a recorded state (written by reactions) ------------------------------------
  VectorXd la;  // slots: body-local M a - f (then the bodies' shares, overwritten)
  VectorXd w;   // n1: M a - f summed into the variables
  // m1: least-squares multipliers of A^T lambda = B u - (M a - f): minimum-norm, from the
  // regularized normal equations refined on the true residual (src/forward/least_squares.hpp)
  VectorXd lam_ls;
  // Their workspace: ls_x (n1) the right-hand side, ls_r (n1) the residual, ls_d (m1) a
  // correction; dense path: G_ls = A A^T + eps I (m1 x m1) and its Cholesky llt_ls.
  VectorXd ls_x, ls_r, ls_d;
  MatrixXd G_ls;
  Eigen::LLT<MatrixXd> llt_ls;
  std::vector<double> edge_force;  // per merge edge: its 2 (node) or 1 (rotation) forces
  VectorXd reactions;              // nr: Model::reactions
  // Joint friction (Model::frictions; src/dynamics/friction.hpp), written by evaluation: the
  // values consistent with the reactions at the accelerations a (iterated per evaluation, sgn(v)
  // = tanh(v / v_s)); friction_next the iteration's next values.
  VectorXd friction, friction_next;

  RunStats stats;  // counters of the run (evaluations, factorizations, projections, ...)

  // The direct solve is used where row_conditioning() >= kDirectAccept (sigma ratio >= 0.1);
  // the augmented-Lagrangian result is accurate below the relative residual kAlfAccept.
  static constexpr double kDirectAccept = 1e-2, kKktAccept = 1e-14, kAlfAccept = 1e-8;

  // ---- the stages (src/forward/forward_data.cpp; the integrator drivers call them) -------------
  // a = accelerations at (t, q0, q1) with the efforts of the options' functions at t. With
  // baumgarte, A a = c - alpha_B (A q1 - b).
  void accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte);
  // The same with the efforts given (nu values).
  void accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte,
                     const VectorXd& efforts);
  // Project q0 on psi = 0 and q1 on A q1 = b, mass-orthogonally and regularized by the
  // augmented-Lagrangian penalty (Bayo, Cuadrado): (W + alpha J^T N^2 J) dx = -alpha J^T N^2 r,
  // iterated (N: the dimensionless row scaling). Positions: solve_positions (NewtonStep::damped,
  // src/kinematics/solve_positions.hpp); velocities: the same correction, a linear problem, here.
  // In regular directions each iteration divides the residual by ~alpha sigma^2 / m (~1e7); in a
  // direction where the Jacobian loses rank (sigma -> 0) the correction vanishes instead of
  // blowing up as 1/sigma, so a state near a singular position is not thrown onto another branch.
  // With quasi-steady springs (mo2d/quasi_steady.hpp) the lengths they hold are settled too.
  void project(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel);
  // The projection with the quasi-steady springs' lengths held as they are.
  void project_held(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel);
  // Reactions of a recorded state with accelerations `a` (least-squares multipliers of
  // A^T lambda = B u - (M a - f), to the digits of the state; minimum-norm where A loses rank:
  // src/forward/least_squares.hpp).
  void compute_reactions(double t, const VectorXd& q0, const VectorXd& q1);
  // (sigma_min / sigma_max)^2 of the dimensionless A at q0 (pivot ratio of its Gram matrix).
  double pivot_indicator(double t, const VectorXd& q0);
  // the integrator projects the state on the constraint manifolds (all but cvode_adams, baumgarte)
  bool projects() const {
    return o.integrator != Integrator::cvode_adams && o.integrator != Integrator::baumgarte;
  }
  // out = the dimensionless row scales of J with the column scaling d (unit rows of J diag(d);
  // mo2d/kinematics.hpp).
  void row_scale_of(const MatrixXd& J, const VectorXd& d, VectorXd& out) const;
  // The pieces the recorder and the integrators read, on either path: A and b at (t, q0);
  // out = A q1 - b (with the A of the last fill); psi and pos_row_scale at (t, q0); out = M x;
  // A at (t, q0) as a dense matrix (allocates: for the messages of singular configurations).
  void fill_velocity_rows(double t, const VectorXd& q0);
  void velocity_residual_into(const VectorXd& q1, VectorXd& out) const;
  void fill_position_rows(double t, const VectorXd& q0);
  void mass_times(const VectorXd& x, VectorXd& out) const;
  MatrixXd dense_velocity_rows(double t, const VectorXd& q0) const;
  // the sparse path's engine, or nullptr on the dense path
  const detail::SparseEngine* sparse_engine() const { return sparse_.get(); }

 private:
  std::unique_ptr<detail::SparseEngine> sparse_;
  std::unique_ptr<detail::SmallLU> lu_kkt_, lu_K_, lu_G1_;  // of KKT, K and G1
  std::unique_ptr<detail::StructuredSchur> schur_;          // the direct solve when has_Minv
  std::vector<detail::SlotEntry> entries_;  // reactions: A entries attributed to body slots
  bool quasi_steady_ = false;               // the model has quasi-steady springs

  void inputs(double t, const VectorXd& q0, const VectorXd& q1);
  void set_inputs(const VectorXd& efforts, double t);
  void load(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte);
  void evaluate(double t, const VectorXd& q0, const VectorXd& q1);
  [[noreturn]] void throw_not_finite(double t, const VectorXd& q0, const VectorXd& q1) const;
  void solve_formulation(double t, const VectorXd& q0);
  void evaluate_friction(double t, const VectorXd& q0, const VectorXd& q1);
  void reactions_at(double t, const VectorXd& q0, const VectorXd& q1);
  void init_sparse();
  void fill_velocity_schur(double t, const VectorXd& q0);
  void solve_sparse(double t, const VectorXd& q0);
  void project_sparse(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel);
  void solve_augmented_lagrangian(double t, const VectorXd& q0);
  void solve_lagrange(double t, const VectorXd& q0);
  void solve_null_space(double t, const VectorXd& q0);
  double solve_kkt();
  double solve_schur();
  double row_conditioning();
  const MatrixXd& H_of(double penalty);
  void choose_independent(const VectorXd& q0, double t);
  double note_conditioning(double t, const VectorXd& q0, double ratio);
};

// Whether a workspace for (m, o) uses the sparse linear algebra (ForwardOptions::linear_algebra).
// Throws Error (element "linear_algebra") for sparse with an integrator or formulation that has
// no sparse path.
bool uses_sparse(const Model& m, const ForwardOptions& o);

// The accelerations a1 at the state (t, q0, q1) under the efforts u (one per Model::inputs entry,
// in order), by the formulation of data's options (ForwardOptions::formulation): the right-hand
// side d/dt q1 that forward_dynamics integrates. Written to data.a and returned (a reference to
// it); the other fields of the evaluation stage are written too (data.lambda: the multipliers,
// data.f, data.c, ...). data must have been built for `model`. No heap allocation. Throws Error
// for a non-finite state, effort or result, and where the formulation cannot solve (the Lagrange
// and null-space formulations at a singular configuration).
const VectorXd& forward_accelerations(const Model& model, ForwardData& data, double t,
                                      const VectorXd& q0, const VectorXd& q1,
                                      const VectorXd& efforts);

}  // namespace mo2d
