#pragma once
// The JSON summary of a run (peaks of the efforts with their times, max residuals, energy error,
// CPU time), written next to the CSV.
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::cli {

std::string inverse_summary(const Scene& s, const Model& m, const Trajectory& r);
std::string forward_summary(const Scene& s, const Model& m, const Trajectory& r);

}  // namespace mo2d::cli
