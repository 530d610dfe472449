// Scene files in Python: load_scene(path, overrides), then inverse(scene) / forward(scene), run
// the way `mo2d inverse` and `mo2d forward` run them (apps/cmd_inverse.cpp, cmd_forward.cpp): the
// same checks, the same output columns, no files written. The GIL is released during a run.
// Run settings given to a run (mo2d.forward(scene, duration=2), python/mo2d/_runs.py) are the
// command line's --duration 2: RunOverrides applied by parse_scene on top of the scene's run:
// block, so the same checks and the same messages ("--duration: run.duration: must be > 0 s").
#include <pybind11/stl.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include "bindings.hpp"
#include "crosscheck_dict.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/scene_sensitivity.hpp"

namespace mo2d::py_bind {

namespace {

std::vector<ParameterOverride> to_overrides(const Overrides& set) {
  std::vector<ParameterOverride> out;
  for (const auto& [name, value] : set) out.push_back({name, value});
  return out;
}

std::vector<RunOverride> to_run_overrides(const Overrides& run) {
  std::vector<RunOverride> out;
  for (const auto& [key, value] : run) out.push_back({key, value});
  return out;
}

std::shared_ptr<SourcedScene> parse_sourced(std::string text, const std::string& file_name,
                                            const Overrides& set, const Overrides& run) {
  auto s = std::make_shared<SourcedScene>();
  static_cast<Scene&>(*s) = parse_scene(text, file_name, to_overrides(set), to_run_overrides(run));
  s->text = std::move(text);
  s->set_overrides = set;
  s->run_overrides = run;
  return s;
}

std::shared_ptr<SourcedScene> load_sourced(const std::string& path, const Overrides& set,
                                           const Overrides& run) {
  std::ifstream in(path, std::ios::binary);
  if (!in) load_scene(path);  // throws load_scene's own error ("cannot open the scene file")
  std::ostringstream text;
  text << in.rdbuf();
  return parse_sourced(text.str(), path, set, run);
}

// The scene read again with `run` after its own run overrides (the later wins).
std::shared_ptr<SourcedScene> with_run(const SourcedScene& s, const Overrides& run) {
  Overrides all = s.run_overrides;
  all.insert(all.end(), run.begin(), run.end());
  return parse_sourced(s.text, s.file, s.set_overrides, all);
}

std::shared_ptr<Model> scene_model(const Scene& s) {
  BuildOptions b;
  b.max_memory = s.run.max_memory;
  return std::make_shared<Model>(build_scene_model(s, b));
}

Result run_inverse(const SourcedScene& scene, bool measures,
                   const std::vector<std::string>& sensitivity) {
  // with contacts: those closed at the start held closed (docs/contact.md, "Inverse dynamics")
  BuildOptions b;
  b.max_memory = scene.run.max_memory;
  ContactInverseModel held = scene_inverse_model(scene, b);
  auto model = std::make_shared<Model>(std::move(held.model));
  check_inverse_motion(scene, *model, held.contacts);
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, *model, run);
  Trajectory r;
  InverseSensitivity sens;
  if (sensitivity.empty()) {
    r = inverse_dynamics(*model, scene.motion, run);
  } else {  // exact derivatives (mo2d/sensitivity.hpp), the scene read again per parameter
    const std::vector<ParameterModels> p =
        scene_parameter_models(scene.text, scene, to_overrides(scene.set_overrides),
                               to_run_overrides(scene.run_overrides), sensitivity, *model, b, run);
    sens = inverse_dynamics_sensitivity(*model, scene.motion, run, p, r);
  }
  scene_inverse_contacts(scene, *model, held.contacts, run, r);
  add_output_columns(*model, r, scene.outputs);
  const Eigen::Index n = r.outputs.cols();  // the design columns follow (not located)
  const std::optional<DesignRequest> design = design_of(scene, measures);
  if (design) add_design_columns(*model, r, *design);
  if (!sensitivity.empty()) add_sensitivity_columns(r, sens);  // d(COLUMN)/d(NAME), not located
  Result out = make_result(model, std::move(r));
  out.design = design;
  out.contacts = std::move(held.contacts);
  out.scene_contacts = scene.contacts;
  out.locate = [model, motion = scene.motion, run, outputs = scene.outputs,
                n](const Trajectory& t) {
    return locate_extremes(*model, motion, run, first_outputs(t, n), outputs);
  };
  return out;
}

Result run_forward(const Scene& scene, bool measures) {
  auto model = scene_model(scene);
  const ForwardOptions run = forward_options(scene, *model);
  check_scene_options(scene, *model, run);
  SceneRun ran = scene_forward(scene, *model, initial_state(scene, *model), run);  // contacts
  Trajectory& r = ran.trajectory;
  add_output_columns(*model, r, scene.outputs);
  const Eigen::Index n = r.outputs.cols();  // the design columns follow (not located)
  const std::optional<DesignRequest> design = design_of(scene, measures);
  if (design) add_design_columns(*model, r, *design);
  Result out = make_result(model, std::move(r));
  out.design = design;
  out.events = std::move(ran.events);
  out.scene_contacts = scene.contacts;
  out.locate = [model, run, scene = std::make_shared<const Scene>(scene), n](const Trajectory& t) {
    return scene_forward_extremes(*scene, *model, run, first_outputs(t, n));
  };
  return out;
}

// The inverse cross-check of `mo2d crosscheck SCENE` (apps/cmd_crosscheck.cpp), without files.
CrosscheckReport run_crosscheck(const Scene& scene, double step) {
  refuse_contacts(scene,
                  "Python's mo2d.crosscheck (the command mo2d crosscheck compares a contact "
                  "scene with Box2D: docs/contact.md, \"Box2D\")");
  const Model model = build_scene_model(scene);
  if (static_cast<int>(scene.motion.size()) != model.dof)
    throw SceneError(Location{scene.file, 0, 0},
                     "the cross-check drives the prescribed motion: the model has " +
                         std::to_string(model.dof) + " DOF and 'motion' prescribes " +
                         std::to_string(scene.motion.size()));
  CrosscheckOptions check;
  check.step = step;
  check.max_steps = scene.run.max_steps;
  check.max_seconds = scene.run.max_seconds;
  check.max_memory = scene.run.max_memory;
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, model, run);
  return crosscheck_inverse(model, build_scene_model(scene, {.reduction = Reduction::none}),
                            scene.motion, run, check);
}

