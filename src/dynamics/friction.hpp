#pragma once
// Joint friction (FrictionDef, Model::frictions): the friction stage shared by inverse and
// forward dynamics. A friction's value F (N along a slide, N m across a revolute joint) acts as
// the generalized force F * terms (FrictionLoad::terms, the column an actuator of the joint would
// have) and opposes the joint's rate v = terms . q1:
//   F = -viscous v - mu N sgn(v)
// with N from the joint's reaction R = (Fx, Fy) (mo2d/dynamics.hpp, friction_forces):
//   slide (prismatic, pin-in-slot):  N = |R x e|, e the unit axis at q0 (the reaction's normal
//                                    component; a prismatic joint's lock torque is left out)
//   revolute:                        N = radius |R|   (the friction torque's arm)
// The reaction depends on F (Orsino Example 4.5): inverse dynamics iterates F -> reactions -> F
// per sample (sgn = sign, 0 at v = 0); forward dynamics iterates F -> accelerations, multipliers
// -> reactions -> F per evaluation with sgn(v) = tanh(v / v_s) (v_s = regularization).
#include <Eigen/Core>

#include "mo2d/model.hpp"

namespace mo2d::detail {

inline constexpr int kMaxFrictionIterations = 200;

double friction_rate(const FrictionLoad& f, const Eigen::Ref<const Eigen::VectorXd>& q1);
// N of the law above (a slide: normal force; a revolute: radius times |reaction|).
double friction_normal(const Model& m, const FrictionLoad& f,
                       const Eigen::Ref<const Eigen::VectorXd>& q0,
                       const Eigen::Ref<const Eigen::VectorXd>& reactions);
// Adds sign * values[k] * terms of every friction: terms of a body slot into `local` (body-local
// slots, as body_applied writes them) when to_local, else into `gen` (n1); the others (a slide
// coordinate) into `gen`.
void add_friction_forces(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& values,
                         double sign, bool to_local, Eigen::Ref<Eigen::VectorXd> local,
                         Eigen::Ref<Eigen::VectorXd> gen);
// sum_k values[k] * v_k: the power of the friction forces (<= 0).
double friction_power(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& values,
                      const Eigen::Ref<const Eigen::VectorXd>& q1);
// Largest |a_k - b_k| / scale_k over the frictions, scale_k = max(|a_k|, |b_k|, mu_k l_k R), R the
// largest |reaction| and l_k = 1 (slide) or radius (revolute): the convergence measure of the
// fixed-point iterations, relative to the friction itself or, where that is ~0 (a joint without
// load), to the largest friction the joint could carry (so that rounding noise in a reaction
// near zero does not stall the iteration). *worst: its friction.
double friction_change(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& a,
                       const Eigen::Ref<const Eigen::VectorXd>& b,
                       const Eigen::Ref<const Eigen::VectorXd>& reactions, int* worst);

}  // namespace mo2d::detail
