#pragma once
// The lumped transmission (Gamba 2009, ch. 1, "fast model"; planar form): an n-shaft gear train
// in a housing R is replaced by the housing R~ and two counter-rotating shafts A and B on one
// axis h~ of it, geared theta_b - theta_c = -(theta_a - theta_c), with parameters chosen so that
// both models have equal Lagrangians (exact: every housing signal and the reference shaft's
// angle agree to solver tolerance).
//
// Full model: housing (mass m_r, centre of mass p_r, inertia I_r about it, in the housing frame);
// shafts k with mass m_k and inertia J_k about their own axes h_k (centre of mass on the axis),
// turning relative to the housing at rho_k phi', phi the reference shaft's angle relative to the
// housing (rho_ref = 1). Kinetic energy, omega the housing's rate, v its velocities:
//   T = T_R(v, omega) + sum 1/2 m_k |v_k|^2 + 1/2 sum J_k (omega + rho_k phi')^2
//     = T_R + T_points + 1/2 Sigma omega^2 + S omega phi' + 1/2 P phi'^2,
//   Sigma = sum J_k,  S = sum rho_k J_k,  P = sum rho_k^2 J_k        (the invariants, 1.34)
// Lumped model, theta_a - theta_c = rho_e phi (1.37):
//   m_a = m_b = 1/2 sum m_k,  h~ = sum m_k h_k / sum m_k                          (1.41, 1.42)
//   I_r~ = I_r + sum m_k |h_k - h~|^2   (the point masses' spread, about R's own centre p_r)
//   J_a + J_b = Sigma,  (J_a - J_b) rho_e = S,  (J_a + J_b) rho_e^2 = P
//   => rho_e = sqrt(P / Sigma),  J_a = (Sigma + S / rho_e) / 2,  J_b = (Sigma - S / rho_e) / 2
//   (J_b >= 0 by Cauchy-Schwarz: S^2 <= Sigma P). The potential energies are equal (same masses,
//   same first moment), and the planar kinetic energies term by term.
// Loads (the cotangent lift of the map, 1.56 ff.): a torque u_k on shaft k relative to the
// housing (a motor or a brake mounted on it) has the generalized force rho_k u_k on phi, so it
// becomes the torque rho_k u_k / rho_e on A relative to the housing; a torque tau_k on shaft k
// from outside (the ground) adds tau_k on the housing as well: tau_k on the housing plus
// rho_k tau_k / rho_e on A relative to it.
//
// The element (add_transmission, scene key `transmissions:`): the train written once with a
// fidelity switch. Both fidelities have the coordinate "NAME.phi" (the input shaft's angle
// relative to the housing since the start; its rate "NAME.phi.rate") and the input "NAME.torque"
// (a motor between the housing and the input shaft, power u phi'), so their results compare
// column by column. With the input shaft as reference (rho = 1):
//  - full: each shaft a body of the System (named as the shaft) on a revolute joint
//    "NAME_SHAFT" at the housing's node "NAME_SHAFT", each other shaft geared to the input by a
//    pair "NAME_SHAFT_mesh" (ratio rho_k, carrier the housing); phi' = omega_in - omega_c;
//  - lumped: the housing's inertia plus the spread, bodies "NAME_a" and "NAME_b" on revolute
//    joints "NAME_a_bearing" and "NAME_b_bearing" at the housing's node "NAME_axis" (h~), the pair
//    "NAME_pair" (B driven by A, ratio -1, carrier the housing); phi = NAME_pair.phi / rho_e, so
//    the input becomes u / rho_e on A relative to the housing (the cotangent lift).
#include <span>
#include <string>
#include <vector>

#include "mo2d/system.hpp"

namespace mo2d {

// One shaft of a gear train in its housing (the full model of the file's description).
struct TransmissionShaft {
  double mass = 0;     // kg (>= 0), centre of mass on the axis
  double inertia = 0;  // kg m^2 about its axis (>= 0)
  Vec2 axis{0, 0};     // the axis in the housing's frame (m)
  double ratio = 1;    // rho_k = (omega_k - omega_c) / (omega_ref - omega_c); the reference: 1
};

// The housing of a gear train: its own mass data in its frame.
struct TransmissionHousing {
  double mass = 0;     // kg (> 0 for the lumped housing to carry the spread)
  Vec2 com{0, 0};      // centre of mass in the housing's frame (m)
  double inertia = 0;  // kg m^2 about the centre of mass
};

// The lumped equivalent of a gear train (Gamba 2009 eq. 1.37-1.42): the housing R~ and the two
// counter-rotating shafts A and B.
struct LumpedTransmission {
  TransmissionHousing housing;          // R~: m_r, p_r, I_r + sum m_k |h_k - h~|^2
  Vec2 axis{0, 0};                      // h~, the common axis of A and B (housing frame)
  double shaft_mass = 0;                // m_a = m_b
  double inertia_a = 0, inertia_b = 0;  // J_a, J_b
  double ratio = 1;                     // rho_e: theta_a - theta_c = rho_e phi
  double sigma = 0, s = 0, p = 0;       // the invariants Sigma, S, P
  // Torque on A relative to the housing that stands for u on shaft k relative to the housing.
  double input_torque(const TransmissionShaft& shaft, double u) const {
    return shaft.ratio * u / ratio;
  }
};

// The lumped equivalent of `shafts` in `housing`. Throws Error (element `name`) for negative or
// non-finite masses or inertias, non-finite ratios or axes, no shafts, or a train without
// rotational inertia (P = 0).
LumpedTransmission lump_transmission(const TransmissionHousing& housing,
                                     std::span<const TransmissionShaft> shafts,
                                     const std::string& name = "transmission");

// How a transmission is modelled: every shaft a body with its gear pairs, or the exact lumped
// equivalent (two shafts, one pair).
enum class TransmissionFidelity { full, lumped };

// One shaft of a transmission element: its data (ratio relative to the input shaft, 1 for the
// input itself) and an optional torque from outside (the ground) on it.
struct TransmissionShaftDef {
  std::string name{};         // the shaft body's name in the full model, unique in its System
  TransmissionShaft shaft{};  // mass, inertia, axis (System frame, initial configuration), ratio
  // N m, counter-clockwise on the shaft from outside (a load, a brake to the ground); empty = 0.
  // The lumped model has no body of this shaft: a law that reads the shaft's own state fails to
  // build there (read the housing's or "NAME.phi" instead).
  Law torque{};
};

// A gear train in a housing body, written once and modelled at `fidelity` (see the file's
// description).
struct TransmissionDef {
  std::string name{};     // unique in its System; prefix of the labels it adds
  std::string housing{};  // a body of the System with at least two nodes, without a shape
  std::string input{};    // the shaft driven by the input "NAME.torque" (ratio 1)
  std::vector<TransmissionShaftDef> shafts{};                  // at least one, the input among them
  TransmissionFidelity fidelity = TransmissionFidelity::full;  // the model to build
};

// Adds transmission `def` to `system` at its fidelity: the bodies, joints, gear pairs, housing
// nodes, coordinate "NAME.phi" with input "NAME.torque" and torques of the file's description
// (lumped: the housing body's inertia gains the shafts' spread). Throws Error (element
// def.name) for an unknown housing or one without two nodes or given by its shape, an input
// that is not one of the shafts or whose ratio is not 1, and whatever lump_transmission refuses.
void add_transmission(System& system, const TransmissionDef& def);

}  // namespace mo2d
