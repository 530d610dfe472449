#pragma once
// mo2d inverse --sensitivity p1,p2: the derivative columns of the CSV, the JSON summary's
// "sensitivities" and the printed table (mo2d/sensitivity.hpp; docs/design.md, "Sensitivities").
#include <string>
#include <vector>

#include "mo2d/sensitivity.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::cli {

// The JSON summary `summary` with "sensitivities": per parameter its value, step and, per effort
// and reaction column, the summary values' derivatives (peak, max, min, mean, rms, peak_to_peak).
std::string add_sensitivity_json(const std::string& summary, const Trajectory& r,
                                 const InverseSensitivity& d,
                                 const std::vector<ParameterModels>& parameters);

// Per parameter and input: d(peak |effort|)/dp, d(RMS)/dp, d(peak-to-peak)/dp.
void print_sensitivity_table(const Trajectory& r, const InverseSensitivity& d);

}  // namespace mo2d::cli
