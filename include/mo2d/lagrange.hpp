#pragma once
// Second formulation, for validation: Lagrange multipliers on the unreduced model
// (Reduction::none: every joint is a constraint row). At each sample the kinematics are solved
// as in inverse_dynamics, then accelerations, multipliers and efforts together from
//   [ M  A^T  -B ] [a1    ]   [ f      ]
//   [ A  0     0 ] [lambda] = [ c      ]
//   [ E  0     0 ] [u     ]   [ s_ddot ]
// so M a1 = f + B u - A^T lambda. Reactions are read from lambda directly.
#include "mo2d/inverse.hpp"

namespace mo2d {

InverseResult inverse_dynamics_lagrange(const Model& m, std::span<const Prescribed> prescribed,
                                        const InverseOptions& options);

}  // namespace mo2d
