#pragma once
// CSV output with a header of labels, written atomically (temporary file, then rename).
#include <span>
#include <string>
#include <vector>

#include "mo2d/model.hpp"
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
// Numbers are written in the shortest form that reads back to the same double (std::to_chars
// without a precision: 0.005, not 0.0050000000000000001); strtod of a cell gives the bits
// written. `units` (one per column, trajectory_csv_units): written as a second header line; none:
// no such line.
std::string trajectory_csv(const Trajectory& r, std::span<const std::string> units = {});
// trajectory_csv(r) written to `path` (atomically: a temporary file, then a rename).
void write_trajectory_csv(const Trajectory& r, const std::string& path);

// The header of trajectory_csv(r): its column labels, in order.
std::vector<std::string> trajectory_csv_labels(const Trajectory& r);
// The unit of every column of trajectory_csv(r), in order (SI, from the kind of the column):
//   t s; node coordinates and sliders (.x .y .q) m, their rates m/s and derivatives m/s^2;
//   body rotation rates (.w) rad/s, rad/s^2; an extra coordinate rad when its rate sums body
//   rotations only, m when it sums lengths only (its .rate: per s); efforts .torque N·m, .force
//   N; reactions .Fx .Fy N, .T N·m; energy.* and work.* J; output columns (mo2d/output_columns.hpp)
//   .fx .fy .tension N, .torque N·m, .power W, .length m, .rate m/s (a torsional spring's rad/s),
//   points and centres of mass m, m/s.
// "" where the model cannot say: a user constraint's multiplier (.lambda: the unit of the
// constraint's own expression), an extra coordinate mixing lengths and angles, the residual
// norms (over rows of different kinds: lengths, angles, user constraints).
std::vector<std::string> trajectory_csv_units(const Model& m, const Trajectory& r);

}  // namespace mo2d
