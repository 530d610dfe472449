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
                "The workspace of forward dynamics (ForwardData): the accelerations, multipliers, "
                "projection and reactions at a state, one evaluation at a time.\n\n"
                "The equations are M a1 = f + B u - A^T lambda, A a1 = c; after a call to "
                "accelerations, the properties (a, multipliers, M, A, ...) are those of that "
                "state (NumPy copies).\n\n"
                "Example::\n\n"
                "    ws = mo2d.ForwardWorkspace(model, efforts=[('pivot.torque', '0.3 * t')])\n"
                "    a1 = ws.accelerations(0.0, model.q0, np.zeros(len(model.rate_labels)))\n"
                "    ws.multipliers")
      .def(py::init(&make_forward), py::arg("model"), py::arg("integrator") = "cvode_bdf",
           py::arg("formulation") = "augmented_lagrangian", py::arg("efforts") = Motions{},
           py::arg("params") = Params{}, py::arg("penalty") = 0.0,
           "A workspace for `model`: integrator and formulation as in forward_dynamics (the "
           "integrator matters for 'baumgarte', whose feedback enters c); efforts: [(input "
           "label, law)] used when accelerations() is given no efforts; params: constants of "
           "the expressions; penalty: the augmented-Lagrangian penalty (0: the default, 1e7 of "
           "the mass scale).")
      .def_property_readonly(
          "model", [](const W& w) { return w.model; }, "The mo2d.Model of the workspace.")
      .def("accelerations", &accelerations, py::arg("t"), py::arg("q0"), py::arg("q1"),
           py::arg("efforts") = py::none(),
           "The accelerations a1 = d/dt q1 (m/s^2, rad/s^2) at the state (t (s), q0, q1), "
           "solving M a1 = f + B u - A^T lambda, A a1 = c; with the workspace's effort laws, "
           "or efforts= the values u (one per input, N m or N). Raises mo2d.Error for sizes "
           "that do not match the model.")
      .def("reactions", &reactions, py::arg("t"), py::arg("q0"), py::arg("q1"),
           "The joint reactions at the state (N, N m), in the order of Model.reaction_labels, "
           "with the workspace's effort laws.")
      .def("project", &project, py::arg("t"), py::arg("q0"), py::arg("q1"),
           py::arg("tolerance") = py::none(),
           "(q0, q1) projected on the constraints psi(q0, t) = 0 and A q1 = b (minimum-norm "
           "corrections); tolerance: on the residuals (default 1e-12 of the model's size). "
           "Returns the tuple (q0, q1).")
      .def(
          "pivot_indicator",
          [](W& w, double t, const VectorXd& q0) {
            check_state(*w.model, q0, VectorXd::Zero(w.model->n1));
            return w.data->pivot_indicator(t, q0);
          },
          py::arg("t"), py::arg("q0"),
          "How far the constraint rows are from losing rank at q0: (sigma_min / sigma_max)^2 "
          "of the dimensionless A (1 well conditioned, 0 singular, e.g. a toggle position).")
      .def_property_readonly(
          "a", [](const W& w) { return w.data->a; },
          "The accelerations a1 of the last accelerations() call (NumPy).")
      .def_property_readonly(
          "multipliers", [](const W& w) { return w.data->lambda; },
          "The multipliers lambda of the last call: M a = f + B u - A^T lambda.")
      .def_property_readonly(
          "efforts", [](const W& w) { return w.data->u; },
          "The efforts u of the last call, one per input (N m, N).")
      .def_property_readonly(
          "f", [](const W& w) { return w.data->f; },
          "The applied and velocity-dependent forces f of the last call (gravity, loads, "
          "springs, the quadratic velocity terms).")
      .def_property_readonly(
          "Bu", [](const W& w) { return w.data->Bu; }, "B u of the last call.")
      .def_property_readonly(
          "c", [](const W& w) { return w.data->c; },
          "The right-hand side c of A a1 = c at the last state.")
      .def_property_readonly(
          "A", [](const W& w) { return w.data->A; },
          "The velocity constraint matrix A (A q1 = b) at the last state (rows x n1).")
      .def_property_readonly(
          "b", [](const W& w) { return w.data->b; },
          "The right-hand side b of A q1 = b at the last state.")
      .def_property_readonly(
          "M", [](const W& w) { return w.data->M; },
          "The mass matrix M (n1 x n1) at the last state.")
      .def_property_readonly(
          "B", [](const W& w) { return w.data->B; },
          "The input matrix B (n1 x inputs): the generalized forces of unit efforts.")
      .def_property_readonly(
          "accurate", [](const W& w) { return w.data->accel_ok; },
          "False when the last accelerations were regularized (the constraints near "
          "singular): they are then not accurate.");
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
                "The workspace of inverse dynamics (InverseData): solve(t) solves one sample "
                "of a prescribed motion, then its properties hold that sample.\n\n"
                "Example::\n\n"
                "    iw = mo2d.InverseWorkspace(model, [('link.angle', '0.5 * sin(3 * t)')])\n"
                "    iw.solve(0.25)\n"
                "    iw.efforts, iw.reactions")
      .def(py::init(&make_inverse), py::arg("model"), py::arg("motion"),
           py::arg("params") = Params{}, py::arg("position_tolerance") = 1e-12,
           py::arg("complement") = "prescribed",
           "A workspace for `model` driven by motion=[(coordinate label, s(t))] (as in "
           "inverse_dynamics); params: constants of the expressions; position_tolerance: "
           "|psi| of the position solve, relative to the model's size; complement: "
           "'prescribed' or 'recursive'.")
      .def_property_readonly(
          "model", [](const W& w) { return w.model; }, "The mo2d.Model of the workspace.")
      .def(
          "solve", [](W& w, double t) { inverse_dynamics_sample(*w.model, *w.data, t); },
          py::arg("t"),
          "Solve the sample at time t (s): positions, velocities, accelerations, efforts and "
          "reactions, starting Newton from the previous sample. Raises mo2d.Error naming the "
          "time (a singular configuration, a position that does not assemble).")
      .def_property_readonly(
          "t", [](const W& w) { return w.data->t; }, "The time of the last sample solved (s).")
      .def_property_readonly(
          "q0", [](const W& w) { return w.data->q0; },
          "The coordinates of the last sample (Model.coordinate_labels; m, rad).")
      .def_property_readonly(
          "q1", [](const W& w) { return w.data->q1; },
          "The quasi-velocities of the last sample (Model.rate_labels; m/s, rad/s).")
      .def_property_readonly(
          "a1", [](const W& w) { return w.data->a1; },
          "The accelerations of the last sample (m/s^2, rad/s^2).")
      .def_property_readonly(
          "efforts", [](const W& w) { return w.data->u; },
          "The efforts of the last sample (Model.input_labels; N m, N).")
      .def_property_readonly(
          "multipliers", [](const W& w) { return w.data->lambda; },
          "The constraint multipliers lambda of the last sample.")
      .def_property_readonly(
          "reactions", [](const W& w) { return w.data->reactions; },
          "The joint reactions of the last sample (Model.reaction_labels; N, N m).")
      .def_property_readonly(
          "friction", [](const W& w) { return w.data->friction; },
          "The joint frictions of the last sample, one per friction (N, N m), consistent with "
          "the reactions.")
      .def_property_readonly(
          "residuals", [](const W& w) { return residuals(*w.data); },
          "The constraint residuals of the last sample: {'position', 'velocity', "
          "'acceleration'} (infinity norms).")
      .def_property_readonly(
          "newton_iterations", [](const W& w) { return w.data->newton_iterations; },
          "The Newton iterations of the last sample's position solve.")
      .def_property_readonly(
          "pivot_ratio", [](const W& w) { return w.data->pivot_ratio; },
          "min/max |pivot| of the last sample's factorization (near 0: near a singular "
          "configuration).")
      .def_property_readonly(
          "warnings",
          [](W& w) {
            finish_inverse_warnings(*w.data);
            return w.data->warnings;
          },
          "The warnings of the samples solved so far (list of str), e.g. a near-singular "
          "configuration with its time.");
}

