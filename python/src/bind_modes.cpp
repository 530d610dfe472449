// Equilibria, linearization and vibration modes in Python (mo2d/modes.hpp, docs/linearization.md):
// linearize (about a state of a Model or a Scene, or along a forward or inverse Result),
// static_equilibrium, modes. The matrices are NumPy arrays with their labels. These keep the GIL
// (a Python-built model may call Python laws).
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <utility>

#include "bindings.hpp"
#include "laws.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/modes.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::py_bind {

namespace {

using Labels = std::vector<std::string>;
using Efforts = std::vector<std::pair<std::string, py::object>>;

// A model and the run settings of the call: from a Scene (its model, its effort laws and
// formulation, its initial state) or a Model (efforts given as [(input label, law)]).
struct Subject {
  std::shared_ptr<Model> model;
  ForwardOptions forward{};
  std::optional<State> start{};  // a forward scene's initial state
};

Subject subject_of(const py::object& x, const Efforts& efforts, const Params& params) {
  Subject s;
  if (py::isinstance<SourcedScene>(x)) {
    const Scene& scene = x.cast<const SourcedScene&>();
    BuildOptions b;
    b.max_memory = scene.run.max_memory;
    s.model = std::make_shared<Model>(build_scene_model(scene, b));
    s.forward = forward_options(scene, *s.model);
    if (scene.run.solve == Solve::forward) s.start = initial_state(scene, *s.model);
  } else if (py::isinstance<Model>(x)) {
    s.model = x.cast<std::shared_ptr<Model>>();
  } else {
    throw Error("expected a mo2d.Scene, a mo2d.Model or a mo2d.Result, got " +
                py::str(py::type::of(x)).cast<std::string>());
  }
  if (!efforts.empty()) {
    s.forward.efforts = EffortLaws(s.model->inputs.size());
    const auto labels = s.model->input_labels();
    for (const auto& [label, v] : efforts) {
      const auto at = std::find(labels.begin(), labels.end(), label);
      if (at == labels.end()) throw Error("efforts: the model has no input '" + label + "'", label);
      s.forward.efforts[static_cast<std::size_t>(at - labels.begin())] = to_law(v, params);
    }
  }
  return s;
}

LinearizeOptions options_of(const Subject& s, const Labels& coordinates, const Labels& velocities,
                            const Labels& outputs) {
  LinearizeOptions o;
  o.coordinates = coordinates;
  o.velocities = velocities;
  o.outputs = outputs;
  o.forward = s.forward;
  return o;
}

// linearize(x, state=None, ...): about a state (x a Model or Scene) or along a Result (a list).
py::object linearize_py(const py::object& x, const std::optional<State>& state,
                        const Labels& coordinates, const Labels& velocities, const Labels& outputs,
                        const Efforts& efforts, const Params& params,
                        const std::optional<std::shared_ptr<Scene>>& scene,
                        double min_conditioning) {
  if (py::isinstance<Result>(x)) {
    const auto& r = x.cast<const Result&>();
    const Subject s = subject_of(scene ? py::cast(*scene) : py::cast(r.model), efforts, params);
    LinearizeOptions o = options_of(s, coordinates, velocities, outputs);
    o.min_conditioning = min_conditioning;
    return py::cast(linearize_along(*r.model, r.trajectory, o));
  }
  const Subject s = subject_of(x, efforts, params);
  LinearizeOptions o = options_of(s, coordinates, velocities, outputs);
  State ref;
  if (state)
    ref = *state;
  else if (s.start)
    ref = *s.start;
  else
    ref = {s.forward.t0, s.model->q0, VectorXd::Zero(s.model->n1)};
  return py::cast(linearize(*s.model, ref, o));
}

Equilibrium equilibrium_py(const py::object& x, const std::optional<VectorXd>& q0, double t,
                           const Labels& coordinates, const Labels& outputs, const Efforts& efforts,
                           const Params& params, double tolerance, int max_iterations) {
  const Subject s = subject_of(x, efforts, params);
  EquilibriumOptions o;
  o.t = py::isinstance<Scene>(x) && t == 0 ? s.forward.t0 : t;
  o.tolerance = tolerance;
  o.max_iterations = max_iterations;
  o.linearize = options_of(s, coordinates, {}, outputs);
  const VectorXd start = q0 ? *q0 : s.start ? s.start->q0 : s.model->q0;
  return static_equilibrium(*s.model, start, o);
}

py::dict shape_of(const StateSpace& ss, const Mode& md) {
  py::dict d;
  for (int i = 0; i < ss.p && i < md.dz.size(); ++i) d[py::str(ss.states[i])] = md.dz[i];
  return d;
}

void bind_state_space(py::module_& m) {
  py::class_<Mode>(m, "Mode",
                   "A vibration mode: one eigenvalue of G (a complex pair once, Im > 0), its "
                   "frequencies, damping and shape (mo2d.modes, StateSpace.modes).\n\n"
                   "Example::\n\n"
                   "    for md in mo2d.modes(scene):\n"
                   "        print(md.hz, md.damping_ratio)")
      .def_readonly("eigenvalue", &Mode::eigenvalue, "The eigenvalue lambda of G (1/s), a complex.")
      .def_readonly("omega_n", &Mode::omega_n, "The natural frequency |lambda| (rad/s).")
      .def_readonly("omega_d", &Mode::omega_d, "The damped frequency |Im lambda| (rad/s).")
      .def_readonly("hz", &Mode::hz, "The natural frequency omega_n / (2 pi) (Hz).")
      .def_readonly("damping_ratio", &Mode::damping_ratio,
                    "The damping ratio -Re lambda / |lambda| (1 for a real negative lambda, -1 "
                    "for a real positive one: unstable).")
      .def_readonly("oscillatory", &Mode::oscillatory, "True when Im lambda != 0.")
      .def_readonly("rigid", &Mode::rigid,
                    "True when |lambda| is about 0: a rigid-body or drift motion, not a "
                    "vibration.")
      .def_readonly("x", &Mode::x, "the eigenvector in the states")
      .def_readonly("dz", &Mode::dz, "the real position shape, largest component 1")
      .def_readonly("dq0", &Mode::dq0, "dq0/dz dz: every coordinate (every node)")
      .def("__repr__", [](const Mode& md) {
        return "<mo2d.Mode omega_n=" + std::to_string(md.omega_n) +
               " rad/s, zeta=" + std::to_string(md.damping_ratio) + ">";
      });
  py::class_<StateSpace>(m, "StateSpace",
                         "A linear model dx/dt = G x + H u, y = C x + D u about a reference "
                         "state (mo2d.linearize; docs/linearization.md).\n\n"
                         "x = (z, w): p independent coordinates then dof quasi-velocities, "
                         "deviations from the reference; u the efforts, y the outputs.\n\n"
                         "Example::\n\n"
                         "    ss = mo2d.linearize(model)\n"
                         "    ss.G, ss.states, [md.hz for md in ss.modes]")
      .def_readonly("t", &StateSpace::t, "The time of the reference (s).")
      .def_readonly("G", &StateSpace::G, "The state matrix (n x n, NumPy), n = p + dof.")
      .def_readonly("H", &StateSpace::H, "The input matrix (n x inputs).")
      .def_readonly("C", &StateSpace::C, "The output matrix (outputs x n).")
      .def_readonly("D", &StateSpace::D, "The feedthrough matrix (outputs x inputs).")
      .def_readonly("states", &StateSpace::states,
                    "The labels of the states x: p coordinate labels, then dof rate labels.")
      .def_readonly("inputs", &StateSpace::inputs,
                    "The labels of the inputs u (Model.input_labels).")
      .def_readonly("outputs", &StateSpace::outputs,
                    "The labels of the outputs y (the outputs= asked for).")
      .def_readonly("p", &StateSpace::p, "The number of position states (coordinates z).")
      .def_readonly("dof", &StateSpace::dof, "The number of velocity states (quasi-velocities w).")
      .def_readonly("drift", &StateSpace::drift, "dx/dt at the reference (0 at an equilibrium)")
      .def_readonly("u", &StateSpace::u, "the reference efforts")
      .def_readonly("dq0_dz", &StateSpace::dq0_dz,
                    "The tangent basis of the positions (coordinates x p): how every "
                    "coordinate moves with z.")
      .def_readonly("dq1_dw", &StateSpace::dq1_dw,
                    "The basis of the velocities (quasi-velocities x dof): q1 = dq1_dw w at fixed "
                    "position.")
      .def_readonly("dq1_dz", &StateSpace::dq1_dz,
                    "How the quasi-velocities change with the position z at fixed w "
                    "(quasi-velocities x p).")
      .def_readonly("conditioning", &StateSpace::conditioning,
                    "How well the chosen coordinates parametrize the state here: 1 ideal, 0 "
                    "singular (the smaller smallest singular value of the two tangent bases).")
      .def_readonly("approximate", &StateSpace::approximate,
                    "What was differenced numerically rather than derived exactly (str; '' when "
                    "nothing).")
      .def_property_readonly(
          "reference",
          [](const StateSpace& ss) {
            return State{ss.t, ss.q0, ss.q1};
          },
          "the reference state (t, q0, q1)")
      .def_property_readonly(
          "x",
          [](const StateSpace& ss) {
            return independent_state(ss, {ss.t, ss.q0, ss.q1});
          },
          "the reference in the states")
      .def_property_readonly(
          "modes", [](const StateSpace& ss) { return vibration_modes(ss); },
          "The vibration modes of G (list of mo2d.Mode): oscillatory ones by ascending "
          "omega_n, then the real ones.")
      .def(
          "shape", [](const StateSpace& ss, const Mode& md) { return shape_of(ss, md); },
          py::arg("mode"), "a mode's dz as {state label: value}")
      .def("csv", &state_space_csv, py::arg("matrix"),
           "One matrix ('G', 'H', 'C' or 'D') as the CSV text `mo2d linearize` writes: a header "
           "of the column labels, one row per row label, 17 significant digits.")
      .def(
          "json", [](const StateSpace& ss) { return state_space_json(ss, vibration_modes(ss)); },
          "the JSON `mo2d linearize` writes")
      .def("__repr__", [](const StateSpace& ss) {
        return "<mo2d.StateSpace at t=" + std::to_string(ss.t) + ": " + std::to_string(ss.n()) +
               " states, " + std::to_string(ss.inputs.size()) + " inputs>";
      });
  py::class_<Equilibrium>(m, "Equilibrium",
                          "A static equilibrium (mo2d.static_equilibrium): the state at rest, "
                          "how it converged, its stiffness, stability and linearization.\n\n"
                          "Example::\n\n"
                          "    eq = mo2d.static_equilibrium(scene)\n"
                          "    eq.stability, eq.state.q0, eq.modes[0].hz")
      .def_readonly("state", &Equilibrium::state, "The state at rest (a mo2d.State, q1 = 0).")
      .def_readonly("iterations", &Equilibrium::iterations, "The Newton iterations taken.")
      .def_readonly("residual", &Equilibrium::residual,
                    "|E a1| at the end: the accelerations left (m/s^2 and rad/s^2 mixed).")
      .def_readonly("moved", &Equilibrium::moved,
                    "The largest coordinate change from the start (m or rad).")
      .def_readonly("linear", &Equilibrium::linear, "The StateSpace about the equilibrium.")
      .def_readonly("stiffness", &Equilibrium::stiffness,
                    "The reduced stiffness Kr = -Mr G21 (p x p): the Hessian of the potential "
                    "in the coordinates z for conservative loads.")
      .def_readonly("reduced_mass", &Equilibrium::reduced_mass,
                    "The reduced mass Mr = dq1_dw^T M dq1_dw (dof x dof).")
      .def_readonly("stiffness_eigenvalues", &Equilibrium::stiffness_eigenvalues,
                    "The eigenvalues of (Kr + Kr^T) / 2, ascending (all > 0: stable).")
      .def_readonly("asymmetry", &Equilibrium::asymmetry,
                    "|Kr - Kr^T| / |Kr|: non-zero for follower loads or feedback.")
      .def_readonly("stability", &Equilibrium::stability, "'stable', 'unstable' or 'neutral'.")
      .def_property_readonly(
          "modes", [](const Equilibrium& e) { return vibration_modes(e.linear); },
          "The vibration modes about the equilibrium (list of mo2d.Mode), as `mo2d modes`.")
      .def("__repr__", [](const Equilibrium& e) {
        return "<mo2d.Equilibrium " + e.stability + ", " + std::to_string(e.iterations) +
               " iterations>";
      });
}

}  // namespace

