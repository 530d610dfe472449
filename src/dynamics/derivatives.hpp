#pragma once
// Directional derivatives of the applied forces and of the laws along a direction (dq0, dq1) of
// the state (internal header of src/dynamics/; used by the Jacobian of the accelerations,
// src/forward/jacobian.cpp). Each is exact: positions and velocities of body points are linear in
// q0 and q1 (Example 2.6 (b)), lengths and angles are differentiated in closed form, laws on Jets.
#include <Eigen/Core>
#include <span>
#include <string>

#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

using VecRef = Eigen::Ref<const Eigen::VectorXd>;

// A quantity a law reads (Quantity) with its derivative along (dq0, dq1): {value, d, 0}.
Jet quantity_jet(const Model& m, const Quantity& q, const VecRef& q0, const VecRef& q1,
                 const VecRef& dq0, const VecRef& dq1);

// law.f(x, t) of the load `role` '`element`', its failures naming the load and the time
// (call_user_code, src/run/user_code.hpp).
Jet call_law(const CompiledLaw& law, std::span<const Jet> x, double t, const char* role,
             const std::string& element);

// A law's value and derivative along (dq0, dq1) at time t (t does not move); role and element
// name the load in errors (call_law).
Jet law_jet(const Model& m, const CompiledLaw& law, const VecRef& q0, const VecRef& q1,
            const VecRef& dq0, const VecRef& dq1, double t, const char* role,
            const std::string& element);

// d local / ds of body_applied (mo2d/dynamics.hpp) along (dq0, dq1), body-local (slots).
void body_applied_derivative(const Model& m, const VecRef& q0, const VecRef& q1, const VecRef& dq0,
                             const VecRef& dq1, double t, Eigen::Ref<Eigen::VectorXd> dlocal);

// d/ds of load_power and damping_power (mo2d/dynamics.hpp) along (dq0, dq1).
double load_power_derivative(const Model& m, const VecRef& q0, const VecRef& q1, const VecRef& dq0,
                             const VecRef& dq1, double t);
double damping_power_derivative(const Model& m, const VecRef& q0, const VecRef& q1,
                                const VecRef& dq0, const VecRef& dq1);

}  // namespace mo2d::detail
