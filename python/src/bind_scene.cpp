// Scene files in Python: load_scene(path, overrides), then inverse(scene) / forward(scene), run
// the way `mo2d inverse` and `mo2d forward` run them (apps/cmd_inverse.cpp, cmd_forward.cpp): the
// same checks, the same output columns, no files written. The GIL is released during a run.
#include <pybind11/stl.h>

#include <memory>
#include <utility>

#include "bindings.hpp"
#include "crosscheck_dict.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::py_bind {

namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

std::vector<ParameterOverride> to_overrides(const Overrides& set) {
  std::vector<ParameterOverride> out;
  for (const auto& [name, value] : set) out.push_back({name, value});
  return out;
}

std::shared_ptr<Model> scene_model(const Scene& s) {
  BuildOptions b;
  b.max_memory = s.run.max_memory;
  return std::make_shared<Model>(build_scene_model(s, b));
}

Result run_inverse(const Scene& scene) {
  auto model = scene_model(scene);
  if (static_cast<int>(scene.motion.size()) != model->dof)
    throw SceneError(Location{scene.file, 0, 0},
                     "inverse dynamics needs one prescribed motion per DOF: the model has " +
                         std::to_string(model->dof) + " DOF and 'motion' prescribes " +
                         std::to_string(scene.motion.size()));
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, *model, run);
  Trajectory r = inverse_dynamics(*model, scene.motion, run);
  add_output_columns(*model, r, scene.outputs);
  return make_result(std::move(model), std::move(r));
}

Result run_forward(const Scene& scene) {
  auto model = scene_model(scene);
  const ForwardOptions run = forward_options(scene, *model);
  check_scene_options(scene, *model, run);
  Trajectory r = forward_dynamics(*model, initial_state(scene, *model), run);
  add_output_columns(*model, r, scene.outputs);
  return make_result(std::move(model), std::move(r));
}

// The inverse cross-check of `mo2d crosscheck SCENE` (apps/cmd_crosscheck.cpp), without files.
CrosscheckReport run_crosscheck(const Scene& scene, double step) {
  const Model model = build_scene_model(scene);
  if (static_cast<int>(scene.motion.size()) != model.dof)
    throw SceneError(Location{scene.file, 0, 0},
                     "the cross-check drives the prescribed motion: the model has " +
                         std::to_string(model.dof) + " DOF and 'motion' prescribes " +
                         std::to_string(scene.motion.size()));
  CrosscheckOptions check;
  check.step = step;
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, model, run);
  return crosscheck_inverse(model, build_scene_model(scene, {.reduction = Reduction::none}),
                            scene.motion, run, check);
}

const char* solve_name(Solve s) {
  return s == Solve::inverse ? "inverse" : "forward";
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene",
                                            "A scene file, read and checked (mo2d.load_scene)")
      .def_readonly("file", &Scene::file)
      .def_readonly("name", &Scene::name)
      .def_property_readonly("parameters",
                             [](const Scene& s) {
                               py::dict d;
                               for (const auto& [k, v] : s.parameters) d[py::str(k)] = v;
                               return d;
                             })
      .def_property_readonly("solve", [](const Scene& s) { return solve_name(s.run.solve); })
      .def_property_readonly("t0", [](const Scene& s) { return s.run.t0; })
      .def_property_readonly("duration", [](const Scene& s) { return s.run.duration; })
      .def_property_readonly("samples", [](const Scene& s) { return s.run.samples; })
      .def("build_model", &scene_model, "the model of the scene (checks the labels it uses)")
      .def("__repr__",
           [](const Scene& s) { return "<mo2d.Scene '" + s.name + "' from " + s.file + ">"; });

  m.def(
      "_load_scene",
      [](const std::string& path, const Overrides& set) {
        const auto overrides = to_overrides(set);
        return std::make_shared<Scene>(load_scene(path, overrides));
      },
      py::arg("path"), py::arg("overrides") = Overrides{});
  m.def(
      "_parse_scene",
      [](const std::string& text, const std::string& file_name, const Overrides& set) {
        const auto overrides = to_overrides(set);
        return std::make_shared<Scene>(parse_scene(text, file_name, overrides));
      },
      py::arg("text"), py::arg("file_name") = "<scene>", py::arg("overrides") = Overrides{});
  m.def("inverse", &run_inverse, py::arg("scene"), py::call_guard<py::gil_scoped_release>(),
        "inverse dynamics of a scene, as `mo2d inverse` runs it (no files written)");
  m.def("forward", &run_forward, py::arg("scene"), py::call_guard<py::gil_scoped_release>(),
        "forward dynamics of a scene from its initial state, as `mo2d forward` runs it");
  m.def(
      "crosscheck",
      [](const Scene& scene, double step) {
        CrosscheckReport r;
        {
          py::gil_scoped_release release;
          r = run_crosscheck(scene, step);
        }
        return crosscheck_dict(r);
      },
      py::arg("scene"), py::arg("step") = 1.0 / 2000,
      "Box2D cross-check of the scene's inverse dynamics (mo2d crosscheck): a dict with agree, "
      "the worst relative errors, failures and the per-channel errors");
}

}  // namespace mo2d::py_bind
