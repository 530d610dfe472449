// Model and Result in Python: a result's columns as NumPy arrays, under the labels of the CSV
// that mo2d inverse / forward write (r.columns is that header, r["crank.torque"] one column).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "bindings.hpp"
#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"

namespace mo2d::py_bind {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// One block of columns of a trajectory with its labels, in the order of the CSV.
struct Block {
  std::vector<std::string> labels;
  const MatrixXd* values;
};

std::vector<std::string> dotted(const std::vector<std::string>& labels) {
  std::vector<std::string> out;
  out.reserve(labels.size());
  for (const auto& l : labels) out.push_back(l + ".dot");
  return out;
}

// The energies of a forward run as one matrix (columns: kEnergyLabels), in the CSV's order.
const std::vector<std::string> kEnergyLabels = {"energy.kinetic", "energy.potential",
                                                "work.inputs",    "energy.dissipated",
                                                "work.loads",     "work.constraints"};
MatrixXd energies(const Trajectory& r) {
  MatrixXd e(r.time.size(), 6);
  if (!r.has_energies()) return MatrixXd(0, 6);
  e << r.kinetic, r.potential, r.input_work, r.dissipated, r.load_work, r.constraint_work;
  return e;
}

// Every column but t, block by block (energies are passed in: they are not stored as a matrix).
std::vector<Block> blocks(const Trajectory& r, const MatrixXd& e) {
  std::vector<Block> b = {{r.coordinate_labels, &r.q0},
                          {r.rate_labels, &r.q1},
                          {dotted(r.rate_labels), &r.a1},
                          {r.input_labels, &r.efforts},
                          {r.reaction_labels, &r.reactions}};
  if (r.has_energies()) b.push_back({kEnergyLabels, &e});
  b.push_back({r.residual_labels, &r.residuals});
  b.push_back({r.output_labels, &r.outputs});
  return b;
}

std::vector<std::string> columns(const Trajectory& r) {
  const MatrixXd e;
  std::vector<std::string> out{"t"};
  for (const auto& b : blocks(r, e)) out.insert(out.end(), b.labels.begin(), b.labels.end());
  return out;
}

// Column `label`; an unknown label is an Error naming it (with Trajectory's own suggestion for
// coordinates, efforts, reactions and outputs).
VectorXd column(const Trajectory& r, const std::string& label) {
  if (label == "t" || label == "time") return r.time;
  const MatrixXd e = energies(r);
  for (const auto& b : blocks(r, e))
    for (std::size_t k = 0; k < b.labels.size(); ++k)
      if (b.labels[k] == label) return b.values->col(static_cast<Eigen::Index>(k));
  throw Error("result: no column '" + label + "' (r.columns lists them)", label);
}

py::dict stats(const RunStats& s, const std::vector<std::string>& warnings) {
  py::dict d;
  d["cpu_seconds"] = s.cpu_seconds;
  d["warnings"] = warnings;
  d["steps"] = s.steps;
  d["rhs_evaluations"] = s.rhs_evaluations;
  d["factorizations"] = s.factorizations;
  d["projections"] = s.projections;
  d["error_test_failures"] = s.error_test_failures;
  d["solver_iterations"] = s.solver_iterations;
  d["regularized_evaluations"] = s.regularized_evaluations;
  d["stepped_over"] = s.stepped_over;
  d["stopped_by_event"] = s.stopped_by_event;
  d["t_end"] = s.t_end;
  d["min_pivot_ratio"] = s.min_pivot_ratio;
  d["max_drift"] = s.max_drift;
  d["linear_algebra"] = s.sparse ? "sparse" : "dense";
  // the a-posteriori estimate of the global error (forward runs; None: not estimated)
  const bool estimated = !std::isnan(s.estimated_error);
  d["estimated_error"] = estimated ? py::object(py::float_(s.estimated_error)) : py::none();
  d["estimated_error_t"] = estimated ? py::object(py::float_(s.estimated_error_t)) : py::none();
  d["estimated_error_variable"] = s.estimated_error_variable;
  d["error_estimate"] = s.error_estimate;
  d["estimate_cpu_seconds"] = s.estimate_cpu_seconds;
  return d;
}

void bind_model(py::module_& m) {
  py::class_<Model, std::shared_ptr<Model>>(
      m, "Model", "A mechanism ready to run (build_model, Scene.build_model)")
      .def_readonly("name", &Model::name)
      .def_readonly("dof", &Model::dof, "degrees of freedom at the initial configuration")
      .def_readonly("coordinate_labels", &Model::coordinate_labels)
      .def_readonly("rate_labels", &Model::rate_labels)
      .def_property_readonly("input_labels", &Model::input_labels)
      .def_property_readonly("reaction_labels", &Model::reaction_labels)
      .def_readonly("q0", &Model::q0, "initial (assembled) coordinates")
      .def_property_readonly("warnings", [](const Model& x) { return x.sketch.warnings; })
      .def("describe", &describe, "the text `mo2d info` prints")
      .def("__repr__", [](const Model& x) {
        return "<mo2d.Model '" + x.name + "': " + std::to_string(x.dof) + " DOF, " +
               std::to_string(x.coordinate_labels.size()) + " coordinates>";
      });
}

}  // namespace

