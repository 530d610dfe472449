// mo2d.optimize (mo2d/optimize.hpp, docs/design.md "Optimization"): the parameters of a scene
// within bounds that minimize an expression of a run's summary values; the result as a dict.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mo2d/optimize.hpp"

namespace mo2d::py_bind {

namespace {

py::dict values(const std::vector<std::string>& names, const std::vector<double>& x) {
  py::dict d;
  for (std::size_t k = 0; k < names.size(); ++k) d[py::str(names[k])] = x[k];
  return d;
}

py::dict optimize(const std::string& scene, const std::string& minimize, const py::dict& vary,
                  const std::vector<std::string>& subject_to, const py::dict& set, int starts,
                  int max_evals, double xtol, std::uint64_t seed, bool measures, double max_seconds,
                  const py::object& progress) {
  OptimizeOptions o;
  o.scene = scene;
  o.minimize = minimize;
  o.subject_to = subject_to;
  o.starts = starts;
  o.max_evals = max_evals;
  o.xtol = xtol;
  o.seed = seed;
  o.measures = measures;
  o.max_seconds = max_seconds;
  for (const auto& [name, bounds] : vary) {
    const auto b = bounds.cast<std::pair<double, double>>();
    o.vary.push_back({name.cast<std::string>(), b.first, b.second});
  }
  for (const auto& [name, value] : set)
    o.set.push_back({name.cast<std::string>(), py::str(value).cast<std::string>()});
  if (!progress.is_none())
    o.progress = [&progress](const OptimizeProgress& p) {
      py::dict d;
      d["evaluation"] = p.evaluation;
      d["start"] = p.start;
      d["x"] = p.x;
      d["value"] = p.value;
      d["violation"] = p.violation;
      d["feasible"] = p.feasible;
      d["improved"] = p.improved;
      d["best"] = p.best;
      progress(d);
    };
  const OptimizeResult r = optimize_scene(o);
  py::dict d;
  d["x"] = values(r.names, r.x);
  d["value"] = r.value;
  d["constraints"] = r.constraints;
  d["feasible"] = r.feasible;
  d["method"] = r.method;
  d["stop"] = r.stop;
  d["evaluations"] = r.evaluations;
  py::list st;
  for (const OptimizeStart& s : r.starts) {
    py::dict e;
    e["x0"] = values(r.names, s.x0);
    e["x"] = values(r.names, s.x);
    e["value"] = s.value;
    e["violation"] = s.violation;
    e["evaluations"] = s.evaluations;
    e["status"] = s.status;
    st.append(e);
  }
  d["starts"] = st;
  d["warnings"] = r.warnings;
  py::dict params;
  for (const auto& [name, value] : r.parameters) params[py::str(name)] = value;
  d["parameters"] = params;
  d["scene_text"] = r.scene_text;
  d["wall_seconds"] = r.wall_seconds;
  d["cpu_seconds"] = r.cpu_seconds;
  return d;
}

}  // namespace

void bind_optimize(py::module_& m) {
  m.def("optimize", &optimize, py::arg("scene"), py::kw_only(), py::arg("minimize"),
        py::arg("vary"), py::arg("subject_to") = std::vector<std::string>{},
        py::arg("set") = py::dict(), py::arg("starts") = 1, py::arg("max_evals") = 200,
        py::arg("xtol") = 1e-6, py::arg("seed") = 1, py::arg("measures") = false,
        py::arg("max_seconds") = 0.0, py::arg("progress") = py::none(),
        "The parameters of a scene file within bounds that minimize an expression of a run's "
        "summary values, as `mo2d optimize` (docs/design.md, \"Optimization\"): NLopt's BOBYQA, "
        "or COBYLA with constraints, from `starts` starts (the scene's values, then points "
        "drawn with `seed`).\n\n"
        "scene: the scene file's path; minimize: an expression of the parameters and "
        "peak.COL, max.COL, min.COL, mean.COL, rms.COL, peak_to_peak.COL, "
        "energy_fluctuation.INPUT, flywheel.INPUT; vary: {name: (lo, hi)}; subject_to: "
        "['G <= H', 'G >= H', 'G' (G <= 0)]; set: fixed parameters {name: value}; max_evals: "
        "per start; xtol: of each range; measures: the frame's and bearings' columns; "
        "max_seconds: wall-time budget of the whole optimization (0: the scene's); progress: "
        "called after every run with a dict: evaluation, start, x, value, violation, feasible "
        "(every constraint within its tolerance), improved (the best so far), best.\n\n"
        "Returns a dict: x {name: best value}, value, constraints (G - H at x), feasible, "
        "method, stop ('converged', 'max_evals', 'max_seconds'), evaluations, starts, "
        "warnings, parameters (all of the scene's at x), scene_text (the scene file with the "
        "best values), wall_seconds, cpu_seconds. Raises mo2d.Error for bad input (an unknown "
        "parameter, lo >= hi, an expression with its column) or a run that fails.\n\n"
        "Example::\n\n"
        "    r = mo2d.optimize('mechanisms/fourbar_balance.yaml',\n"
        "                      minimize='rms.frame.shaking.F^2',\n"
        "                      vary={'m1': (0, 2), 'm3': (0, 3)})\n"
        "    r['x']  # {'m1': 0.7..., 'm3': 1.35...}");
}

}  // namespace mo2d::py_bind
