#pragma once
// Internal: the causes an explicit integrator's error names when its step fails (forward_rk.cpp).
//  - LoadGrowth: the efforts and loads whose values grew most since the start, for a step that
//    collapsed in the error test. A law that blows up in finite time (an effort 1 / (1 - t), a
//    feedback x^2 that runs away) leaves an adaptive step nothing to converge to; the error then
//    says which law, not only "step size too small".
//  - stiffness_cause: dynamics too stiff for the steps tried (a PD gain of 1e12), whose stages
//    land far off the mechanism's configuration, where the accelerations are not accurate: not
//    a singular configuration, which the error would otherwise blame.
#include <string>
#include <vector>

#include "mo2d/forward_data.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

class LoadGrowth {
 public:
  // The start of the run (t0, q0, q1), kept: nothing is evaluated before describe(), so a run
  // that succeeds calls no law more than it would without it.
  LoadGrowth(const Model& m, const ForwardData& d, double t0, const VectorXd& q0,
             const VectorXd& q1);
  // Compares the efforts (by input label), forces (|F|), torques, spring tensions and torsional
  // spring torques at the start and at (t, q0, q1) (d's effort laws): "; the loads
  // grew (...): 'push' = 3.1e+12 at t = 0.999 s (1 at t = 0 s), ..." for the (up to 3) values that
  // grew most, by more than kGrowth times; "" when none did or a value cannot be evaluated. For
  // the error path only.
  std::string describe(double t, const VectorXd& q0, const VectorXd& q1) const;

  static constexpr double kGrowth = 1e3;

 private:
  const Model& m_;
  const ForwardData& d_;
  double t0_ = 0;
  VectorXd q0_start_, q1_start_;
  std::vector<double> values(double t, const VectorXd& q0, const VectorXd& q1) const;
};

// "" unless the explicit method's steps of at least h_min from s are beyond its stability limit
// (|lambda|max h_min > kStabilityBound, |lambda|max estimated at s by choose_method) while the
// configuration at s is regular (pivot ratio at least `regular`); then the cause, e.g. "the
// dynamics are stiff there, not singular: |lambda|max = 1.2e+07 /s at t = 0 s ...: use
// cvode_bdf". For the error path only (it evaluates the accelerations a few hundred times).
std::string stiffness_cause(const Model& m, const ForwardOptions& o, ForwardData& d, const State& s,
                            double h_min, double regular);

}  // namespace mo2d::detail
