#pragma once
// CSV output with a header of labels, written atomically (temporary file, then rename).
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"

namespace mo2d {

// The CSV files are written atomically (a temporary, then renamed; mo2d/output.hpp). The writers
// refuse a non-finite value (Error naming the column and the time).

// Columns: t, coordinates, quasi-velocities, their derivatives (label + ".dot"), efforts,
// reactions, residual.position, residual.velocity, residual.acceleration.
std::string inverse_csv(const InverseResult& r);
void write_inverse_csv(const InverseResult& r, const std::string& path);

// Columns: t, coordinates, quasi-velocities, their derivatives (label + ".dot"), efforts,
// reactions, energy.kinetic, energy.potential, work.inputs, energy.dissipated, work.loads (forces
// and torques), work.constraints (time-dependent constraints), residual.position,
// residual.velocity.
std::string forward_csv(const ForwardResult& r);
void write_forward_csv(const ForwardResult& r, const std::string& path);

}  // namespace mo2d
