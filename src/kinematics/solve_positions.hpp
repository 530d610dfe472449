#pragma once
// The one Newton solver of the position constraints psi(q0, t) = 0 (the holonomic rows of
// constraints/constraints.hpp, docs/equations.md), over the coordinates not held fixed. Its three
// callers differ only in how a step solves the linearized constraints and in how far it goes:
//
//   caller                          step          line search      iterations      non-finite psi
//   assembly (assemble, from        minimum_norm  armijo, >= 1e-8  100, the last   error at the
//     build_model, consistent_state)                               not tested      start, trials
//                                                                                  rejected
//   inverse dynamics, per sample    lu (pivot     decrease,        options (30),   error
//     (newton in inverse.cpp)         test)       >= 1e-4          the last tested
//   forward projection              damped (mass  none             6, the last     not checked
//     (ForwardData::project)          metric)                      not tested
//
// Why each keeps its own (and the results stay those of the three solvers this one replaced):
// - assembly starts from a guess that may be far from the constraints and may fix coordinates
//   that leave J rectangular or rank deficient: the minimum-norm Gauss-Newton step keeps the
//   solution on the branch nearest the guess, the Armijo search on |psi|_2 makes it globally
//   convergent, and a non-finite trial (a user function outside its domain) is a step too far.
// - inverse dynamics starts from a prediction O(h^3) away with J square (as many prescribed
//   coordinates as degrees of freedom): the exact step by the allocation-free SmallLU, whose pivot
//   ratio also tells a singular configuration apart (status singular, reported by the caller);
//   the caller continues from the last solved sample when Newton does not converge.
// - the forward projection starts within the integrator's tolerance of the manifold: a fixed
//   number of regularized steps in the mass metric (dx small where J loses rank, so a state near
//   a singular position is not thrown onto another branch), no line search, no error (the drift
//   check of the recorder judges the result).
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <span>

#include "linalg/small_lu.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

class PatternLU;  // linalg/pattern_lu.hpp

using Eigen::MatrixXd;
using Eigen::VectorXd;

// How an iteration solves the linearized constraints J dx = psi (J = d psi / d q0 over the free
// coordinates); the iterate moves by -alpha dx.
enum class NewtonStep {
  // J square: dx = J^-1 psi (SmallLU, no allocation); a pivot ratio below
  // NewtonOptions::singular_pivot_ratio stops with NewtonStatus::singular.
  lu,
  // Gauss-Newton: the least-squares dx of least norm (complete orthogonal decomposition with the
  // rank threshold NewtonOptions::rank_threshold; allocates).
  minimum_norm,
  // Regularized in the metric W (NewtonBuffers::metric), on the rows of J diag(d) made unit (N):
  // (W + alpha J^T N^2 J) dx = alpha J^T N^2 psi, alpha = NewtonOptions::penalty (the
  // augmented-Lagrangian projection of Bayo and Cuadrado). Overwrites J and psi by N J, N psi.
  damped,
};

// How much of the step an iteration takes.
enum class LineSearch {
  none,      // the whole step
  decrease,  // alpha = 1, 1/2, 1/4, ... >= min_alpha until |psi|_inf decreases strictly
  armijo,    // alpha = 1, 1/2, ... >= min_alpha until |psi|_2 <= (1 - 1e-4 alpha) |psi|_2
};

// What a non-finite residual does.
enum class NonFinite {
  ignore,  // nothing: it flows into the iterates (the caller's later checks report it)
  reject,  // at the start: stops with NewtonStatus::non_finite; at a line-search trial: rejected
  stop,    // anywhere: stops with NewtonStatus::non_finite, psi holding it
};

struct NewtonOptions {
  double tolerance = 0;    // converged when |psi|_inf <= tolerance (absolute)
  int max_iterations = 0;  // iterations (steps) at most
  bool test_last = true;   // evaluate and test the iterate of iteration max_iterations
  NewtonStep step = NewtonStep::lu;
  double singular_pivot_ratio = 0;  // lu
  double rank_threshold = 0;        // minimum_norm
  double penalty = 0;               // damped
  LineSearch line_search = LineSearch::none;
  double min_alpha = 0;  // the smallest step fraction a line search tries
  NonFinite non_finite = NonFinite::stop;
};

enum class NewtonStatus {
  converged,
  singular,        // lu: J's pivot ratio below singular_pivot_ratio
  stalled,         // the line search found no acceptable step
  max_iterations,  // not converged in max_iterations
  non_finite,      // a non-finite residual (NonFinite::reject at the start, or NonFinite::stop)
};

struct NewtonResult {
  NewtonStatus status = NewtonStatus::converged;
  // iterations begun (the last one unfinished unless converged; max_iterations + 1 when the last
  // iterate was tested and failed)
  int iterations = 0;
  // |psi|_inf at the last iterate tested: the returned q0, unless the iteration limit was reached
  // with test_last false
  double residual = 0;
};

// The caller's storage, sized once for the model (m0 rows, `free` = the coordinates not held
// fixed): the solver allocates nothing, except for NewtonStep::minimum_norm.
struct NewtonBuffers {
  VectorXd& psi;                    // m0: the residual of the last iterate evaluated
  MatrixXd& J;                      // m0 x free: its Jacobian over the free coordinates
  VectorXd& dx;                     // free: the last step
  VectorXd* q_trial = nullptr;      // n0: a line search's trial point
  SmallLU* lu = nullptr;            // NewtonStep::lu (size free)
  PatternLU* pattern_lu = nullptr;  // NewtonStep::lu: used instead of lu if set
  // NewtonStep::damped (all coordinates free): the metric W (n0 x n0), the column scaling d (n0),
  // and workspace for N (m0), W + alpha J^T N^2 J and its factorization
  const MatrixXd* metric = nullptr;
  const VectorXd* col_scale = nullptr;
  VectorXd* row_scale = nullptr;
  MatrixXd* W = nullptr;
  Eigen::LLT<MatrixXd>* llt = nullptr;
};

// Newton on psi(q0, t) = 0 from q0, moving only the coordinates k with colmap[k] >= 0 (colmap:
// coordinate -> free column, -1 held fixed; empty: all free). On return q0 is the last accepted
// iterate; psi and J are evaluated there unless the status is non_finite (psi: the non-finite
// residual) or the iteration limit was reached with test_last false (then they are those of the
// iterate before, and for NewtonStep::damped scaled).
NewtonResult solve_positions(const Model& m, const NewtonOptions& o, NewtonBuffers& w, double t,
                             std::span<const int> colmap, VectorXd& q0);

}  // namespace mo2d::detail