void bind_energies(py::module_& m) {
  m.def(
      "energy_balance", [](const Result& r) { return energy_balance(r.trajectory); },
      py::arg("result"),
      "The energy balance of a forward run at every sample (J, a NumPy array): K + V - (K + "
      "V)(t0) - W_inputs - W_loads - W_constraints + D, zero for an exact solution, so its "
      "size is the integration error. Raises mo2d.Error for a run without energies (inverse "
      "dynamics).");
  m.def(
      "energy_balance_error", [](const Result& r) { return energy_balance_error(r.trajectory); },
      py::arg("result"),
      "max |energy_balance(result)| (J): one number for the integration error of a forward "
      "run.");
  m.def(
      "kinetic_energy",
      [](const Model& model, const VectorXd& q1) {
        check_state(model, model.q0, q1);
        return kinetic_energy(model, q1);
      },
      py::arg("model"), py::arg("q1"),
      "The kinetic energy 1/2 q1^T M q1 (J) of the quasi-velocities q1 (Model.rate_labels).");
  m.def(
      "potential_energy",
      [](const Model& model, const VectorXd& q0) {
        check_state(model, q0, VectorXd::Zero(model.n1));
        return potential_energy(model, q0);
      },
      py::arg("model"), py::arg("q0"),
      "The potential energy (J) at the coordinates q0: gravity and the linear springs.");
}

}  // namespace

void bind_workspace(py::module_& m) {
  bind_forward_workspace(m);
  bind_inverse_workspace(m);
  bind_energies(m);
}

}  // namespace mo2d::py_bind
