// Runs of a System built in Python: build_model, inverse and forward dynamics, consistent
// states, the Box2D cross-checks. These keep the GIL (the model may call Python laws).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

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

Reduction to_reduction(const std::string& s) {
  if (s == "flat") return Reduction::flat;
  if (s == "subsystems") return Reduction::subsystems;
  if (s == "none") return Reduction::none;
  throw Error("reduction: 'flat', 'subsystems' or 'none', not '" + s + "'", "reduction");
}

Result inverse(const std::shared_ptr<Model>& model, const Motions& motion, double t0, double t1,
               const py::object& samples, const Params& params, const std::string& complement) {
  InverseOptions o;
  o.t0 = t0;
  o.t1 = t1;
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

Result forward(const std::shared_ptr<Model>& model, const State& initial, double t1,
               const py::object& samples, const std::string& integrator, double rtol, double atol,
               double step, const Motions& efforts, const Params& params, double max_seconds,
               const std::string& formulation, const py::object& max_steps,
               const py::object& stop_when) {
  ForwardOptions o;
  o.t0 = initial.t;
  o.t1 = t1;
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
  py::class_<State>(m, "State", "A consistent state: t, q0 (coordinates), q1 (quasi-velocities)")
      .def_readwrite("t", &State::t)
      .def_readwrite("q0", &State::q0)
      .def_readwrite("q1", &State::q1);
  m.def(
      "consistent_state",
      [](const Model& model, const Pairs& positions, const Pairs& velocities, double t0) {
        return consistent_state(model, {positions, velocities}, t0);
      },
      py::arg("model"), py::arg("positions") = Pairs{}, py::arg("velocities") = Pairs{},
      py::arg("t0") = 0.0,
      "positions held at the given values, the others assembled; exactly dof velocities given");
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
      py::arg("system"), py::arg("reduction") = "flat", py::arg("assemble") = true);
  bind_state(m);
  m.def("inverse_dynamics", &inverse, py::arg("model"), py::arg("motion"), py::arg("t0") = 0.0,
        py::arg("t1") = 1.0, py::arg("samples") = py::int_(501), py::arg("params") = Params{},
        py::arg("complement") = "prescribed",
        "motion: [(coordinate, expression of t or callable -> (s, s', s''))], one per DOF");
  m.def(
      "forward_dynamics", &forward, py::arg("model"), py::arg("initial"), py::arg("t1"),
      py::arg("samples") = py::int_(101), py::arg("integrator") = "cvode_bdf",
      py::arg("rtol") = 1e-8, py::arg("atol") = 1e-10, py::arg("step") = 1e-3,
      py::arg("efforts") = Motions{}, py::arg("params") = Params{},
      py::arg("max_seconds") = kDefaultMaxSeconds, py::arg("formulation") = "augmented_lagrangian",
      py::arg("max_steps") = py::int_(kDefaultMaxSteps), py::arg("stop_when") = py::none(),
      "efforts: [(input label, law)]; integrator: cvode_bdf, cvode_adams, rk4, dopri5, erk6, erk8, "
      "baumgarte; "
      "stop_when(t, q0, q1) -> float: the run stops where it changes sign");
  m.def(
      "crosscheck_inverse",
      [](const System& s, const Motions& motion, double t0, double t1, double step,
         const Params& params) {
        InverseOptions o;
        o.t0 = t0;
        o.t1 = t1;
        CrosscheckOptions c;
        c.step = step;
        return crosscheck_dict(crosscheck_inverse(s, to_motions(motion, params), o, c));
      },
      py::arg("system"), py::arg("motion"), py::arg("t0") = 0.0, py::arg("t1") = 1.0,
      py::arg("step") = 1.0 / 2000, py::arg("params") = Params{});
  m.def(
      "crosscheck_forward",
      [](const Model& model, const State& initial, double t1, double step) {
        CrosscheckOptions c;
        c.step = step;
        return crosscheck_dict(crosscheck_forward(model, initial, t1, c));
      },
      py::arg("model"), py::arg("initial"), py::arg("t1"), py::arg("step") = 1.0 / 2000,
      "model built with reduction='none'");
  bind_workspace(m);
  bind_extras(m);
}

}  // namespace mo2d::py_bind
