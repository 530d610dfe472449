// Step by step in Python: the forward workspace (ForwardData, mo2d/forward_data.hpp: the
// accelerations and multipliers at a state, the projection, the reactions), the inverse
// workspace (InverseData, one sample at a time: inverse_dynamics_sample) and the energies of a
// state and of a run (energy_balance). NumPy in, NumPy out (copies). The GIL is kept: the model
// may call Python laws.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <utility>

#include "bindings.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward_data.hpp"
#include "run_args.hpp"

namespace mo2d::py_bind {

namespace {

// A ForwardData with the model it was built for (the workspace holds a reference to it).
struct ForwardWorkspace {
  std::shared_ptr<Model> model;
  std::unique_ptr<ForwardData> data;
};

// A state given from Python must have the model's sizes (Eigen would assert otherwise).
void check_state(const Model& m, const VectorXd& q0, const VectorXd& q1) {
  if (q0.size() != m.n0 || q1.size() != m.n1)
    throw Error("state of '" + m.name + "': q0 has " + std::to_string(q0.size()) +
                    " values and q1 " + std::to_string(q1.size()) + ", the model has " +
                    std::to_string(m.n0) + " coordinates and " + std::to_string(m.n1) +
                    " quasi-velocities",
                m.name);
}

ForwardWorkspace make_forward(const std::shared_ptr<Model>& model, const std::string& integrator,
                              const std::string& formulation, const Motions& efforts,
                              const Params& params, double penalty) {
  ForwardOptions o;
  o.integrator = to_integrator(integrator);
  o.formulation = to_formulation(formulation);
  o.penalty = penalty;
  // the workspace shows its matrices (A, M, ...) as dense arrays: the dense path fills them
  o.linear_algebra = LinearAlgebra::dense;
  o.efforts = to_efforts(*model, efforts, params);
  return {model, std::make_unique<ForwardData>(*model, o)};
}

// a1 at (t, q0, q1): with the workspace's effort laws, or the efforts u given (one per input).
VectorXd accelerations(ForwardWorkspace& w, double t, const VectorXd& q0, const VectorXd& q1,
                       const std::optional<VectorXd>& efforts) {
  check_state(*w.model, q0, q1);
  if (!efforts) {
    w.data->accelerations(t, q0, q1, w.data->o.integrator == Integrator::baumgarte);
    return w.data->a;
  }
  if (efforts->size() != w.model->n_inputs())
    throw Error("efforts: " + std::to_string(w.model->n_inputs()) + " values expected (" +
                    std::to_string(efforts->size()) + " given)",
                w.model->name);
  return forward_accelerations(*w.model, *w.data, t, q0, q1, *efforts);
}

// The reactions at (t, q0, q1) with the workspace's effort laws: the accelerations there, then
// the least-squares multipliers of the joints (ForwardData::compute_reactions).
VectorXd reactions(ForwardWorkspace& w, double t, const VectorXd& q0, const VectorXd& q1) {
  accelerations(w, t, q0, q1, std::nullopt);
  w.data->compute_reactions(t, q0, q1);
  return w.data->reactions;
}

std::pair<VectorXd, VectorXd> project(ForwardWorkspace& w, double t, VectorXd q0, VectorXd q1,
                                      std::optional<double> tolerance) {
  check_state(*w.model, q0, q1);
  const double tol = tolerance.value_or(1e-12 * w.model->scale);
  w.data->project(t, q0, q1, tol, tol);
  return {std::move(q0), std::move(q1)};
}

void bind_forward_workspace(py::module_& m) {
  using W = ForwardWorkspace;
  py::class_<W>(m, "ForwardWorkspace",
                "The workspace of forward dynamics (ForwardData): accelerations, multipliers, "
                "projection and reactions at a state, one evaluation at a time")
      .def(py::init(&make_forward), py::arg("model"), py::arg("integrator") = "cvode_bdf",
           py::arg("formulation") = "augmented_lagrangian", py::arg("efforts") = Motions{},
           py::arg("params") = Params{}, py::arg("penalty") = 0.0)
      .def_property_readonly("model", [](const W& w) { return w.model; })
      .def("accelerations", &accelerations, py::arg("t"), py::arg("q0"), py::arg("q1"),
           py::arg("efforts") = py::none(),
           "a1 = d/dt q1 at the state (M a1 = f + B u - A^T lambda, A a1 = c)")
      .def("reactions", &reactions, py::arg("t"), py::arg("q0"), py::arg("q1"),
           "the joint reactions (Model.reaction_labels) at the state")
      .def("project", &project, py::arg("t"), py::arg("q0"), py::arg("q1"),
           py::arg("tolerance") = py::none(), "(q0, q1) projected on psi = 0 and A q1 = b")
      .def(
          "pivot_indicator",
          [](W& w, double t, const VectorXd& q0) {
            check_state(*w.model, q0, VectorXd::Zero(w.model->n1));
            return w.data->pivot_indicator(t, q0);
          },
          py::arg("t"), py::arg("q0"), "(sigma_min / sigma_max)^2 of the dimensionless A")
      .def_property_readonly("a", [](const W& w) { return w.data->a; })
      .def_property_readonly("multipliers", [](const W& w) { return w.data->lambda; })
      .def_property_readonly("efforts", [](const W& w) { return w.data->u; })
      .def_property_readonly("f", [](const W& w) { return w.data->f; })
      .def_property_readonly("Bu", [](const W& w) { return w.data->Bu; })
      .def_property_readonly("c", [](const W& w) { return w.data->c; })
      .def_property_readonly("A", [](const W& w) { return w.data->A; })
      .def_property_readonly("b", [](const W& w) { return w.data->b; })
      .def_property_readonly("M", [](const W& w) { return w.data->M; })
      .def_property_readonly("B", [](const W& w) { return w.data->B; })
      .def_property_readonly("accurate", [](const W& w) { return w.data->accel_ok; });
}

// An InverseData with its model (InverseData copies the prescribed motions).
struct InverseWorkspace {
  std::shared_ptr<Model> model;
  std::unique_ptr<InverseData> data;
};

InverseWorkspace make_inverse(const std::shared_ptr<Model>& model, const Motions& motion,
                              const Params& params, double position_tolerance,
                              const std::string& complement) {
  InverseOptions o;
  o.position_tolerance = position_tolerance;
  if (complement == "recursive")
    o.complement = ComplementMethod::recursive;
  else if (complement != "prescribed")
    throw Error("complement: 'prescribed' or 'recursive', not '" + complement + "'");
  const auto prescribed = to_motions(motion, params);
  return {model, std::make_unique<InverseData>(*model, prescribed, o)};
}

py::dict residuals(const InverseData& d) {
  py::dict r;
  r["position"] = d.residual_position;
  r["velocity"] = d.residual_velocity;
  r["acceleration"] = d.residual_acceleration;
  return r;
}

void bind_inverse_workspace(py::module_& m) {
  using W = InverseWorkspace;
  py::class_<W>(m, "InverseWorkspace",
                "The workspace of inverse dynamics (InverseData): solve(t) solves one sample")
      .def(py::init(&make_inverse), py::arg("model"), py::arg("motion"),
           py::arg("params") = Params{}, py::arg("position_tolerance") = 1e-12,
           py::arg("complement") = "prescribed")
      .def_property_readonly("model", [](const W& w) { return w.model; })
      .def(
          "solve", [](W& w, double t) { inverse_dynamics_sample(*w.model, *w.data, t); },
          py::arg("t"), "positions, velocities, accelerations, efforts and reactions at t")
      .def_property_readonly("t", [](const W& w) { return w.data->t; })
      .def_property_readonly("q0", [](const W& w) { return w.data->q0; })
      .def_property_readonly("q1", [](const W& w) { return w.data->q1; })
      .def_property_readonly("a1", [](const W& w) { return w.data->a1; })
      .def_property_readonly("efforts", [](const W& w) { return w.data->u; })
      .def_property_readonly("multipliers", [](const W& w) { return w.data->lambda; })
      .def_property_readonly("reactions", [](const W& w) { return w.data->reactions; })
      .def_property_readonly("friction", [](const W& w) { return w.data->friction; })
      .def_property_readonly("residuals", [](const W& w) { return residuals(*w.data); })
      .def_property_readonly("newton_iterations",
                             [](const W& w) { return w.data->newton_iterations; })
      .def_property_readonly("pivot_ratio", [](const W& w) { return w.data->pivot_ratio; })
      .def_property_readonly("warnings", [](W& w) {
        finish_inverse_warnings(*w.data);
        return w.data->warnings;
      });
}

void bind_energies(py::module_& m) {
  m.def(
      "energy_balance", [](const Result& r) { return energy_balance(r.trajectory); },
      py::arg("result"),
      "K + V - (K + V)(t0) - W_inputs - W_loads - W_constraints + D at every sample (J): the "
      "integration error of a forward run");
  m.def(
      "energy_balance_error", [](const Result& r) { return energy_balance_error(r.trajectory); },
      py::arg("result"), "max |energy_balance(result)|");
  m.def(
      "kinetic_energy",
      [](const Model& model, const VectorXd& q1) {
        check_state(model, model.q0, q1);
        return kinetic_energy(model, q1);
      },
      py::arg("model"), py::arg("q1"), "1/2 q1^T M q1");
  m.def(
      "potential_energy",
      [](const Model& model, const VectorXd& q0) {
        check_state(model, q0, VectorXd::Zero(model.n1));
        return potential_energy(model, q0);
      },
      py::arg("model"), py::arg("q0"), "gravity and linear springs");
}

}  // namespace

void bind_workspace(py::module_& m) {
  bind_forward_workspace(m);
  bind_inverse_workspace(m);
  bind_energies(m);
}

}  // namespace mo2d::py_bind
