#pragma once
// Impact with Newton's restitution and Coulomb friction over the contacts closing at once
// (internal to src/contact/; docs/contact.md, "Friction"): the velocity-level law of Moreau (1988,
// "Unilateral contact and dry friction in finite freedom dynamics", CISM 302) used by Moreau-Jean
// time-stepping (Jean 1999; Acary and Brogliato 2008, "Numerical Methods for Nonsmooth Dynamical
// Systems", the Newton impact-friction law with tangential restitution 0; Siconos's
// NewtonImpactFrictionNSL), in its planar complementarity form (Pfeiffer and Glocker 1996,
// "Multibody Dynamics with Unilateral Contacts", ch. 7):
//
//   normal:   w_n = g'+ + e g'- >= 0,  P_n >= 0,  w_n P_n = 0
//   tangent:  |P_t| <= mu P_n;  v_t+ = 0 (stick), or P_t = -mu P_n sign(v_t+) (slip)
//
// with g'+ = g'- + W_nn P_n + W_nt P_t and v_t+ = v_t- + W_tn P_n + W_tt P_t (W = [J_n; J_t] G
// [J_n; J_t]^T, G the constrained compliance, impact.hpp). The tangential impulse acts with the
// post-impact sliding velocity: a contact that sticks leaves without sliding, one that slides keeps
// its friction at the cone's edge against its direction after the impact.
//
// Solved exactly by enumerating each contact's mode (open; closed and sticking; closed and sliding
// forward or backward: 4^k combinations, 2 for a frictionless contact), the fewest closed contacts
// first and sticking before sliding; the first combination whose linear equations have a solution
// that meets every inequality (to 1e-10 relative) is taken. (With friction the problem may have
// several solutions or none; the enumeration order picks one, and none is an error.)
#include <Eigen/Core>

namespace mo2d::detail {

// W (2k x 2k: rows and columns the k normal, then the k tangential directions), the rates before
// g'- (normal) and v_t- (tangent), e and mu per contact (mu = 0: frictionless, its tangential
// impulse 0). Writes P_n, P_t; false if no combination works.
bool solve_friction_impact(const Eigen::MatrixXd& W, const Eigen::VectorXd& rate,
                           const Eigen::VectorXd& tangent_rate, const Eigen::VectorXd& e,
                           const Eigen::VectorXd& mu, Eigen::VectorXd& Pn, Eigen::VectorXd& Pt);

}  // namespace mo2d::detail