// The forward cross-check of `mo2d crosscheck SCENE` for a scene that solves forward
// (apps/cmd_crosscheck.cpp: forward_check): both engines from the scene's initial state, the
// scene's efforts and controllers in both, compared at its samples; the step refined unless given.
ForwardCrosscheck run_crosscheck_forward(const Scene& scene, double step, bool step_given) {
  refuse_contacts(scene,
                  "Python's mo2d.crosscheck (the command mo2d crosscheck compares a contact "
                  "scene with Box2D: docs/contact.md, \"Box2D\")");
  const Model model = build_scene_model(scene, {.reduction = Reduction::none});
  const State initial = initial_state(scene, model);
  const int samples = scene.run.samples > 0 ? scene.run.samples : 101;
  const EffortLaws efforts = forward_options(scene, build_scene_model(scene)).efforts;
  CrosscheckOptions check;
  check.step = step;
  check.refine_step = !step_given;
  check.max_steps = scene.run.max_steps;
  check.max_seconds = scene.run.max_seconds;
  check.max_memory = scene.run.max_memory;
  return crosscheck_forward(model, initial, scene.run.t0 + scene.run.duration, check, samples,
                            efforts);
}

const char* solve_name(Solve s) {
  return s == Solve::inverse ? "inverse" : "forward";
}

}  // namespace