Result make_result(std::shared_ptr<Model> model, Trajectory trajectory) {
  Result r;
  r.model = std::move(model);
  r.trajectory = std::move(trajectory);
  r.warnings = r.model->sketch.warnings;
  const auto& w = r.trajectory.stats.warnings;
  r.warnings.insert(r.warnings.end(), w.begin(), w.end());
  return r;
}

void bind_results(py::module_& m) {
  bind_model(m);
  py::class_<Result>(m, "Result",
                     "A run: NumPy arrays of its columns (r.t, r['crank.torque']), r.columns (the "
                     "CSV header), r.efforts / r.reactions (samples x labels), r.stats")
      .def_property_readonly("kind", [](const Result& r) { return to_string(r.trajectory.kind); })
      .def_property_readonly("model", [](const Result& r) { return r.model; })
      .def_property_readonly("t", [](const Result& r) { return r.trajectory.time; })
      .def_property_readonly("columns", [](const Result& r) { return columns(r.trajectory); })
      .def(
          "__getitem__",
          [](const Result& r, const std::string& label) { return column(r.trajectory, label); },
          "one column by label (any of r.columns)")
      .def("__contains__",
           [](const Result& r, const std::string& label) {
             const auto c = columns(r.trajectory);
             return std::find(c.begin(), c.end(), label) != c.end();
           })
      .def("__len__", [](const Result& r) { return r.trajectory.time.size(); })
      .def_property_readonly("q0", [](const Result& r) { return r.trajectory.q0; })
      .def_property_readonly("q1", [](const Result& r) { return r.trajectory.q1; })
      .def_property_readonly("a1", [](const Result& r) { return r.trajectory.a1; })
      .def_property_readonly("efforts", [](const Result& r) { return r.trajectory.efforts; })
      .def_property_readonly("effort_labels",
                             [](const Result& r) { return r.trajectory.input_labels; })
      .def_property_readonly("reactions", [](const Result& r) { return r.trajectory.reactions; })
      .def_property_readonly("reaction_labels",
                             [](const Result& r) { return r.trajectory.reaction_labels; })
      .def_property_readonly("residuals", [](const Result& r) { return r.trajectory.residuals; })
      .def_property_readonly("residual_labels",
                             [](const Result& r) { return r.trajectory.residual_labels; })
      .def_property_readonly("outputs", [](const Result& r) { return r.trajectory.outputs; })
      .def_property_readonly("output_labels",
                             [](const Result& r) { return r.trajectory.output_labels; })
      .def_property_readonly("stats",
                             [](const Result& r) { return stats(r.trajectory.stats, r.warnings); })
      .def_property_readonly("cpu_seconds",
                             [](const Result& r) { return r.trajectory.stats.cpu_seconds; })
      .def_property_readonly(
          "extremes",
          [](Result& r) {
            if (!r.locate)
              throw Error(
                  "extremes: located for the runs of mo2d.inverse / forward (scenes) and "
                  "inverse_dynamics / forward_dynamics only");
            if (!r.extremes) r.extremes = r.locate(r.trajectory);
            py::dict d;
            for (const Extreme& e : *r.extremes) {
              py::dict x;
              x["max"] = e.max;
              x["t_max"] = e.t_max;
              x["min"] = e.min;
              x["t_min"] = e.t_min;
              x["located"] = e.located_max && e.located_min;
              x["sampled_max"] = e.sampled_max;
              x["sampled_min"] = e.sampled_min;
              d[py::str(e.label)] = x;
            }
            return d;
          },
          "{label: {max, t_max, min, t_min, located, sampled_max, sampled_min}} of every effort, "
          "reaction and output column, located between the samples (computed on first read; "
          "mo2d/extremes.hpp)")
      .def_readonly("warnings", &Result::warnings)
      .def(
          "csv", [](const Result& r) { return trajectory_csv(r.trajectory); },
          "the CSV text mo2d inverse / forward writes")
      .def("__repr__", [](const Result& r) {
        return std::string("<mo2d.Result ") + to_string(r.trajectory.kind) + " of '" +
               r.model->name + "': " + std::to_string(r.trajectory.time.size()) + " samples>";
      });
}

}  // namespace mo2d::py_bind
