#pragma once
// CSV output with a header of labels, written atomically (temporary file, then rename).
#include <string>

#include "mo2d/trajectory.hpp"

namespace mo2d {

// The CSV files are written atomically (a temporary, then renamed; mo2d/output.hpp). The writers
// refuse a non-finite value (Error naming the column and the time).

// Columns: t, coordinates, quasi-velocities, their derivatives (label + ".dot"), efforts,
// reactions; for a forward run energy.kinetic, energy.potential, work.inputs, energy.dissipated,
// work.loads (forces and torques), work.constraints (time-dependent constraints); then the
// residuals (Trajectory::residual_labels): residual.position, residual.velocity and, for an
// inverse run, residual.acceleration; then the columns added on request (Trajectory::output_labels,
// mo2d/output_columns.hpp).
std::string trajectory_csv(const Trajectory& r);
void write_trajectory_csv(const Trajectory& r, const std::string& path);

}  // namespace mo2d
