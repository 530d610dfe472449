#pragma once
// The quasi-steady-state model of a spring (SpringReduce::quasi_steady; Gamba 2009, 2.3;
// docs/reduction.md, "The quasi-steady-state model"). The spring's length rate is held at zero
// by the row of the constraint reduction (A = d l / d q0, multiplier the tension T), and the
// length it holds is its equilibrium length under T: the l at which the spring's own law at
// zero rate gives T,
//
//   T_law(l, rate = 0) = T        (linear: l = l_0 + T / k; damping gives nothing at zero rate)
//
// i.e. the configuration where the full model's acceleration of l vanishes (f_fast = 0 of the
// thesis's numerical QSS). T depends on the configuration, so forward runs settle the fixed
// point L = L_law(T(q(L))) at every projection (settle_quasi_steady): project on the constraints
// with the held lengths, evaluate T, move the held lengths, until they move by less than the
// projection's tolerance (the iteration contracts by (dT/dl) / k per pass). Between projections
// the row holds L extrapolated linearly with the derivative of the equilibrium length along the
// motion at the last projection (Tdot / k), so that the state moves with the quasi-steady manifold
// (its rate the slow manifold's, z2 = dT/dt, not the thesis's z2 = 0, which a state in positions
// and velocities cannot follow without a jump every step).
// The same holds for a torsional spring (its cell the angle a from rest, held where the torque
// law at zero rate gives the row's torque tau: a = -tau / k when linear) and for a quasi-steady
// chain (the taut span's length rest + T / k; the idle span's cell waits at its rest length).
#include <Eigen/Core>
#include <array>
#include <atomic>
#include <cmath>
#include <type_traits>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d {

struct ForwardData;

// The length a quasi-steady spring's row holds, L(t) = length + rate (t - t0): the length settled
// at the last projection of a forward run (t0) and its rate there, the derivative of the
// equilibrium length along the motion (src/forward/quasi_steady.cpp, rates_along_motion).
// ReducedSpring::held_length points at `length`, the first member (the cell is shared by the
// row's psi and the forward run; standard layout, so the pointer converts back: held_of).
struct HeldLength {
  double length = 0;  // m, settled at the last projection (at t0)
  double rate = 0;    // m/s, d/dt of the equilibrium length there
  double t0 = 0;      // s, the time of the last settling
  // Whether a forward run holds the cell (QuasiSteadyRun): two runs at once on one Model (or on
  // copies, which share the cell) would move each other's lengths.
  std::atomic<bool> in_use{false};
  // The held length at time t (m).
  double at(double t) const { return length + rate * (t - t0); }
};
static_assert(std::is_standard_layout_v<HeldLength>);
// The cell of a quasi-steady spring (s.held_length must be set: reduce: quasi_steady).
inline HeldLength& held_of(const ReducedSpring& s) {
  return *reinterpret_cast<HeldLength*>(s.held_length.get());
}

// The equilibrium length of the reduced spring s under the tension T at the state (t, q0, q1):
// l_0 + T / k for a linear spring; for a tension law, Newton on T_law(l) = T with the law's
// "length" / "extension" at l and its "rate" 0 (its other arguments at the state), from the
// length held now. Throws Error (the spring, t, T) where the law has no such length.
double quasi_steady_length(const Model& m, const ReducedSpring& s, double T,
                           const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double t);

// The cell of a quasi-steady chain's span (0 upper, 1 lower; c.held[span] must be set).
inline HeldLength& held_of(const ChainLoad& c, int span) {
  return *reinterpret_cast<HeldLength*>(c.held[span].get());
}

// Whether m has quasi-steady elements (springs, torsional springs, chains).
bool has_quasi_steady(const Model& m);

// Every quasi-steady element's held value back to rest (the rest length; a torsional spring's
// angle from rest 0; the state a Model is built in; forward runs do it at their end).
void reset_quasi_steady(const Model& m);

namespace detail {
// A forward run's hold on the quasi-steady elements of a Model (springs, torsional springs,
// chain spans), for the run's lifetime: the constructor claims every held-length cell (an Error
// naming the model if another run holds one) and puts them at rest, the destructor puts them back
// to rest and releases them, also when the run throws, so that inverse dynamics, modes and the
// next run see the Model as built. legs: a run made of several forward runs on this thread (the
// inextensible chains' span switching, src/forward/chain_switching.cpp): while it holds the cells,
// the legs' own holds do nothing and the lengths carry over from leg to leg.
class QuasiSteadyRun {
 public:
  // Claims m's cells (none: nothing to do; inside a run of legs: nothing at all).
  explicit QuasiSteadyRun(const Model& m, bool legs = false);
  // Resets and releases the cells (if it claimed them).
  ~QuasiSteadyRun();
  QuasiSteadyRun(const QuasiSteadyRun&) = delete;
  QuasiSteadyRun& operator=(const QuasiSteadyRun&) = delete;

 private:
  const Model& m_;
  std::vector<HeldLength*> held_;
  bool owns_ = false, legs_ = false;
};

// The values of m's held cells (their length, rate, t0) at an accepted state of a forward run.
// Every projection moves the cells, also those of a step that is then rejected, of the secant
// tries that locate an event and of the steps to an output time inside the step: the explicit
// drivers put the accepted state's values back before each such try (restore_held), so that the
// tries' rows hold the accepted state's L(t) and not whatever was projected last.
using HeldValues = std::vector<std::array<double, 3>>;
HeldValues save_held(const Model& m);
void restore_held(const Model& m, const HeldValues& v);
// Every held cell of m at its value at t with rate 0 (the span switching at an event: the held
// values jump with the mode; the next leg's start settles them and their rates afresh).
void hold_still(const Model& m, double t);
// A quasi-steady chain's taut span (its cells held still by the switching) released to its rest
// length (the held length at T = 0) when its tension reaches 0: where T jumps through 0 with the
// loads the located state past the jump holds it at rest + T / k with T < 0. Returns the length
// it held beyond its rest length (m); the caller puts the state on the row (an engagement).
double release_span(const ChainLoad& c, int span, double rest);

// Project (q0, q1) on the constraints with the quasi-steady lengths settled at t (above).
// Throws Error naming the spring if the fixed point does not converge in 30 passes.
void settle_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1,
                         double tol_pos, double tol_vel);
// The start of a forward run: the held lengths from the rest lengths (a leg of a run of legs:
// from the lengths held at its start), settled on the initial state (which moves onto them). Throws
// Error naming the springs for an integrator that does not project (cvode_adams, baumgarte): it
// could not follow the lengths; and for cvode_bdf, whose step history does not follow their updates
// at the projections (it fails or crawls).
void start_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1);
}  // namespace detail

}  // namespace mo2d
