// The designer's measures in Python (mo2d/design.hpp, docs/design.md): mo2d.four_bar (Grashof
// class, limit and dead positions from four lengths), mo2d.transmission_angle, and Result.design
// (the summary of a scene run with a design: block or measures=True).
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.hpp"

namespace mo2d::py_bind {

namespace {

py::object number(double v) {
  return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
}

py::dict positions_dict(const FourBarLengths& l) {
  const FourBarPositions p = four_bar_positions(l);
  py::dict d;
  d["grashof"] = to_string(grashof_class(l));
  d["input_rotates"] = p.input_rotates;
  d["input_range"] = p.input_rotates ? py::object(py::none())
                                     : py::object(py::make_tuple(p.input_min, p.input_max));
  d["limit_extended"] = py::make_tuple(number(p.limit_extended), number(p.output_extended));
  d["limit_folded"] = py::make_tuple(number(p.limit_folded), number(p.output_folded));
  d["min_transmission"] = p.min_transmission;
  d["max_transmission"] = p.max_transmission;
  return d;
}

}  // namespace

std::optional<DesignRequest> design_of(const Scene& scene, bool measures) {
  if (!measures && scene.design.empty()) return std::nullopt;
  return scene_design_request(scene, measures);
}

Trajectory first_outputs(const Trajectory& r, Eigen::Index n) {
  if (r.outputs.cols() == n) return r;
  Trajectory t = r;
  t.outputs = r.outputs.leftCols(n);
  t.output_labels.resize(static_cast<size_t>(n));
  return t;
}

py::object design_dict(const Result& r) {
  if (!r.design) return py::none();
  const DesignSummary s = design_summary(*r.model, r.trajectory, *r.design);
  py::dict efforts;
  for (const EffortMeasures& e : s.efforts) {
    py::dict x;
    x["mean"] = e.mean;
    x["rms"] = e.rms;
    x["peak_to_peak"] = e.peak_to_peak;
    x["mean_speed"] = e.mean_speed;
    x["travel"] = e.travel;
    x["energy_fluctuation"] = e.energy_fluctuation;
    x["flywheel_inertia"] = number(e.flywheel_inertia);
    efforts[py::str(e.input)] = x;
  }
  py::dict bars;
  for (const FourBarSummary& f : s.four_bars) {
    py::dict x = positions_dict(f.lengths);
    x["lengths"] =
        py::make_tuple(f.lengths.ground, f.lengths.input, f.lengths.coupler, f.lengths.output);
    x["run_min_transmission"] = f.run_min_transmission;
    x["run_max_transmission"] = f.run_max_transmission;
    bars[py::str(f.name)] = x;
  }
  py::dict d;
  d["efforts"] = efforts;
  d["four_bars"] = bars;
  d["speed_fluctuation"] = number(s.speed_fluctuation > 0 ? s.speed_fluctuation : NAN);
  return d;
}

void bind_design(py::module_& m) {
  m.def(
      "four_bar",
      [](double ground, double input, double coupler, double output) {
        return positions_dict({ground, input, coupler, output});
      },
      py::arg("ground"), py::arg("input"), py::arg("coupler"), py::arg("output"),
      "A four-bar loop from its link lengths (m), closed forms (docs/design.md): {'grashof': "
      "'crank-rocker' | 'double-crank' | 'rocker-crank' | 'double-rocker' | 'change-point' | "
      "'triple-rocker', 'input_rotates', 'input_range' (dead positions, rad; None if it turns), "
      "'limit_extended', 'limit_folded' ((input, output) angles at the toggle positions, rad "
      "from the ground line; None where not reached), 'min_transmission', "
      "'max_transmission' (rad)}. Raises mo2d.Error for lengths that cannot close.");
  m.def(
      "transmission_angle",
      [](double ground, double input, double coupler, double output, double theta) {
        return transmission_angle({ground, input, coupler, output}, theta);
      },
      py::arg("ground"), py::arg("input"), py::arg("coupler"), py::arg("output"), py::arg("theta"),
      "The transmission angle (rad, in [0, pi]) of a four-bar at input angle theta (rad from "
      "the ground line), by the cosine law; NaN where the loop does not close.");
}

}  // namespace mo2d::py_bind
