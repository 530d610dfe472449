#pragma once
// Mass and applied forces of the nodal formulation (Orsino eq. 5.25-5.27, errata applied).
//
// Each body has its own local slots: nodes (x, y) and its rotation rate. With the centre of mass
// given by nodes i, j and (gamma, rho), v* = J (v_i, v_j), J = [J_i J_j],
//   J_i = [1-gamma  rho; -rho  1-gamma],  J_j = [gamma  -rho; rho  gamma],
// so the kinetic energy 1/2 m |v*|^2 + 1/2 I w^2 gives the constant mass matrix m J^T J (+) I, and
// a force F at a body point with coefficients (gamma_p, rho_p) has generalized force J_p^T F.
// Reduced vectors are obtained by summing the local slots into the model variables (eq. 5.27).
#include <Eigen/Core>

#include "mo2d/model.hpp"

namespace mo2d {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Local generalized inertia force M_b a_b for every body (concatenated, Body::offset).
void body_inertia(const Model& m, const Eigen::Ref<const VectorXd>& a1, Eigen::Ref<VectorXd> local);
// Local applied generalized forces (gravity, forces, torques, spring-dampers) at time t.
void body_applied(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> local);
// Sum local slots into reduced variables: out += P^T local.
void scatter_local(const Model& m, const Eigen::Ref<const VectorXd>& local,
                   Eigen::Ref<VectorXd> out);

// Dense reduced mass matrix (n1 x n1), for checks and the Lagrange formulation.
MatrixXd mass_matrix(const Model& m);
// Reduced applied forces f(q0, q1, t) (n1).
void applied_forces(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                    const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> f);
// Potential energy of gravity, of the linear springs (those without a law; a unilateral one
// only while it acts) and of the chains' spans; power dissipated by their dampers (>= 0; a
// unilateral spring: its tension less the elastic part, times dl/dt).
double potential_energy(const Model& m, const Eigen::Ref<const VectorXd>& q0);
double damping_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1);
// Power of the applied forces (F . v of their points), torques (tau . omega of their bodies) and
// of the springs and torsional springs given by a law (-T dl/dt, tau (w2 - w1)) at time t: what
// the energy balance integrates as their work (gravity and the linear springs' elastic forces are
// in potential_energy, their dampers in damping_power, the inputs are B u . q1).
double load_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t);
// The world-frame force of a point load and the torque of a torque load at (t, q0, q1).
Vec2 point_force(const Model& m, const PointLoad& f, const Eigen::Ref<const VectorXd>& q0,
                 const Eigen::Ref<const VectorXd>& q1, double t);
double torque_value(const Model& m, const TorqueLoad& tq, const Eigen::Ref<const VectorXd>& q0,
                    const Eigen::Ref<const VectorXd>& q1, double t);
// A spring's length l, its rate dl/dt and its tension T (> 0 pulls its two points together; the
// law's, clipped for a unilateral spring, or k (l - l0) + c dl/dt) at (t, q0, q1); its power on
// the mechanism is -T dl/dt.
struct SpringValue {
  // l (m), dl/dt (m/s), T (N)
  double length = 0, rate = 0, tension = 0;
};
// The SpringValue of spring `s` of model `m` at time t (s), positions q0 and rates q1.
SpringValue spring_value(const Model& m, const SpringLoad& s, const Eigen::Ref<const VectorXd>& q0,
                         const Eigen::Ref<const VectorXd>& q1, double t);
// A torsional spring's torque on body 2 (its opposite on body 1; the law's, or
// -k theta - c (w2 - w1)) and the relative rate w2 - w1; its power is torque (w2 - w1).
struct TorsionalValue {
  // torque (N m) and w2 - w1 (rad/s)
  double torque = 0, rate = 0;
};
// The TorsionalValue of torsional spring `l` at time t (s), positions q0 and rates q1.
TorsionalValue torsional_value(const Model& m, const TorsionalLoad& l,
                               const Eigen::Ref<const VectorXd>& q0,
                               const Eigen::Ref<const VectorXd>& q1, double t);
// A chain drive's spans (ChainLoad; src/dynamics/chain.hpp): each span's material length and
// tension (> 0 pulls), and the chain's power on the mechanism, -sum T dl/dt.
struct ChainValue {
  // material lengths of the two spans (m), their tensions (N, >= 0) and the chain's power (W)
  double upper_length = 0, upper_tension = 0, lower_length = 0, lower_tension = 0, power = 0;
};
// The ChainValue of chain `c` at time t (s), positions q0 and rates q1.
ChainValue chain_value(const Model& m, const ChainLoad& c, const Eigen::Ref<const VectorXd>& q0,
                       const Eigen::Ref<const VectorXd>& q1, double t);
// The value of every joint friction (Model::frictions; FrictionDef in mo2d/system.hpp) at the
// state (q0, q1) with the joint reactions `reactions` (Model::reactions order): out[k] =
// -viscous v - mu N sgn(v), v the joint's rate, N its normal force from the reaction,
// sgn(v) = tanh(v / regularization) when regularized (forward dynamics), else sign(v) with
// sign(0) = 0 (inverse dynamics). out has Model::frictions.size() entries.
void friction_forces(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1,
                     const Eigen::Ref<const VectorXd>& reactions, bool regularized,
                     Eigen::Ref<VectorXd> out);
// Input matrix B (n1 x inputs): generalized force per unit effort.
MatrixXd input_matrix(const Model& m);

}  // namespace mo2d