void bind_modes(py::module_& m) {
  bind_state_space(m);
  m.def("linearize", &linearize_py, py::arg("x"), py::arg("state") = py::none(),
        py::arg("coordinates") = Labels{}, py::arg("velocities") = Labels{},
        py::arg("outputs") = Labels{}, py::arg("efforts") = Efforts{}, py::arg("params") = Params{},
        py::arg("scene") = py::none(), py::arg("min_conditioning") = 1e-3,
        "Linearize a mechanism: dx/dt = G x + H u, y = C x + D u.\n\n"
        "x a Model or a Scene: the StateSpace about `state` (a mo2d.State; default: a forward "
        "scene's initial state, else the model's configuration at rest). x a Result: a list of "
        "StateSpace, one per sample, all in the same coordinates; give the run's effort laws "
        "(scene= the scene it ran, or efforts=), checked against the run's; min_conditioning: "
        "the least conditioning of the coordinates allowed along it. coordinates, velocities: "
        "the state's labels to use (default: chosen by pivoting); outputs: output labels for "
        "y; efforts: [(input label, law)]; params: constants of the expressions. Raises "
        "mo2d.Error naming the time and the coordinates (a singular configuration, coordinates "
        "that stop parametrizing the motion).\n\n"
        "Example::\n\n"
        "    ss = mo2d.linearize(mo2d.load_scene('mechanisms/pendulum.yaml'))\n"
        "    ss.G, ss.modes[0].omega_n");
  m.def("static_equilibrium", &equilibrium_py, py::arg("x"), py::arg("q0") = py::none(),
        py::arg("t") = 0.0, py::arg("coordinates") = Labels{}, py::arg("outputs") = Labels{},
        py::arg("efforts") = Efforts{}, py::arg("params") = Params{}, py::arg("tolerance") = 1e-10,
        py::arg("max_iterations") = 50,
        "The static equilibrium of a Model or Scene nearest q0 (default: the scene's initial "
        "configuration, or the model's), by Newton on the reduced equations at rest.\n\n"
        "t (s): the time of the loads; coordinates, outputs, efforts, params: as in "
        "linearize; tolerance: on the accelerations, relative to gravity; max_iterations: "
        "Newton's budget. Returns a mo2d.Equilibrium with its stiffness, stability and "
        "linearization. Raises mo2d.Error (with the residual and the iterations) where it "
        "does not converge.\n\n"
        "Example::\n\n"
        "    eq = mo2d.static_equilibrium(model)\n"
        "    eq.stability, eq.stiffness");
  m.def(
      "modes",
      [](const py::object& x, const Labels& coordinates, const Efforts& efforts,
         const Params& params) {
        if (py::isinstance<StateSpace>(x)) return vibration_modes(x.cast<const StateSpace&>());
        if (py::isinstance<Equilibrium>(x))
          return vibration_modes(x.cast<const Equilibrium&>().linear);
        return vibration_modes(
            equilibrium_py(x, std::nullopt, 0.0, coordinates, {}, efforts, params, 1e-10, 50)
                .linear);
      },
      py::arg("x"), py::arg("coordinates") = Labels{}, py::arg("efforts") = Efforts{},
      py::arg("params") = Params{},
      "The vibration modes (list of mo2d.Mode) of a StateSpace or an Equilibrium, or of a "
      "Model / Scene at its static equilibrium, as `mo2d modes`: oscillatory ones by "
      "ascending omega_n, then the real ones. coordinates, efforts, params: as in "
      "static_equilibrium.\n\n"
      "Example::\n\n"
      "    [md.hz for md in mo2d.modes(mo2d.load_scene('mechanisms/pendulum.yaml'))]");
}

}  // namespace mo2d::py_bind
