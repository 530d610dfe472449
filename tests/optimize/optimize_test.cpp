// mo2d optimize (mo2d/optimize.hpp): the optimum against closed forms (a crank's counterweight that
// cancels its shaking force; Berkof and Lowen's two counterweights of a four-bar), an optimum on
// a bound, a constraint active at the optimum, the budgets that end an optimization, and the
// refusals of bad input (an unknown parameter, LO >= HI, an expression that does not parse or
// names no value).
#include "mo2d/optimize.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

namespace optimize_test {
namespace {

using namespace mo2d;
constexpr double kPi = std::numbers::pi;

const std::string kCrank = std::string(MO2D_TEST_DATA_DIR) + "/crank_counterweight.yaml";
const std::string kFourBar = std::string(MO2D_MECHANISMS_DIR) + "/fourbar_balance.yaml";

// The crank's scene (tests/data/crank_counterweight.yaml): m = 1 kg at r = 0.1 m, the counterweight
// m_cw at r_cw = 0.05 m behind the pivot, w = 2 pi rad/s, no gravity: the shaking force is
// |m r - m_cw r_cw| w^2 at every sample, zero at m_cw = m r / r_cw = 2 kg.
OptimizeOptions crank(const std::string& minimize, double lo, double hi) {
  OptimizeOptions o;
  o.scene = kCrank;
  o.minimize = minimize;
  o.vary = {{"m_cw", lo, hi}};
  o.xtol = 1e-10;
  return o;
}

bool has_warning(const OptimizeResult& r, const std::string& text) {
  for (const auto& w : r.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

std::string error_of(const OptimizeOptions& o) {
  try {
    optimize_scene(o);
  } catch (const OptimizeInputError& e) {
    return e.what();
  } catch (const Error& e) {
    return std::string("not an input error: ") + e.what();
  }
  return "no error";
}

TEST(Optimize, CounterweightCancelsTheShakingForce) {
  const OptimizeResult r = optimize_scene(crank("rms.frame.shaking.F^2", 0, 5));
  ASSERT_EQ(r.x.size(), 1u);
  EXPECT_NEAR(r.x[0], 1.0 * 0.1 / 0.05, 1e-8);
  EXPECT_LT(r.value, 1e-14);
  EXPECT_EQ(r.method, "BOBYQA");
  EXPECT_EQ(r.stop, "converged");
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_LT(r.evaluations, 60);
  // the written scene defines m_cw as the optimum, and nothing else changed
  const Scene s = parse_scene(r.scene_text, kCrank);
  for (const auto& [name, value] : s.parameters)
    if (name == "m_cw") {
      EXPECT_EQ(value, r.x[0]);
    }
  EXPECT_NE(r.scene_text.find("r_cw: 0.05    # m"), std::string::npos);
}

// Berkof and Lowen: the total centre of mass of a four-bar is still when
// m1 r1 = -m_crank g1 a + m_coupler a (1 - g2) and m3 r3 = -m_rocker g3 c + m_coupler c g2 (gi:
// the centres of mass along the links, here 1/2; the counterweights behind the pivots), checked
// at other lengths than the scene's (the scene's geometry follows a and c).
TEST(Optimize, FourBarBalancedByBerkofLowen) {
  OptimizeOptions o;
  o.scene = kFourBar;
  o.minimize = "rms.frame.shaking.F^2";
  o.vary = {{"m1", 0, 2}, {"m3", 0, 3}};
  o.set = {{"a", "0.12"}, {"c", "0.32"}};
  o.run = {{"samples", "37"}};
  o.xtol = 1e-10;
  const OptimizeResult r = optimize_scene(o);
  const double a = 0.12, c = 0.32, r1 = 0.05, r3 = 0.1;
  EXPECT_NEAR(r.x[0], (0.2 * 0.5 + 0.5 * 0.5) * a / r1, 1e-7);
  EXPECT_NEAR(r.x[1], (0.4 * 0.5 + 0.5 * 0.5) * c / r3, 1e-7);
  EXPECT_EQ(r.stop, "converged");
  // the --set parameters are written too: the file reproduces the run
  const Scene s = parse_scene(r.scene_text, kFourBar);
  for (const auto& [name, value] : s.parameters) {
    if (name == "a") {
      EXPECT_EQ(value, a);
    }
    if (name == "m3") {
      EXPECT_EQ(value, r.x[1]);
    }
  }
}

TEST(Optimize, OptimumBeyondABoundEndsOnTheBound) {
  const OptimizeResult r = optimize_scene(crank("rms.frame.shaking.F^2", 0, 1));
  EXPECT_EQ(r.x[0], 1.0);
  EXPECT_TRUE(has_warning(r, "m_cw = 1 is at its upper bound")) << r.warnings.size();
  // and from below: the lightest counterweight within [3, 5] is the best
  const OptimizeResult s = optimize_scene(crank("rms.frame.shaking.F^2", 3, 5));
  EXPECT_EQ(s.x[0], 3.0);
  EXPECT_TRUE(has_warning(s, "lower bound"));
}

// The lightest counterweight that keeps the shaking force within 1 N: (m r - m_cw r_cw) w^2 = 1,
// the constraint active at the optimum (written both ways round).
TEST(Optimize, ConstraintActiveAtTheOptimum) {
  const double w = 2 * kPi, expected = (1.0 * 0.1 - 1.0 / (w * w)) / 0.05;
  for (const char* c :
       {"rms.frame.shaking.F <= 1", "1 >= peak.frame.shaking.F", "rms.frame.shaking.F - 1"}) {
    OptimizeOptions o = crank("m_cw", 0, 5);
    o.subject_to = {c};
    // the progress says feasible exactly when the violation is within the tolerance (the CLI
    // printed "(infeasible)" for any violation > 0); the best design's last report is feasible
    int within = 0;
    bool last_best_feasible = false;
    o.progress = [&](const OptimizeProgress& p) {
      EXPECT_EQ(p.feasible, p.violation <= o.constraint_tol) << p.violation;
      within += p.violation > 0 && p.violation <= o.constraint_tol ? 1 : 0;
      if (p.improved) last_best_feasible = p.feasible;
    };
    const OptimizeResult r = optimize_scene(o);
    EXPECT_TRUE(last_best_feasible) << c;
    EXPECT_GT(within, 0) << c;  // the case the old message got wrong did occur
    EXPECT_EQ(r.method, "COBYLA");
    EXPECT_NEAR(r.x[0], expected, 1e-7) << c;
    ASSERT_EQ(r.constraints.size(), 1u);
    EXPECT_NEAR(r.constraints[0], 0, 1e-8) << c;
    EXPECT_TRUE(r.feasible) << c;
  }
  // a constraint no design meets: the least infeasible design, with a warning
  OptimizeOptions o = crank("m_cw", 0, 5);
  o.subject_to = {"rms.frame.shaking.F >= 100"};
  const OptimizeResult r = optimize_scene(o);
  EXPECT_FALSE(r.feasible);
  EXPECT_TRUE(has_warning(r, "no design evaluated satisfies every constraint"));
}

TEST(Optimize, BudgetsEndTheOptimization) {
  // evaluations: the start stops with a warning, its best design returned
  OptimizeOptions o = crank("rms.frame.shaking.F^2", 0, 5);
  o.max_evals = 3;
  OptimizeResult r = optimize_scene(o);
  EXPECT_EQ(r.evaluations, 3);
  EXPECT_EQ(r.stop, "max_evals");
  EXPECT_TRUE(has_warning(r, "--max-evals"));
  // wall time: evaluations made slow (100 ms each) against a budget of 0.35 s
  o = crank("rms.frame.shaking.F^2", 0, 5);
  o.starts = 50;
  o.max_seconds = 0.35;
  o.progress = [](const OptimizeProgress&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  };
  r = optimize_scene(o);
  EXPECT_EQ(r.stop, "max_seconds");
  EXPECT_TRUE(has_warning(r, "wall-time budget of 0.35 s (--max-seconds) ran out"));
  EXPECT_LE(r.evaluations, 5);
  EXPECT_GE(r.evaluations, 1);
  EXPECT_EQ(r.x.size(), 1u);
  // a budget that ends before the first run: an error, not a design
  o.progress = {};
  o.max_seconds = 1e-9;
  try {
    optimize_scene(o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ran out before the first run ended"), std::string::npos)
        << e.what();
  }
}

TEST(Optimize, StartsAreSeeded) {
  OptimizeOptions o = crank("rms.frame.shaking.F^2", 0, 5);
  o.starts = 3;
  o.max_evals = 1;
  const OptimizeResult a = optimize_scene(o), b = optimize_scene(o);
  o.seed = 2;
  const OptimizeResult c = optimize_scene(o);
  ASSERT_EQ(a.starts.size(), 3u);
  EXPECT_EQ(a.starts[0].x0[0], 0.0);  // the scene's value
  EXPECT_EQ(a.starts[1].x0, b.starts[1].x0);
  EXPECT_EQ(a.starts[2].x0, b.starts[2].x0);
  EXPECT_NE(a.starts[1].x0, c.starts[1].x0);
  EXPECT_NE(a.starts[1].x0, a.starts[2].x0);
}

TEST(Optimize, BadInputIsRefusedWithItsPlace) {
  OptimizeOptions o = crank("rms.frame.shaking.F^2", 0, 5);
  o.vary = {{"m_cww", 0, 1}};
  EXPECT_NE(error_of(o).find("'m_cww' is not a parameter of"), std::string::npos) << error_of(o);
  EXPECT_NE(error_of(o).find("did you mean 'm_cw'"), std::string::npos) << error_of(o);
  o.vary = {{"m_cw", 2, 1}};
  EXPECT_NE(error_of(o).find("LO < HI"), std::string::npos) << error_of(o);
  EXPECT_THROW(parse_design_variable("m_cw=2:2"), OptimizeInputError);
  EXPECT_THROW(parse_design_variable("m_cw=0"), OptimizeInputError);
  EXPECT_THROW(parse_design_variable("m_cw=0:nan"), OptimizeInputError);
  const DesignVariable v = parse_design_variable("m_cw=0.5:2e1");
  EXPECT_EQ(v.name, "m_cw");
  EXPECT_EQ(v.lo, 0.5);
  EXPECT_EQ(v.hi, 20);
  o = crank("rms.frame.shaking.F^", 0, 5);
  EXPECT_NE(error_of(o).find("objective 'rms.frame.shaking.F^', column 21"), std::string::npos)
      << error_of(o);
  o = crank("1 + peak.frame.shaking.G", 0, 5);
  EXPECT_NE(error_of(o).find("column 5: 'peak.frame.shaking.G': the run has no column"),
            std::string::npos)
      << error_of(o);
  EXPECT_NE(error_of(o).find("did you mean 'peak.frame.shaking.F'"), std::string::npos)
      << error_of(o);
  o = crank("m_cw < 1", 0, 5);
  EXPECT_NE(error_of(o).find("column 6: an objective is a number to minimize"), std::string::npos)
      << error_of(o);
  o = crank("m_cw", 0, 5);
  o.subject_to = {"m_cw < 1"};
  EXPECT_NE(error_of(o).find("constraint 1 'm_cw < 1', column 6"), std::string::npos)
      << error_of(o);
  o.subject_to = {"m_cw <= 1 + * 2"};  // the right side's column counts from the text's start
  EXPECT_NE(error_of(o).find("constraint 1 'm_cw <= 1 + * 2', column 13"), std::string::npos)
      << error_of(o);
  o.subject_to = {"m_cw <= 1 + rms.pivot.torqe"};
  EXPECT_NE(error_of(o).find("column 13: 'rms.pivot.torqe'"), std::string::npos) << error_of(o);
}

}  // namespace
}  // namespace optimize_test
