// Runs of a System built in Python: build_model, inverse and forward dynamics, consistent
// states, the Box2D cross-checks. These keep the GIL (the model may call Python laws).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include "bindings.hpp"
#include "crosscheck_dict.hpp"
#include "laws.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/mo2d.hpp"
#include "run_args.hpp"

namespace mo2d::py_bind {

Integrator to_integrator(const std::string& s) {
  for (Integrator i :
       {Integrator::cvode_bdf, Integrator::cvode_adams, Integrator::rk4, Integrator::dopri5,
        Integrator::erk6, Integrator::erk8, Integrator::baumgarte})
    if (s == to_string(i)) return i;
  throw Error(
      "integrator: cvode_bdf, cvode_adams, rk4, dopri5, erk6, erk8 or baumgarte, not '" + s + "'",
      "integrator");
}

Formulation to_formulation(const std::string& s) {
  for (Formulation f :
       {Formulation::augmented_lagrangian, Formulation::lagrange, Formulation::null_space})
    if (s == to_string(f)) return f;
  throw Error("formulation: augmented_lagrangian, lagrange or null_space, not '" + s + "'",
              "formulation");
}

namespace {

// seconds from a Python number (int, float, NumPy scalar); another type is a TypeError naming it
double to_seconds(const py::object& value, const std::string& name) {
  const double v = PyFloat_AsDouble(value.ptr());
  if (v == -1.0 && PyErr_Occurred() != nullptr) {
    PyErr_Clear();
    throw py::type_error(name + ": a number of seconds, not " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  }
  return v;
}

}  // namespace

double end_time(const char* function, double t0, const py::object& duration, const py::object& t1,
                double default_duration) {
  const std::string f(function);
  if (!t1.is_none()) {
    if (!duration.is_none()) throw py::type_error(f + ": duration= or t1= (deprecated), not both");
    const std::string message = f +
                                "(t1=...) is deprecated: give duration= (s), the run ends at t0 + "
                                "duration (as run.duration of scene files and --duration)";
    if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0)
      throw py::error_already_set();
    return to_seconds(t1, f + ": t1");
  }
  if (duration.is_none()) {
    if (std::isnan(default_duration))
      throw py::type_error(f +
                           ": missing the argument duration (s): the run ends at t0 + duration");
    return t0 + default_duration;
  }
  return t0 + to_seconds(duration, f + ": duration");
}

int to_count(const py::object& value, const char* name) {
  if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
    throw py::type_error(std::string(name) + ": an integer, not " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  const py::int_ v = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!v) throw py::error_already_set();
  const py::int_ lo(std::numeric_limits<int>::min()), hi(std::numeric_limits<int>::max());
  if (v < lo || v > hi)
    throw Error(std::string(name) + " = " + py::repr(v).cast<std::string>() +
                    " is out of range: at most " + std::to_string(std::numeric_limits<int>::max()),
                name);
  return v.cast<int>();
}

std::vector<Prescribed> to_motions(const Motions& motion, const Params& params) {
  std::vector<Prescribed> out;
  for (const auto& [c, v] : motion) out.push_back(to_motion(c, v, params));
  return out;
}

// Efforts by input label ("crank_pivot.torque" -> law), ordered like Model::inputs.
EffortLaws to_efforts(const Model& m, const Motions& e, const Params& params) {
  EffortLaws out(m.inputs.size());
  const auto labels = m.input_labels();
  for (const auto& [label, v] : e) {
    const auto at = std::find(labels.begin(), labels.end(), label);
    if (at == labels.end()) throw Error("efforts: the model has no input '" + label + "'", label);
    out[static_cast<std::size_t>(at - labels.begin())] = to_law(v, params);
  }
  return out;
}

namespace {

using Pairs = std::vector<std::pair<std::string, double>>;
constexpr double kNoDefault = std::numeric_limits<double>::quiet_NaN();  // end_time: required

Reduction to_reduction(const std::string& s) {
  if (s == "flat") return Reduction::flat;
  if (s == "subsystems") return Reduction::subsystems;
  if (s == "none") return Reduction::none;
  throw Error("reduction: 'flat', 'subsystems' or 'none', not '" + s + "'", "reduction");
}

Result inverse(const std::shared_ptr<Model>& model, const Motions& motion, double t0,
               const py::object& duration, const py::object& samples, const Params& params,
               const std::string& complement, const py::object& t1) {
  InverseOptions o;
  o.t0 = t0;
  o.t1 = end_time("inverse_dynamics", t0, duration, t1, 1.0);
  o.samples = to_count(samples, "samples");
  if (complement == "recursive")
    o.complement = ComplementMethod::recursive;
  else if (complement != "prescribed")
    throw Error("complement: 'prescribed' or 'recursive', not '" + complement + "'");
  const std::vector<Prescribed> motions = to_motions(motion, params);
  Result out = make_result(model, inverse_dynamics(*model, motions, o));
  out.locate = [model, motions, o](const Trajectory& t) {
    return locate_extremes(*model, motions, o, t);
  };
  return out;
}

// stop_when(t, q0, q1) -> float of Python (None: none); the run stops where it changes sign.
std::function<double(double, const VectorXd&, const VectorXd&)> to_stop(const py::object& f) {
  if (f.is_none()) return {};
  if (!PyCallable_Check(f.ptr())) throw Error("stop_when: a callable (t, q0, q1) -> float");
  return
      [f](double t, const VectorXd& q0, const VectorXd& q1) { return f(t, q0, q1).cast<double>(); };
}

Result forward(const std::shared_ptr<Model>& model, const State& initial,
               const py::object& duration, const py::object& samples, const std::string& integrator,
               double rtol, double atol, double step, const Motions& efforts, const Params& params,
               double max_seconds, const std::string& formulation, const py::object& max_steps,
               const py::object& stop_when, const py::object& t1) {
  ForwardOptions o;
  o.t0 = initial.t;
  o.t1 = end_time("forward_dynamics", initial.t, duration, t1, kNoDefault);
  o.samples = to_count(samples, "samples");
  o.integrator = to_integrator(integrator);
  o.formulation = to_formulation(formulation);
  o.rtol = rtol;
  o.atol = atol;
  o.step = step;
  o.max_seconds = max_seconds;
  o.max_steps = to_count(max_steps, "max_steps");
  o.efforts = to_efforts(*model, efforts, params);
  o.stop_when = to_stop(stop_when);
  Result out = make_result(model, forward_dynamics(*model, initial, o));
  out.locate = [model, o](const Trajectory& t) { return locate_extremes(*model, o, t); };
  return out;
}

void bind_state(py::module_& m) {
  py::class_<State>(m, "State",
                    "A state of a model: the time t, the coordinates q0 and the quasi-velocities "
                    "q1. Made by mo2d.consistent_state (on the constraints); forward_dynamics "
                    "starts from one, a StateSpace's reference is one.")
      .def_readwrite("t", &State::t, "The time (s).")
      .def_readwrite("q0", &State::q0,
                     "The coordinates, a NumPy array in the order of Model.coordinate_labels "
                     "(m, rad).")
      .def_readwrite("q1", &State::q1,
                     "The quasi-velocities, a NumPy array in the order of Model.rate_labels "
                     "(m/s, rad/s).");
  m.def(
      "consistent_state",
      [](const Model& model, const Pairs& positions, const Pairs& velocities, double t0) {
        return consistent_state(model, {positions, velocities}, t0);
      },
      py::arg("model"), py::arg("positions") = Pairs{}, py::arg("velocities") = Pairs{},
      py::arg("t0") = 0.0,
      "A State on the constraints at time t0 (s), to start forward_dynamics from.\n\n"
      "positions: [(coordinate label, value)] held at the values given (m, rad), the other "
      "coordinates assembled from the model's initial configuration; velocities: [(rate "
      "label, value)], exactly dof independent ones (m/s, rad/s), the others solved. Raises "
      "mo2d.Error (naming the labels) when they cannot be met.\n\n"
      "Example::\n\n"
      "    x0 = mo2d.consistent_state(model, positions=[('link.angle', 0.2)],\n"
      "                               velocities=[('link.w', 1.0)])");
}

}  // namespace

void bind_runs(py::module_& m) {
  m.def(
      "build_model",
      [](const System& s, const std::string& reduction, bool assemble) {
        BuildOptions b;
        b.reduction = to_reduction(reduction);
        b.assemble = assemble;
        return std::make_shared<Model>(build_model(s, b));
      },
      py::arg("system"), py::arg("reduction") = "flat", py::arg("assemble") = true,
      "Build the Model of a System: flatten its subsystems, check every name, assemble the "
      "initial configuration and form the equations.\n\n"
      "reduction: 'flat' (the default: one set of equations), 'subsystems' (reduced per "
      "subsystem) or 'none' (no elimination; for inverse_dynamics_lagrange and "
      "crosscheck_forward); assemble=False keeps the written configuration as it is. Raises "
      "mo2d.Error naming the element at fault (an unknown label with the closest one).\n\n"
      "Example::\n\n"
      "    model = mo2d.build_model(s)\n"
      "    model.dof, model.input_labels");
  bind_state(m);
  m.def("inverse_dynamics", &inverse, py::arg("model"), py::arg("motion"), py::arg("t0") = 0.0,
        py::arg("duration") = py::none(), py::arg("samples") = py::int_(501),
        py::arg("params") = Params{}, py::arg("complement") = "prescribed", py::kw_only(),
        py::arg("t1") = py::none(),
        "Inverse dynamics: the efforts and reactions that drive a prescribed motion.\n\n"
        "motion: [(coordinate label, s(t))], one per degree of freedom; s an expression "
        "string of t or a callable returning (s, s', s'') (m or rad, and their derivatives)\n"
        "t0: s, the start\n"
        "duration: s (default 1); the run ends at t0 + duration\n"
        "samples: the number of samples, ends included\n"
        "params: {name: value}, constants of the expressions\n"
        "complement: 'prescribed' or 'recursive', how the efforts' orthogonal complement is "
        "formed\n"
        "t1: the end time, deprecated (use duration)\n\n"
        "Returns a mo2d.Result. Raises mo2d.Error naming the time and the element (a singular "
        "configuration, a motion that does not assemble).\n\n"
        "Example::\n\n"
        "    r = mo2d.inverse_dynamics(model, [('link.angle', '0.5 * sin(3 * t)')],\n"
        "                              duration=2, samples=201)\n"
        "    r['pivot.torque']");
  m.def("forward_dynamics", &forward, py::arg("model"), py::arg("initial"),
        py::arg("duration") = py::none(), py::arg("samples") = py::int_(101),
        py::arg("integrator") = "cvode_bdf", py::arg("rtol") = 1e-8, py::arg("atol") = 1e-10,
        py::arg("step") = 1e-3, py::arg("efforts") = Motions{}, py::arg("params") = Params{},
        py::arg("max_seconds") = kDefaultMaxSeconds,
        py::arg("formulation") = "augmented_lagrangian",
        py::arg("max_steps") = py::int_(kDefaultMaxSteps), py::arg("stop_when") = py::none(),
        py::kw_only(), py::arg("t1") = py::none(),
        "Forward dynamics: integrate the motion from a consistent state under the loads and "
        "efforts.\n\n"
        "initial: a mo2d.State to start from (mo2d.consistent_state)\n"
        "duration: s; the run ends at initial.t + duration\n"
        "samples: the output samples, ends included\n"
        "integrator: 'cvode_bdf', 'cvode_adams', 'rk4', 'dopri5', 'erk6', 'erk8' or "
        "'baumgarte'\n"
        "rtol, atol: the adaptive integrators' tolerances\n"
        "step: s; the fixed step of rk4 and baumgarte\n"
        "efforts: [(input label, law)], N m or N; a law as in mo2d.Law\n"
        "params: {name: value}, constants of the expressions\n"
        "max_seconds (s), max_steps: the run's budgets\n"
        "formulation: 'augmented_lagrangian', 'lagrange' or 'null_space'\n"
        "stop_when: f(t, q0, q1) -> float; the run stops where it changes sign "
        "(r.stats['stopped_by_event'])\n"
        "t1: the end time, deprecated (use duration)\n\n"
        "Returns a mo2d.Result with the energies. Raises mo2d.Error naming the time and the "
        "variable (a budget run out, a non-finite value).\n\n"
        "Example::\n\n"
        "    x0 = mo2d.consistent_state(model, velocities=[('link.w', 1.0)])\n"
        "    r = mo2d.forward_dynamics(model, x0, duration=1.0, integrator='rk4', step=1e-3)\n"
        "    r['energy.kinetic']");
  m.def(
      "crosscheck_inverse",
      [](const System& s, const Motions& motion, double t0, const py::object& duration, double step,
         const Params& params, const py::object& t1) {
        InverseOptions o;
        o.t0 = t0;
        o.t1 = end_time("crosscheck_inverse", t0, duration, t1, 1.0);
        CrosscheckOptions c;
        c.step = step;
        return crosscheck_dict(crosscheck_inverse(s, to_motions(motion, params), o, c));
      },
      py::arg("system"), py::arg("motion"), py::arg("t0") = 0.0, py::arg("duration") = py::none(),
      py::arg("step") = 1.0 / 2000, py::arg("params") = Params{}, py::kw_only(),
      py::arg("t1") = py::none(),
      "Cross-check the inverse dynamics of a System against Box2D (docs/crosscheck.md).\n\n"
      "motion: [(coordinate label, s(t))] as in inverse_dynamics; t0 (s); duration (s, "
      "default 1); step (s): Box2D's time step; params: constants of the expressions. t1: the "
      "end time, deprecated (use duration). Returns a dict with 'agree' (bool), the worst "
      "relative errors, 'failures' and the per-channel errors.");
  m.def(
      "crosscheck_forward",
      [](const Model& model, const State& initial, const py::object& duration, double step,
         const py::object& t1, double position_tolerance, double angle_tolerance) {
        CrosscheckOptions c;
        c.step = step;
        const double end = end_time("crosscheck_forward", initial.t, duration, t1, kNoDefault);
        return crosscheck_dict(crosscheck_forward(model, initial, end, c), position_tolerance,
                               angle_tolerance);
      },
      py::arg("model"), py::arg("initial"), py::arg("duration") = py::none(),
      py::arg("step") = 1.0 / 2000, py::kw_only(), py::arg("t1") = py::none(),
      py::arg("position_tolerance") = kForwardPositionTolerance,
      py::arg("angle_tolerance") = kForwardAngleTolerance,
      "Cross-check forward dynamics against Box2D from the state `initial` over duration (s) "
      "with Box2D's time step `step` (s); the model must be built with reduction='none'. t1: "
      "the end time, deprecated (use duration). Returns a dict with 'agree' (the largest "
      "centre-of-mass error relative to the size within position_tolerance and the largest "
      "body angle error within angle_tolerance, rad: the defaults of `mo2d crosscheck "
      "--forward`), 'box2d_cause' (why they disagree when Box2D is the cause, else ''), "
      "'branch_switch', 'notes', the largest and final errors and their time series.");
  bind_workspace(m);
  bind_extras(m);
}

}  // namespace mo2d::py_bind