void bind_run_settings(py::class_<SourcedScene, std::shared_ptr<SourcedScene>>& c) {
  c.def_property_readonly(
       "tolerance", [](const SourcedScene& s) { return s.run.tolerance; },
       "run.tolerance: the position tolerance of inverse dynamics' Newton solve (relative to "
       "the mechanism's size; `--tolerance`).")
      .def_property_readonly(
          "integrator", [](const SourcedScene& s) { return to_string(s.run.integrator); },
          "run.integrator of forward runs: 'cvode_bdf', 'cvode_adams', 'rk4', 'dopri5', 'erk6', "
          "'erk8' or 'baumgarte' (`--integrator`).")
      .def_property_readonly(
          "formulation", [](const SourcedScene& s) { return to_string(s.run.formulation); },
          "run.formulation of forward runs: 'augmented_lagrangian', 'lagrange' or 'null_space' "
          "(`--formulation`).")
      .def_property_readonly(
          "rtol", [](const SourcedScene& s) { return s.run.rtol; },
          "run.rtol: the relative tolerance of the adaptive integrators (`--rtol`).")
      .def_property_readonly(
          "atol", [](const SourcedScene& s) { return s.run.atol; },
          "run.atol: the absolute tolerance of the adaptive integrators, in the units of the "
          "state (`--atol`).")
      .def_property_readonly(
          "step", [](const SourcedScene& s) { return s.run.step; },
          "run.step (s): the fixed step of forward runs with rk4 or baumgarte (`--step`).")
      .def_property_readonly(
          "max_steps", [](const SourcedScene& s) { return s.run.max_steps; },
          "run.max_steps: the step budget of a forward run; a run that needs more stops with "
          "a mo2d.Error naming the time (`--max-steps`).")
      .def_property_readonly(
          "max_seconds", [](const SourcedScene& s) { return s.run.max_seconds; },
          "run.max_seconds: the wall-clock budget of a run (s; `--max-seconds`).")
      .def_property_readonly(
          "max_memory", [](const SourcedScene& s) { return s.run.max_memory; },
          "run.max_memory: the memory budget of a run's dense matrices and results (bytes; "
          "`--max-memory`).")
      .def_property_readonly(
          "run_overrides", [](const SourcedScene& s) { return s.run_overrides; },
          "The run settings given on top of the scene's run: block (list of (key, text)), in "
          "order (load_scene(run=...), mo2d.forward(scene, duration=...)).")
      .def("with_run", &with_run, py::arg("run"),
           "The scene read again (from its kept text) with these run settings on top of its "
           "own: run is a list of (key, text), e.g. [('duration', '2')], as `--duration 2`. "
           "Returns a new mo2d.Scene; raises mo2d.Error naming the flag for a bad value.");
}

