#pragma once
// Internal: the stages of linearize (src/modes/select.cpp, linearize.cpp).
#include <string>
#include <vector>

#include "mo2d/modes.hpp"

namespace mo2d::detail {

// The independent coordinates and quasi-velocities of ss (p, dof, coordinate_vars,
// velocity_vars, states) at the reference, chosen by pivoting or from o's labels (checked).
void choose_coordinates(const Model& m, const State& ref, const LinearizeOptions& o,
                        StateSpace& ss);
// The independent coordinates (q0 indices) for a whole reference: among the pivot's choices at
// its states, the one whose smallest selection quality over all of them is the largest.
std::vector<int> coordinates_along(const Model& m, const std::vector<State>& states);
// o with the independent coordinates and further quasi-velocities of ss written out as labels:
// the same coordinates again (a Newton iteration's line search, every state of a reference).
LinearizeOptions same_coordinates(const Model& m, const StateSpace& ss, LinearizeOptions o);
// dq0/dz, dq1/dw and dq1/dz of ss at the reference (after choose_coordinates).
void tangent_bases(const Model& m, const State& ref, StateSpace& ss);
// X = K^-1 [0; I], K = [J; the rows sel of the identity] (cols columns); Error if singular.
Eigen::MatrixXd selection_basis(const Eigen::MatrixXd& J, const std::vector<int>& sel, int cols,
                                const std::string& what, double t);

}  // namespace mo2d::detail
