#pragma once
// Internal stages of one inverse-dynamics sample shared by inverse.cpp and inverse_friction.cpp,
// and the run over the samples shared with inverse_sensitivity.cpp.
#include <functional>
#include <string>

#include "mo2d/inverse.hpp"

namespace mo2d {

// From d.local_a (body-local M a - f, spent here), d.S, d.lu_u (C^T B) and d.friction: the
// efforts d.u, multipliers d.lambda and reactions d.reactions (Theorem 4.3).
void inverse_efforts_and_reactions(const Model& m, InverseData& d);
// The same with the joint friction: the fixed-point iteration friction -> reactions -> friction
// (Orsino Example 4.5) to InverseOptions::friction_tolerance; throws naming the friction and t.
void inverse_friction(const Model& m, InverseData& d, double t);

namespace detail {
// The run over options' samples with workspace d (inverse_dynamics): each sample solved, then
// `after_sample(k)` (if set) while d holds sample k, then recorded; the run's budget named `run`.
Trajectory inverse_run(const Model& m, InverseData& d, const InverseOptions& options,
                       const std::string& run, const std::function<void(int)>& after_sample);
}  // namespace detail

}  // namespace mo2d