void bind_scene(py::module_& m) {
  py::class_<SourcedScene, std::shared_ptr<SourcedScene>> c(
      m, "Scene",
      "A scene file, read and checked (mo2d.load_scene, mo2d.parse_scene; "
      "docs/scene-format.md).\n\n"
      "Its parameters, the settings of its run: block (read-only; give others to the runs: "
      "mo2d.forward(scene, duration=2)) and its model. The scene keeps its text: a file edited "
      "after load_scene is not read again.\n\n"
      "Example::\n\n"
      "    scene = mo2d.load_scene('mechanisms/fourbar.yaml', set={'a': 0.12})\n"
      "    scene.parameters['a'], scene.duration, scene.integrator\n"
      "    r = mo2d.inverse(scene)");
  c.def_readonly("file", &Scene::file,
                 "The path of the scene file (or the file_name given to parse_scene).")
      .def_readonly("name", &Scene::name, "The scene's name (its name: key; 'scene' without one).")
      .def_property_readonly(
          "parameters",
          [](const SourcedScene& s) {
            py::dict d;
            for (const auto& [k, v] : s.parameters) d[py::str(k)] = v;
            return d;
          },
          "The scene's parameters evaluated, after set= overrides: a dict {name: float}.")
      .def_property_readonly(
          "solve", [](const SourcedScene& s) { return solve_name(s.run.solve); },
          "run.solve: 'inverse' or 'forward', the run the scene asks for.")
      .def_property_readonly(
          "t0", [](const SourcedScene& s) { return s.run.t0; },
          "run.t0: the start time of the runs (s; `--t0`).")
      .def_property_readonly(
          "duration", [](const SourcedScene& s) { return s.run.duration; },
          "run.duration: the length of the runs (s); they end at t0 + duration "
          "(`--duration`).")
      .def_property_readonly(
          "samples", [](const SourcedScene& s) { return s.run.samples; },
          "run.samples: the number of samples of a run, ends included; 0: the default, 501 "
          "(inverse) or 101 (forward) (`--samples`).")
      .def(
          "build_model", [](const SourcedScene& s) { return scene_model(s); },
          "The mo2d.Model of the scene, as `mo2d info` builds it (checks the labels the scene "
          "uses; raises mo2d.Error with file:line:column).")
      .def("__repr__", [](const SourcedScene& s) {
        return "<mo2d.Scene '" + s.name + "' from " + s.file + ">";
      });
  bind_run_settings(c);

  m.def("_load_scene", &load_sourced, py::arg("path"), py::arg("overrides") = Overrides{},
        py::arg("run") = Overrides{});
  m.def(
      "_parse_scene",
      [](const std::string& text, const std::string& file_name, const Overrides& set,
         const Overrides& run) { return parse_sourced(text, file_name, set, run); },
      py::arg("text"), py::arg("file_name") = "<scene>", py::arg("overrides") = Overrides{},
      py::arg("run") = Overrides{});
  m.def(
      "_inverse",
      [](const SourcedScene& s, bool measures, const std::vector<std::string>& sensitivity) {
        return run_inverse(s, measures, sensitivity);
      },
      py::arg("scene"), py::arg("measures") = false,
      py::arg("sensitivity") = std::vector<std::string>{}, py::call_guard<py::gil_scoped_release>(),
      "inverse dynamics of a scene, as `mo2d inverse` runs it (no files written)");
  m.def(
      "_forward", [](const SourcedScene& s, bool measures) { return run_forward(s, measures); },
      py::arg("scene"), py::arg("measures") = false, py::call_guard<py::gil_scoped_release>(),
      "forward dynamics of a scene from its initial state, as `mo2d forward` runs it");
  m.def(
      "crosscheck",
      [](const SourcedScene& scene, const py::object& step, const py::object& forward,
         double position_tolerance, double angle_tolerance) {
        const bool step_given = !step.is_none();
        const double h = step_given ? step.cast<double>() : 1.0 / 2000;
        const bool fwd =
            forward.is_none() ? scene.run.solve == Solve::forward : forward.cast<bool>();
        if (fwd) {
          ForwardCrosscheck r;
          {
            py::gil_scoped_release release;
            r = run_crosscheck_forward(scene, h, step_given);
          }
          return crosscheck_dict(r, position_tolerance, angle_tolerance);
        }
        CrosscheckReport r;
        {
          py::gil_scoped_release release;
          r = run_crosscheck(scene, h);
        }
        return crosscheck_dict(r);
      },
      py::arg("scene"), py::arg("step") = py::none(), py::kw_only(),
      py::arg("forward") = py::none(), py::arg("position_tolerance") = kForwardPositionTolerance,
      py::arg("angle_tolerance") = kForwardAngleTolerance,
      "Cross-check a scene against Box2D, as `mo2d crosscheck` does: forward for a scene whose "
      "run solves forward (or forward=True), else inverse.\n\n"
      "Inverse: drives the scene's prescribed motion in a Box2D world stepped at `step` (s, "
      "default 1/2000) and compares the joint reactions and efforts; returns a dict with "
      "'agree' (bool), the worst relative errors, 'failures' and the per-channel errors and "
      "time series. Raises mo2d.Error when the motion does not prescribe every degree of "
      "freedom.\n\n"
      "Forward: both engines from the scene's initial state under its loads, efforts and "
      "controllers, compared at its samples (Box2D's step refined from 1/2000 s unless `step` "
      "is given); returns a dict with 'agree' (the largest centre-of-mass error relative to the "
      "size within position_tolerance, the largest body angle error within angle_tolerance, "
      "rad), 'box2d_cause', 'branch_switch', 'notes', and the errors and their time series.\n\n"
      "Example::\n\n"
      "    report = mo2d.crosscheck(mo2d.load_scene('mechanisms/fourbar.yaml'))\n"
      "    report['agree']");
}

}  // namespace mo2d::py_bind
