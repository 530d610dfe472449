#pragma once
// The named summary values of a run that an optimization's objective and constraints read
// (mo2d/optimize.hpp: peak.COL, max.COL, min.COL, mean.COL, rms.COL, peak_to_peak.COL,
// energy_fluctuation.INPUT, flywheel.INPUT).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "mo2d/design.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::optimize_detail {

// A summary value: a statistic of one column (or of one input, for the design summary's).
struct RunValue {
  enum class Stat { peak, max, min, mean, rms, peak_to_peak, energy_fluctuation, flywheel };
  Stat stat = Stat::peak;
  std::string column{};  // a CSV label (mo2d/csv.hpp), or an input label
};

// The statistic prefixes, in the order of RunValue::Stat ("peak", ..., "flywheel").
const std::vector<std::string>& run_value_prefixes();
// "rms.crank_pivot.torque" -> {rms, "crank_pivot.torque"}; nullopt without a known prefix.
std::optional<RunValue> parse_run_value(const std::string& name);
// Whether the value needs the design summary (energy_fluctuation, flywheel).
inline bool needs_design_summary(const RunValue& v) {
  return v.stat == RunValue::Stat::energy_fluctuation || v.stat == RunValue::Stat::flywheel;
}

// The samples of the CSV column `label` of r (t, coordinates, rates, their ".dot", efforts,
// reactions, energies of a forward run, residuals, outputs); nullopt when r has none.
std::optional<Eigen::VectorXd> column_samples(const Trajectory& r, const std::string& label);

// The value of v in run r (d: its design summary, for energy_fluctuation and flywheel). Throws
// Error when r has no such column or input (the caller resolves names on a first run).
double run_value(const RunValue& v, const Trajectory& r, const DesignSummary* d);

}  // namespace mo2d::optimize_detail
