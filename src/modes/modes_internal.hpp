#pragma once
// Internal: the stages of linearize (src/modes/select.cpp, linearize.cpp).
#include <string>
#include <vector>

#include "mo2d/modes.hpp"
#include "run/run_budget.hpp"

namespace mo2d::detail {

// The independent coordinates and quasi-velocities of ss (p, dof, coordinate_vars,
// velocity_vars, states) at the reference, chosen by pivoting or from o's labels (checked).
void choose_coordinates(const Model& m, const State& ref, const LinearizeOptions& o,
                        StateSpace& ss);
// The independent coordinates (q0 indices) for a whole reference: among the pivot's choices at
// its states, the one whose smallest selection quality over all of them is the largest.
// (budget: checked at every state.)
std::vector<int> coordinates_along(const Model& m, const std::vector<State>& states,
                                   RunBudget* budget = nullptr);
// o with the independent coordinates and further quasi-velocities of ss written out as labels:
// the same coordinates again (a Newton iteration's line search, every state of a reference).
LinearizeOptions same_coordinates(const Model& m, const StateSpace& ss, LinearizeOptions o);
// dq0/dz, dq1/dw and dq1/dz of ss at the reference (after choose_coordinates).
void tangent_bases(const Model& m, const State& ref, StateSpace& ss);
// X = K^-1 [0; I], K = [J; the rows sel of the identity] (cols columns); Error if singular.
Eigen::MatrixXd selection_basis(const Eigen::MatrixXd& J, const std::vector<int>& sel, int cols,
                                const std::string& what, double t);

// The budgets (modes_budget.cpp). Refuses, before any work, `linearizations` linearizations of
// m (and, if `modes`, the eigenvectors of G) whose dense matrices need more than max_memory bytes
// (Error "max_memory") or whose estimated time exceeds max_seconds (BudgetExhausted), naming
// the sizes. <= 0 or inf: no limit.
void check_modes_budget(const std::string& what, const Model& m, double max_seconds,
                        double max_memory, int linearizations, bool modes);
// The same for the eigenvectors of ss's G (vibration_modes).
void check_eigen_budget(const std::string& what, const StateSpace& ss, double max_seconds,
                        double max_memory);
// The wall-clock budget of that work at time t (checked between its stages; polls interrupts).
RunBudget::Settings modes_budget(const std::string& what, const Model& m, double t,
                                 double max_seconds);
// The estimate's constants: Eigen's JacobiSVD with full V costs about kSvdFlops n^3 (n x n);
// kDenseFlopsPerSecond is twice the rate measured here (linearize of 100- and 200-link chains:
// 0.38 s and 3.3 s, estimated 0.15 s and 1.2 s), so that the estimate is
// below the real time (a refusal is certain to be right; the stages' checks catch the rest).
inline constexpr double kSvdFlops = 20;
inline constexpr double kDenseFlopsPerSecond = 8e9;
// linearize within a budget started by the caller (static_equilibrium, linearize_along): checked
// between its stages.
StateSpace linearize_within(const Model& m, const State& reference, const LinearizeOptions& o,
                            RunBudget& budget);

}  // namespace mo2d::detail
