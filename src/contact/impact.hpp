#pragma once
// Impact with Newton's restitution over the contacts closing at once (internal to src/contact/).
//
// At the impact the positions are fixed and the velocities jump by the impulses P_j >= 0 along the
// gaps' gradients J_j, the other constraints holding (A v+ = b):
//   [M A^T; A 0] [v+ - v-; mu] = [sum_j J_j^T P_j; 0],   so  v+ = v- + sum_j x_j P_j,
// x_j = G J_j^T (G the top-left block of the inverse). The gap rates after are
//   g'+ = g'- + W P,  W_ij = J_i x_j  (symmetric, positive semi-definite),
// and Newton's law with complementarity (Glocker and Pfeiffer; Pfeiffer and Glocker 1996,
// "Multibody Dynamics with Unilateral Contacts", ch. 7):
//   w = W P + (1 + e) g'- >= 0,   P >= 0,   w_i P_i = 0
// (w_i = g'+_i + e_i g'-_i: a contact that pushes leaves at e times its approach speed; one that
// does not push leaves at least as fast). A linear complementarity problem, solved exactly by
// enumerating the active sets (2^k for k <= kMaxImpactContacts contacts; for a positive definite
// W its solution is unique). The energy the contacts dissipate is minus their impulses' work,
//   -sum_j P_j (g'-_j + g'+_j) / 2 >= 0 for e <= 1
// (an impulse does the work P times the mean of the velocities before and after). It is the
// kinetic energy lost, K(v-) - K(v+), unless a constraint moves by itself (a driven cam, A v + b =
// 0 with b != 0): then its impulses do work too, K(v+) - K(v-) + lost, which a contact that lifts
// the follower off a faster cam makes positive (the kinetic energy can grow at an impact).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d::detail {

inline constexpr int kMaxImpactContacts = 8;

// The solution of the LCP w = W P + q >= 0, P >= 0, w . P = 0 (k <= kMaxImpactContacts) by
// enumeration; false if no active set gives one (to tol, relative to |q|).
bool solve_lcp_enumerate(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, Eigen::VectorXd& P);

// The contacts' friction at an impact (friction_impact.hpp): their tangents' Jacobians J_t (rows,
// k x n1; 0 for a frictionless contact), sliding rates v_t- and coefficients mu.
struct ImpactFriction {
  Eigen::MatrixXd J;
  Eigen::VectorXd rate, mu;
};

struct ImpactResult {
  Eigen::VectorXd q1;               // v+
  Eigen::VectorXd impulse;          // P per contact (N s)
  Eigen::VectorXd rate;             // g'+ per contact (m/s)
  Eigen::VectorXd tangent_impulse;  // P_t per contact (N s; 0 without friction)
  Eigen::VectorXd tangent_rate;     // v_t+ per contact (m/s; without friction: v_t-)
  double energy_lost = 0;           // J, dissipated by the contacts' impulses
  double constraint_work = 0;       // J, done by the other constraints' impulses (0 if none moves)
};

// The impact at (t, q0) with velocities q1 (v-), the contacts' gradients J (rows, k x n1), their
// rates g'- and restitutions e; with friction (any mu > 0) the law of friction_impact.hpp, its
// impulses' work counted in energy_lost. Throws Error naming `names` and t if the LCP has no
// solution.
ImpactResult newton_impact(const Model& m, double t, const Eigen::VectorXd& q0,
                           const Eigen::VectorXd& q1, const Eigen::MatrixXd& J,
                           const Eigen::VectorXd& rate, const Eigen::VectorXd& e,
                           const std::string& names, const ImpactFriction* friction = nullptr);

}  // namespace mo2d::detail
