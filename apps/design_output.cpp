// The designer's measures on the command line: request, table and JSON (design_output.hpp).
#include "design_output.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>

namespace mo2d::cli {

namespace {

using json = nlohmann::ordered_json;
constexpr double kDeg = 180 / std::numbers::pi;

// A number for JSON: null when not finite (a limit position the input never reaches).
json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

// Sampled maximum of |column| and its time (labels ending in `suffix`: each joint's load).
struct Peak {
  std::string label;
  double value = 0, t = 0;
};
std::vector<Peak> peaks(const Trajectory& r, const std::string& suffix) {
  std::vector<Peak> out;
  for (size_t c = 0; c < r.output_labels.size(); ++c) {
    const std::string& l = r.output_labels[c];
    if (l.size() < suffix.size() || l.compare(l.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    Eigen::Index k = 0;
    const double v = r.outputs.col(static_cast<Eigen::Index>(c)).cwiseAbs().maxCoeff(&k);
    out.push_back({l, v, r.time[k]});
  }
  return out;
}

}  // namespace

void print_design_table(const Trajectory& r, const DesignSummary& d) {
  std::printf("  %-24s %14s %14s %14s %14s %16s\n", "input (design)", "mean", "RMS", "peak-to-peak",
              "dE max [J]", "flywheel [kg m2]");
  for (const EffortMeasures& e : d.efforts)
    std::printf("  %-24s %14.8g %14.8g %14.8g %14.8g %16.8g\n", e.input.c_str(), e.mean, e.rms,
                e.peak_to_peak, e.energy_fluctuation, e.flywheel_inertia);
  if (d.speed_fluctuation > 0)
    std::printf("  flywheel for a speed fluctuation Cs = %g: I = dE max / (Cs w_mean^2)\n",
                d.speed_fluctuation);
  for (const FourBarSummary& f : d.four_bars) {
    const FourBarPositions& p = f.positions;
    std::printf("  four-bar %s: %s (ground %g, input %g, coupler %g, output %g m)\n",
                f.name.c_str(), to_string(f.grashof), f.lengths.ground, f.lengths.input,
                f.lengths.coupler, f.lengths.output);
    if (p.input_rotates)
      std::printf("    input turns fully;");
    else
      std::printf("    input between dead positions %.6g and %.6g deg;", p.input_min * kDeg,
                  p.input_max * kDeg);
    std::printf(" limit positions at input %.6g deg (extended), %.6g deg (folded)\n",
                p.limit_extended * kDeg, p.limit_folded * kDeg);
    std::printf(
        "    transmission angle %.6g to %.6g deg (closed form), %.6g to %.6g deg in the run\n",
        p.min_transmission * kDeg, p.max_transmission * kDeg, f.run_min_transmission * kDeg,
        f.run_max_transmission * kDeg);
  }
  for (const Peak& p : peaks(r, "frame.shaking.F"))
    std::printf("  max shaking force %.8g N at t = %.6g s\n", p.value, p.t);
  for (const Peak& p : peaks(r, "frame.shaking.M"))
    std::printf("  max |shaking moment| %.8g N m at t = %.6g s\n", p.value, p.t);
  for (const Peak& p : peaks(r, ".load"))
    std::printf("  max bearing load %-24s %14.8g N at t = %.6g s\n", p.label.c_str(), p.value, p.t);
}

std::string design_json(const Trajectory& r, const DesignSummary& d) {
  json j = json::object();
  json efforts = json::object();
  for (const EffortMeasures& e : d.efforts)
    efforts[e.input] = {{"mean", e.mean},
                        {"rms", e.rms},
                        {"peak_to_peak", e.peak_to_peak},
                        {"mean_speed", e.mean_speed},
                        {"travel", e.travel},
                        {"energy_fluctuation", e.energy_fluctuation},
                        {"flywheel_inertia", number(e.flywheel_inertia)}};
  j["efforts"] = efforts;
  j["speed_fluctuation"] = number(d.speed_fluctuation > 0 ? d.speed_fluctuation : NAN);
  json bars = json::object();
  for (const FourBarSummary& f : d.four_bars) {
    const FourBarPositions& p = f.positions;
    bars[f.name] = {
        {"lengths",
         {{"ground", f.lengths.ground},
          {"input", f.lengths.input},
          {"coupler", f.lengths.coupler},
          {"output", f.lengths.output}}},
        {"grashof", to_string(f.grashof)},
        {"input_rotates", p.input_rotates},
        {"input_range", p.input_rotates ? json(nullptr) : json{p.input_min, p.input_max}},
        {"limit_positions",
         {{"extended",
           {{"input", number(p.limit_extended)}, {"output", number(p.output_extended)}}},
          {"folded", {{"input", number(p.limit_folded)}, {"output", number(p.output_folded)}}}}},
        {"transmission_angle",
         {{"min", number(p.min_transmission)},
          {"max", number(p.max_transmission)},
          {"run_min", number(f.run_min_transmission)},
          {"run_max", number(f.run_max_transmission)}}}};
  }
  j["four_bars"] = bars;
  json maxima = json::object();
  for (const std::string suffix : {"frame.shaking.F", "frame.shaking.M", ".load"})
    for (const Peak& p : peaks(r, suffix)) maxima[p.label] = {{"max_abs", p.value}, {"t", p.t}};
  j["maxima"] = maxima;
  return j.dump();
}

}  // namespace mo2d::cli
