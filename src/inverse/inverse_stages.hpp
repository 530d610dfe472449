#pragma once
// Internal stages of one inverse-dynamics sample shared by inverse.cpp and inverse_friction.cpp.
#include "mo2d/inverse.hpp"

namespace mo2d {

// From d.local_a (body-local M a - f, spent here), d.S, d.lu_u (C^T B) and d.friction: the
// efforts d.u, multipliers d.lambda and reactions d.reactions (Theorem 4.3).
void inverse_efforts_and_reactions(const Model& m, InverseData& d);
// The same with the joint friction: the fixed-point iteration friction -> reactions -> friction
// (Orsino Example 4.5) to InverseOptions::friction_tolerance; throws naming the friction and t.
void inverse_friction(const Model& m, InverseData& d, double t);

}  // namespace mo2d
