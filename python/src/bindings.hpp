#pragma once
// The Python module mo2d._mo2d (pybind11): one bind_* function per part of the API, called in this
// order by module.cpp. The pure-Python package python/mo2d/ re-exports it and adds the sweeps.
//
// Ownership: a Result keeps the Model it was computed with (shared_ptr), so a Python script may
// render or query a result after dropping its model. Models built from a Python System may hold
// Python callables (laws): every call that evaluates them keeps the GIL; the scene runs (no Python
// code inside) release it.
#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/extremes.hpp"
#include "mo2d/model.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::py_bind {

namespace py = pybind11;

using Overrides = std::vector<std::pair<std::string, std::string>>;

// mo2d.Scene: a Scene with the text, the parameter and the run overrides it was read with, so
// that a run with other settings reads the same text again (a file edited since is not read
// again). bind_scene.cpp.
struct SourcedScene : Scene {
  std::string text{};
  Overrides set_overrides{}, run_overrides{};  // Scene::run: the settings they give
};

// The result of a run with the model that produced it and the warnings of the build.
struct Result {
  std::shared_ptr<Model> model{};
  Trajectory trajectory{};
  std::vector<std::string> warnings{};  // build warnings (sketch), then the run's
  // Scene runs: locate_extremes of the run (mo2d/extremes.hpp), called on the first read of
  // Result.extremes (a sweep that does not read them does not pay for them); its result.
  std::function<std::vector<Extreme>(const Trajectory&)> locate{};
  std::optional<std::vector<Extreme>> extremes{};
  // Scene runs with a design: block or measures=True: what add_design_columns added (the
  // columns are in trajectory.outputs); Result.design summarizes the run with it.
  std::optional<DesignRequest> design{};
  // Scene runs with contacts: the contact events in time order (Result.events)
  std::vector<ContactEvent> events{};
  // Scene inverse runs with contacts: each contact, held closed or left out (Result.contacts)
  std::vector<InverseContact> contacts{};
  // Scene runs: the scene's contacts, which its frames and animations draw
  std::vector<ContactDef> scene_contacts{};
};

// A label that is not a column of a result (r["pivot.torq"]): raised as mo2d.ColumnError, a
// subclass of both mo2d.Error and KeyError, whose message names the closest column ("did you
// mean", model/suggest.hpp, as the scene loader suggests).
struct ColumnError : Error {
  using Error::Error;
};

// mo2d.Error (a subclass of Exception) and the translation of mo2d::Error, SceneError and
// ExpressionError into it, with the attributes element, time, file, line, column; ColumnError
// into mo2d.ColumnError.
void bind_errors(py::module_& m);
void bind_interrupts();              // Ctrl-C during a run: KeyboardInterrupt (module.cpp)
void bind_results(py::module_& m);   // Model, Result
void bind_scene(py::module_& m);     // Scene, load_scene, inverse, forward, crosscheck
void bind_system(py::module_& m);    // System, Law, Motion, build_model, runs
void bind_render(py::module_& m);    // frames, filmstrips, plots to PNG/SVG/PDF
void bind_view(py::module_& m);      // the viewer page, _repr_html_ and _repr_svg_ (bind_view.cpp)
void bind_modes(py::module_& m);     // StateSpace, Mode, Equilibrium, linearize, modes
void bind_design(py::module_& m);    // four_bar, transmission_angle (bind_design.cpp)
void bind_optimize(py::module_& m);  // optimize (bind_optimize.cpp; with NLopt)
// A scene's design request: its design: block, with measures also the frame and bearing loads;
// none when neither is asked for.
std::optional<DesignRequest> design_of(const Scene& scene, bool measures);
// r with only its first n output columns (the scene's, without the design columns that follow).
Trajectory first_outputs(const Trajectory& r, Eigen::Index n);
// Result.design: the summary of the run's design measures (dict), None without a request.
py::object design_dict(const Result& r);

// A Result from a finished run (adds the model's build warnings in front of the run's).
Result make_result(std::shared_ptr<Model> model, Trajectory trajectory);

}  // namespace mo2d::py_bind
