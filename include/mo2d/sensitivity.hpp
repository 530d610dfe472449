#pragma once
// Exact sensitivities of an inverse-dynamics run to parameters that set only mass data and load
// coefficients (issue 36, item 2; docs/design.md, "Sensitivities").
//
// With the motion prescribed, positions q0, rates q1 and accelerations a1 do not depend on such a
// parameter p, and the efforts u, multipliers and reactions are linear in the body-local
// generalized force  l(p) = M(p) a1 - f(q0, q1, t; p)  (Theorem 4.3: C^T B u = C^T P^T l,
// K^T [lambda; mu] = B u - P^T l, reactions linear in lambda, u and l). So per sample
//   du/dp = (C^T B)^-1 C^T P^T l'(p),  dlambda/dp = the same transpose solve with B du - P^T l',
// with the factorizations of the run's own sample (one more pair of solves per parameter).
//
// l'(p) is taken from the models built at p + h, p + 2h, p + 3h (ParameterModels; a parameter
// reaches the model through the scene's expressions, evaluated in double) by the one-sided
// three-point formula l' = (-3 l(p) + 4 l(p+h) - l(p+2h)) / (2h), which is exact (to rounding)
// when l depends on p as a polynomial of degree <= 2 (masses, inertias, spring and damper
// coefficients, gravity, load coefficients: degree 1; a centre of mass moved by p: degree 2).
// Every sample checks that the third difference l(p+3h) - 3 l(p+2h) + 3 l(p+h) - l(p) vanishes
// (<= kSensitivityThirdDifference of max |l|); otherwise the dependence is not polynomial of
// degree <= 2 and the sample throws an Error naming the parameter, the time and the body. A
// parameter that changes anything the positions depend on (geometry, constraints, inputs, the
// prescribed motion) is refused before the run (check_parameter_models).
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// Relative step of the parameter models: h = kSensitivityStep |p| (p = 0: h = kSensitivityStep).
// The formula has no truncation error for the dependences it accepts, so the step is large: its
// rounding, eps max|l| / h, then stays small even for a parameter whose share of l is small (an
// inertia next to gravity's moment), and a nonlinear dependence shows a large third difference.
inline constexpr double kSensitivityStep = 0.1;
// Largest third difference of l (relative to max |l| of the sample) still taken as rounding.
inline constexpr double kSensitivityThirdDifference = 1e-11;

// One parameter of a sensitivity: its name, value p and step h, and the model built at p + h,
// p + 2h and p + 3h (everything else as the run's model).
struct ParameterModels {
  // the parameter's name (in the scene's parameters: block)
  std::string name{};
  // its value p and the step h (> 0)
  double value = 0, step = 0;
  // the models at p + h, p + 2h, p + 3h
  std::vector<Model> at{};
};

// The step h of a parameter of value p (see kSensitivityStep).
double sensitivity_step(double value);

// Throws Error (element: the parameter) when model `p.at[k]` differs from `m` in anything the
// positions, rates or accelerations of an inverse run depend on, naming what it changes:
// "sensitivity to 'L2': it changes the geometry (body 'coupler' node 'coupler.B'); geometric
// parameters are not supported yet". Also refuses models with joint friction (its reactions are
// not linear in the loads).
void check_parameter_models(const Model& m, const ParameterModels& p);

// Workspace of the sensitivities of one run (allocated once; inverse_sensitivity_sample does not
// allocate, except for a model with user constraints, whose rows it compares per sample, and on
// its error paths).
struct SensitivityData {
  // sized for model m and `parameters` (one column per parameter)
  SensitivityData(const Model& m, std::span<const ParameterModels> parameters);
  // d efforts / dp and d reactions / dp of the last sample, one column per parameter
  Eigen::MatrixXd efforts, reactions;
  // scratch
  Eigen::VectorXd l0, l1, l2, l3, dl, local, w, Ctw, du, rhs, z, psi, bb, cc;
  Eigen::MatrixXd A;
  std::vector<double> edge_force;
  bool user_rows = false;  // the model has user constraints (checked per sample)
};

// After inverse_dynamics_sample(m, d, t): the derivatives of its efforts and reactions to each
// parameter (s.efforts, s.reactions). Throws Error naming the parameter, the time and the body
// where a parameter's dependence is not polynomial of degree <= 2 (see above), or, for a model
// with user constraints, where a parameter model's constraints differ at the sample.
void inverse_sensitivity_sample(const Model& m, const InverseData& d,
                                std::span<const ParameterModels> parameters, SensitivityData& s);

// The derivatives of a whole run: per parameter, samples x inputs and samples x reactions.
struct InverseSensitivity {
  // the parameters' names, in order
  std::vector<std::string> parameters{};
  // per parameter: d efforts / dp (samples x inputs) and d reactions / dp (samples x reactions)
  std::vector<Eigen::MatrixXd> efforts{}, reactions{};
};

// inverse_dynamics() with the sensitivities of every sample: the run into `r` (as
// inverse_dynamics returns it), the derivatives returned. Calls check_parameter_models first.
InverseSensitivity inverse_dynamics_sensitivity(const Model& m,
                                                std::span<const Prescribed> prescribed,
                                                const InverseOptions& options,
                                                std::span<const ParameterModels> parameters,
                                                Trajectory& r);

// The label of the derivative of column `label` to parameter `p`: "d(label)/d(p)".
std::string sensitivity_label(const std::string& label, const std::string& p);
// Adds to r's output columns d(effort)/d(p) for every input, then d(reaction)/d(p) for every
// reaction, parameter by parameter (the CSV of mo2d inverse --sensitivity).
void add_sensitivity_columns(Trajectory& r, const InverseSensitivity& d);

// The summary values of a column x(t) at the samples (as mo2d optimize reads them: peak = max |x|
// at the samples, mean and RMS by the trapezoid rule) and their derivatives given dx/dp at the
// samples (chain rule; a peak, max or min: the derivative at its sample).
struct SummaryDerivative {
  // the values
  double peak = 0, max = 0, min = 0, mean = 0, rms = 0, peak_to_peak = 0;
  // their derivatives to the parameter
  double d_peak = 0, d_max = 0, d_min = 0, d_mean = 0, d_rms = 0, d_peak_to_peak = 0;
};
// The summary values of x at the samples t and their derivatives given dx (SummaryDerivative).
SummaryDerivative summary_derivative(const Eigen::Ref<const Eigen::VectorXd>& t,
                                     const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& dx);

}  // namespace mo2d
