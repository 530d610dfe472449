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

}  // namespace mo2d
