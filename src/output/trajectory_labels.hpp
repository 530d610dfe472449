#pragma once
// Internal: an empty Trajectory of a run on a model, with its kind and every column label set
// (shared by inverse_dynamics, inverse_dynamics_lagrange and forward_dynamics).
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::detail {

// Labels from the model; residual labels: position and velocity, plus acceleration for an
// inverse run.
Trajectory labelled_trajectory(const Model& m, RunKind kind);

}  // namespace mo2d::detail
