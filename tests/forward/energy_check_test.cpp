// The energy-balance check of every forward run (src/forward/energy_balance.cpp): a run whose
// balance is off by more than 1 % of its energy scale says so. The IFToMM double four-bar (no
// loads, no dissipation: the balance is E(t) - E(0)) with rk4 at h = 0.1 s takes its ten singular
// passages in steps far too long and ends 2.5 J off (1.9 % of the scale; before the check it
// ended so with no warning); at h = 4e-3 s it ends 4.5e-7 J off and says nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace energy_check_test {

using namespace mo2d;

int balance_warnings(const Trajectory& r) {
  int n = 0;
  for (const std::string& w : r.stats.warnings) n += w.rfind("energy balance of ", 0) == 0;
  return n;
}

Trajectory run(double h) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  return forward_dynamics(
      m, s, {.t0 = 0, .t1 = 10, .samples = 101, .integrator = Integrator::rk4, .step = h});
}

TEST(EnergyCheck, ALongFixedStepOverSingularPassagesIsReported) {
  const Trajectory coarse = run(0.1);
  EXPECT_GT(energy_balance_error(coarse), 1.0);  // independent of the check: the balance itself
  ASSERT_EQ(balance_warnings(coarse), 1);
  for (const std::string& w : coarse.stats.warnings)
    if (w.rfind("energy balance of ", 0) == 0) {
      std::printf("  %s\n", w.c_str());
      EXPECT_NE(w.find("'double_fourbar'"), std::string::npos) << w;
      EXPECT_NE(w.find(" at t = "), std::string::npos) << w;
    }
  const Trajectory fine = run(4e-3);
  EXPECT_LT(energy_balance_error(fine), 1e-5);
  EXPECT_EQ(balance_warnings(fine), 0);
}

}  // namespace energy_check_test
