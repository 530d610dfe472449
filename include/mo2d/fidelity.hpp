#pragma once
// The fidelity report (docs/reduction.md, "Which springs to reduce"): each compliant element of a
// model (spring, torsional spring, spring law with a derivative) with its own natural frequency
// against the time scales of a run, the reduction that would remove it and what that is expected
// to cost in accuracy. Elements already reduced (reduce: constraint | quasi_steady springs and
// torsional springs, inextensible and quasi-steady chains) are listed with their reduction and
// the frequency of the mode it removed (their own row left out). `mo2d info --fidelity SCENE`
// prints it.
//
// An element's frequency is that of its own coordinate (the length l of a spring, the relative
// angle of a torsional spring) with everything else free to follow:
//   omega = sqrt(k / m_r),   1 / m_r = g^T Mr^-1 g,   Mr = C^T M C,   g = C^T dl/dq1,
// C a basis of the velocities the constraints allow at the initial configuration (null space of
// A), M the mass matrix, dl/dq1 the gradient of the element's rate (dl/dt = dl/dq1 . q1) and k the
// local stiffness there (k of a linear element; the law's derivative with respect to its own
// length / extension or angle otherwise). m_r is the inertia the element sees (the reduced mass
// m1 m2 / (m1 + m2) of two free masses on a spring), so omega is exact for an element between
// otherwise free bodies and an upper bound on the fastest mode it takes part in otherwise
// (Rayleigh: a constraint on the other motions can only raise it).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d {

// The time scales of a run: its duration, the interval between output samples, and the step of a
// fixed-step integrator (0 for an adaptive one).
struct RunTimeScale {
  // duration of the run (s)
  double duration = 1;
  // interval between output samples (s)
  double output_interval = 0.01;
  // step of a fixed-step integrator (s; 0: adaptive)
  double step = 0;
};

// One compliant element (a spring, a torsional spring, a chain span) in the fidelity report: its
// stiffness and damping, the inertia it moves, its natural frequency omega = sqrt(k / m_r) and the
// error expected if it were reduced to a constraint (docs/reduction.md).
struct CompliantElement {
  // the element's name in the model
  std::string name;
  std::string kind;          // "spring", "torsional spring", "chain span" (+ " (taut)")
  bool reduced = false;      // already reduced (reduce: or a chain's fidelity)
  std::string reduction;     // how: "reduce: constraint", "fidelity: inextensible", ... ("": not)
  double stiffness = 0;      // local, N/m or N m/rad
  double damping = 0;        // local, N s/m or N m s/rad
  double inertia = 0;        // m_r, kg or kg m^2 (inf: the element's coordinate cannot move)
  double omega = 0;          // rad/s (0: no stiffness; inf: no inertia)
  double damping_ratio = 0;  // c / (2 sqrt(k m_r))
  // (omega_out / omega)^2, omega_out = pi / output_interval (the fastest motion the outputs
  // resolve): the expected relative error of the resolved signals when the element is reduced
  // to a constraint; and the same for the slowest scale of the run, omega_run = 2 pi / duration.
  double error_output = 0, error_run = 0;
  double steps_per_period = 0;  // 2 pi / (omega h) for a fixed step h (0: adaptive)
  std::string verdict;          // what to do, in words
};

// The report at configuration q0 (time t) for a run of time scales `scale`.
std::vector<CompliantElement> fidelity_report(const Model& m, const Eigen::VectorXd& q0,
                                              const Eigen::VectorXd& q1, double t,
                                              const RunTimeScale& scale);
// A table of the report, one line per element (with its verdict), for `mo2d info --fidelity`.
std::string describe_fidelity(const std::vector<CompliantElement>& report,
                              const RunTimeScale& scale);

}  // namespace mo2d
