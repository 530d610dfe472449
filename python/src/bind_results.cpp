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
#include "model/suggest.hpp"

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

// Column `label`; an unknown label is a ColumnError naming it and the closest column (the
// suggestion of the scene loader, model/suggest.hpp).
VectorXd column(const Trajectory& r, const std::string& label) {
  if (label == "t" || label == "time") return r.time;
  const MatrixXd e = energies(r);
  for (const auto& b : blocks(r, e))
    for (std::size_t k = 0; k < b.labels.size(); ++k)
      if (b.labels[k] == label) return b.values->col(static_cast<Eigen::Index>(k));
  throw ColumnError("result: no column '" + label + "'" + did_you_mean(label, columns(r)) +
                        " (r.columns lists them)",
                    label);
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
      m, "Model",
      "A mechanism ready to run: its coordinates, quasi-velocities, inputs and equations.\n\n"
      "Made by mo2d.build_model(system) or Scene.build_model(); the runs (inverse_dynamics, "
      "forward_dynamics, linearize, ...) take it. A Result keeps the Model it was computed "
      "with.\n\n"
      "Example::\n\n"
      "    model = mo2d.build_model(system)\n"
      "    model.dof, model.coordinate_labels, model.input_labels\n"
      "    print(model.describe())")
      .def_readonly("name", &Model::name, "The name of the System (or scene) it was built from.")
      .def_readonly("dof", &Model::dof,
                    "Degrees of freedom at the initial configuration (an int): the number of "
                    "motions to prescribe in inverse dynamics.")
      .def_readonly("coordinate_labels", &Model::coordinate_labels,
                    "Labels of the coordinates q0 (list of str): node positions "
                    "'crank.A.x' (m), angles 'crank.angle' (rad), slides 'slide.q' (m), extra "
                    "coordinates; the order of q0 and of Result.q0's columns.")
      .def_readonly("rate_labels", &Model::rate_labels,
                    "Labels of the quasi-velocities q1 (list of str): 'crank.w' (rad/s), "
                    "'crank.A.vx' (m/s), 'slide.v' (m/s), ...; the order of q1 and Result.q1.")
      .def_property_readonly(
          "input_labels", &Model::input_labels,
          "Labels of the inputs (actuated joints), e.g. 'pivot.torque' (N m) or 'slide.force' "
          "(N): the columns of Result.efforts and the keys of efforts=[(label, law)].")
      .def_property_readonly(
          "reaction_labels", &Model::reaction_labels,
          "Labels of the reaction components, e.g. 'pivot.Fx', 'pivot.Fy' (N), 'slide.T' "
          "(N m): the columns of Result.reactions.")
      .def_readonly("q0", &Model::q0,
                    "The initial (assembled) coordinates, a NumPy array in the order of "
                    "coordinate_labels (m and rad).")
      .def_property_readonly(
          "warnings", [](const Model& x) { return x.sketch.warnings; },
          "Warnings of the build (list of str), e.g. sketched nodes moved far by the assembly.")
      .def("describe", &describe,
           "The description `mo2d info` prints (str): bodies, joints, coordinates, inputs, "
           "degrees of freedom.")
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
  py::class_<Result>(
      m, "Result",
      "A run (inverse or forward dynamics): its samples as NumPy arrays, one row per sample.\n\n"
      "r.t is the time (s); r['crank_pivot.torque'] any column of the CSV `mo2d inverse` / "
      "`forward` writes, by its label (r.columns lists them; an unknown label raises "
      "mo2d.ColumnError, a KeyError, with the closest label); r.efforts / r.reactions are "
      "samples x labels matrices; r.stats the run's statistics.\n\n"
      "Example::\n\n"
      "    r = mo2d.inverse(mo2d.load_scene('mechanisms/fourbar.yaml'))\n"
      "    r.t, r['crank_pivot.torque'], r.stats['cpu_seconds']\n"
      "    df = r.to_pandas()")
      .def_property_readonly(
          "kind", [](const Result& r) { return to_string(r.trajectory.kind); },
          "'inverse' or 'forward': the run that made it.")
      .def_property_readonly(
          "model", [](const Result& r) { return r.model; },
          "The mo2d.Model the run was computed with (kept alive by the result).")
      .def_property_readonly(
          "t", [](const Result& r) { return r.trajectory.time; },
          "The sample times (s), a NumPy array (a copy on each read); also r['t'].")
      .def_property_readonly(
          "columns", [](const Result& r) { return columns(r.trajectory); },
          "The labels of the columns (list of str), the CSV header: 't', the coordinates, the "
          "quasi-velocities, their derivatives ('.dot'), the efforts, the reactions, the "
          "energies (forward runs), the residuals and the outputs.")
      .def(
          "__getitem__",
          [](const Result& r, const std::string& label) { return column(r.trajectory, label); },
          py::arg("label"),
          "One column by its label (any of r.columns, or 'time'), a NumPy array of one value per "
          "sample. Raises mo2d.ColumnError (a KeyError and a mo2d.Error) for a label that is "
          "not a column, naming the closest one.")
      .def("__contains__",
           [](const Result& r, const std::string& label) {
             const auto c = columns(r.trajectory);
             return std::find(c.begin(), c.end(), label) != c.end();
           })
      .def("__len__", [](const Result& r) { return r.trajectory.time.size(); })
      .def_property_readonly(
          "q0", [](const Result& r) { return r.trajectory.q0; },
          "The coordinates at every sample: samples x Model.coordinate_labels (m, rad).")
      .def_property_readonly(
          "q1", [](const Result& r) { return r.trajectory.q1; },
          "The quasi-velocities at every sample: samples x Model.rate_labels (m/s, rad/s).")
      .def_property_readonly(
          "a1", [](const Result& r) { return r.trajectory.a1; },
          "The accelerations d/dt q1 at every sample: samples x Model.rate_labels (m/s^2, "
          "rad/s^2).")
      .def_property_readonly(
          "efforts", [](const Result& r) { return r.trajectory.efforts; },
          "The input efforts at every sample: samples x effort_labels (N m for torques, N for "
          "forces).")
      .def_property_readonly(
          "effort_labels", [](const Result& r) { return r.trajectory.input_labels; },
          "The labels of the columns of efforts (Model.input_labels), e.g. 'pivot.torque'.")
      .def_property_readonly(
          "reactions", [](const Result& r) { return r.trajectory.reactions; },
          "The joint reactions at every sample: samples x reaction_labels (N, N m).")
      .def_property_readonly(
          "reaction_labels", [](const Result& r) { return r.trajectory.reaction_labels; },
          "The labels of the columns of reactions, e.g. 'pivot.Fx', 'pivot.Fy'.")
      .def_property_readonly(
          "residuals", [](const Result& r) { return r.trajectory.residuals; },
          "The constraint residuals at every sample: samples x residual_labels, the infinity "
          "norms of psi (position), A q1 - b (velocity) and, where recorded, A a1 - c.")
      .def_property_readonly(
          "residual_labels", [](const Result& r) { return r.trajectory.residual_labels; },
          "The labels of the columns of residuals: 'residual.position', 'residual.velocity'[, "
          "'residual.acceleration'].")
      .def_property_readonly(
          "outputs", [](const Result& r) { return r.trajectory.outputs; },
          "The output columns of a scene run (its outputs: block, loads' powers, ...): samples "
          "x output_labels; empty for a System's runs.")
      .def_property_readonly(
          "output_labels", [](const Result& r) { return r.trajectory.output_labels; },
          "The labels of the columns of outputs, e.g. 'gas.power'.")
      .def_property_readonly(
          "stats", [](const Result& r) { return stats(r.trajectory.stats, r.warnings); },
          "The run's statistics, a dict: cpu_seconds, warnings, steps, rhs_evaluations, "
          "factorizations, projections, error_test_failures, stopped_by_event, t_end, "
          "max_drift, estimated_error (None: not estimated), ... (as the CLI's run summary).")
      .def_property_readonly(
          "cpu_seconds", [](const Result& r) { return r.trajectory.stats.cpu_seconds; },
          "The CPU time of the run (s); also r.stats['cpu_seconds'].")
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
      .def_property_readonly(
          "design", &design_dict,
          "The designer's measures of a scene run with a design: block or measures=True "
          "(docs/design.md): {'efforts': {input: {mean, rms, peak_to_peak, mean_speed, travel, "
          "energy_fluctuation, flywheel_inertia}}, 'four_bars': {name: {grashof, lengths, "
          "limit positions, transmission angles}}, 'speed_fluctuation'}; None otherwise. The "
          "columns (frame.shaking.Fx, J.load, L.transmission_angle, ...) are read as r[label].")
      .def_property_readonly(
          "events",
          [](const Result& r) {
            py::list out;
            for (const ContactEvent& e : r.events) {
              py::dict x;
              x["kind"] = contact_event_name(e.kind);
              x["t"] = e.t;
              x["contact"] = e.contact;
              x["speed"] = e.speed;
              x["speed_after"] = e.speed_after;
              x["impulse"] = e.impulse;
              x["energy_lost"] = e.energy_lost;
              x["predicted_t"] = e.predicted_t;
              out.append(x);
            }
            return out;
          },
          "The contact events of a scene run with contacts (docs/contact.md), in time order: a "
          "list of dicts {kind: 'onset' | 'exit' | 'impact' | 'lift_off' | 'zeno' | 'stick' | "
          "'slip' (friction), t (s), contact, speed (approach speed before, m/s), speed_after "
          "(impact: separation speed after; lift_off in an impact: its separation speed, m/s), "
          "impulse (N s), energy_lost (J, the whole "
          "impact's), predicted_t (Zeno: the accumulation time, s)}; [] otherwise.")
      .def_property_readonly(
          "contacts",
          [](const Result& r) {
            py::dict out;
            for (const InverseContact& c : r.contacts) {
              py::dict x;
              x["held"] = c.held;
              x["gap"] = c.gap;
              if (c.held) {
                x["column"] = c.column;
                x["min_force"] = c.min_force;
                x["t_min"] = c.t_min;
                x["t_negative"] = std::isnan(c.t_negative) ? py::object(py::none())
                                                           : py::object(py::float_(c.t_negative));
                x["preload"] = c.preload;
              } else {
                x["min_gap"] = c.min_gap;
                x["t_min_gap"] = c.t_min_gap;
              }
              out[py::str(c.name)] = x;
            }
            return out;
          },
          "The contacts of a scene's inverse run with contacts (docs/contact.md, \"Inverse "
          "dynamics\"): {name: {held, gap (m, at the start), and held: column (its normal "
          "force, r[column], N), min_force (N), t_min (s), t_negative (s: the first time the "
          "force is negative, the contact would open; None: never), preload (N: -min_force when "
          "negative, else 0); left out: min_gap (m), t_min_gap (s)}}; {} otherwise.")
      .def_readonly("warnings", &Result::warnings,
                    "The build (sketch) warnings, then the run's, as the command line prints "
                    "them (list of str).")
      .def(
          "csv", [](const Result& r) { return trajectory_csv(r.trajectory); },
          "The CSV text `mo2d inverse` / `mo2d forward` writes for this run (str), byte for "
          "byte.")
      .def("__repr__", [](const Result& r) {
        return std::string("<mo2d.Result ") + to_string(r.trajectory.kind) + " of '" +
               r.model->name + "': " + std::to_string(r.trajectory.time.size()) + " samples>";
      });
}

}  // namespace mo2d::py_bind
