// Summary values of a run (mo2d/design.hpp, design_summary): the input torque's mean, RMS,
// peak-to-peak, energy fluctuation and flywheel inertia against the closed forms of a crank
// turning at constant speed under gravity (u = m g r cos theta); the bearing load columns against
// the reactions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/design.hpp"
#include "mo2d/mo2d.hpp"

namespace design_summary_test {
namespace {

using namespace mo2d;
constexpr double kPi = std::numbers::pi;

// A crank of mass m, its centre of mass r from the ground pivot, at constant speed w for one turn:
// the torque that holds it is u = m g r cos(theta), so mean 0, RMS m g r / sqrt 2, peak-to-peak
// 2 m g r, and the energy it delivers swings by 2 m g r (its potential energy): the flywheel for
// a coefficient of speed fluctuation Cs is I = 2 m g r / (Cs w^2).
TEST(DesignSummary, CrankUnderGravityAtConstantSpeed) {
  const double m = 2, r = 0.15, g = 9.81, w = 3.0, cs = 0.02;
  System s("crank");
  s.set_gravity({0, -g});
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {0.3, 0}}},
              .mass = m,
              .inertia = 0.01,
              .com = CenterOfMass::between("O", "A", r / 0.3)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  const Model model = build_model(s);
  const std::vector<Prescribed> motion{{"crank.angle", [w](Jet t) { return w * t; }}};
  InverseOptions o;
  o.t0 = 0;
  o.t1 = 2 * kPi / w;
  o.samples = 2001;
  Trajectory run = inverse_dynamics(model, motion, o);
  const DesignRequest q{.bearings = true, .speed_fluctuation = cs};
  add_design_columns(model, run, q);
  const DesignSummary d = design_summary(model, run, q);
  ASSERT_EQ(d.efforts.size(), 1u);
  const EffortMeasures& e = d.efforts[0];
  const double mgr = m * g * r;
  EXPECT_EQ(e.input, "pivot.torque");
  EXPECT_NEAR(e.mean, 0, 1e-9 * mgr);
  EXPECT_NEAR(e.rms, mgr / std::sqrt(2.0), 1e-6 * mgr);
  EXPECT_NEAR(e.peak_to_peak, 2 * mgr, 1e-6 * mgr);
  EXPECT_NEAR(e.mean_speed, w, 1e-12 * w);
  EXPECT_NEAR(e.travel, 2 * kPi, 1e-12);
  // the trapezoid rule's error on E(t) = m g r sin(w t): (w h)^2 / 12 = 8.2e-7 of it (measured
  // 8.22e-7)
  const double dE_rel = 1.5e-6;
  EXPECT_NEAR(e.energy_fluctuation, 2 * mgr, dE_rel * 2 * mgr);
  EXPECT_NEAR(e.flywheel_inertia, 2 * mgr / (cs * w * w), dE_rel * 2 * mgr / (cs * w * w));
  // the bearing load: magnitude and direction of the pivot's reaction
  const int load = run.output("pivot.load"), dir = run.output("pivot.load_angle");
  const int fx = run.reaction("pivot.Fx"), fy = run.reaction("pivot.Fy");
  for (Eigen::Index k = 0; k < run.time.size(); k += 100) {
    const Vec2 F(run.reactions(k, fx), run.reactions(k, fy));
    EXPECT_NEAR(run.outputs(k, load) * std::cos(run.outputs(k, dir)), F.x(), 1e-12 * F.norm());
    EXPECT_NEAR(run.outputs(k, load) * std::sin(run.outputs(k, dir)), F.y(), 1e-12 * F.norm());
  }
  // without a coefficient there is no flywheel
  EXPECT_TRUE(std::isnan(design_summary(model, run, {}).efforts[0].flywheel_inertia));
}

}  // namespace
}  // namespace design_summary_test
