// The shipped slider-crank with a clearance at its wrist pin
// (mechanisms/slider_crank_clearance.yaml, issue 35), run through the scene path as `mo2d forward`
// runs it, against what holds whatever the rattling does:
//  - the pin never leaves its hole: |rod.B - slider.B| <= c at every sample, and = c while the
//    contact is persistent (from a Zeno accumulation to the next lift-off);
//  - the slider stays within the clearance's reach of the ideal slider-crank's closed form
//    x(theta) = r cos(theta) + sqrt(L^2 - r^2 sin^2(theta)): with rod.B within c of the slider,
//    |x - x(theta)| <= c sqrt(1 + k^2), k = r / sqrt(L^2 - r^2) the largest slope dx_B/dy_B of
//    the rod's end (to first order in c; reached where the pin sits in the hole's worst direction);
//  - each impact of the one contact separates at e times its approach speed, and the energy the
//    impacts dissipate closes the energy balance with the drive's work.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double clearance_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

// |rod.B - slider.B| at sample k
double pin_offset(const Trajectory& tr, Eigen::Index k) {
  const double dx = tr.q0(k, tr.column("rod.B.x")) - tr.q0(k, tr.column("slider.B.x"));
  const double dy = tr.q0(k, tr.column("rod.B.y")) - tr.q0(k, tr.column("slider.B.y"));
  return std::hypot(dx, dy);
}

TEST(ClearanceScene, PinStaysInItsHoleAndTheSliderWithinReachOfTheIdealMechanism) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/slider_crank_clearance.yaml");
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  const Trajectory& tr = run.trajectory;
  const double r = clearance_parameter(scene, "r"), L = clearance_parameter(scene, "L");
  const double c = clearance_parameter(scene, "c"), e = clearance_parameter(scene, "e");
  const double omega = clearance_parameter(scene, "omega");
  const double reach = c * std::sqrt(1 + r * r / (L * L - r * r));
  // the persistent phases: from each Zeno accumulation to the next lift-off (or the end)
  std::vector<std::pair<double, double>> held;
  for (const ContactEvent& ev : run.events) {
    if (ev.kind == ContactEvent::Kind::zeno) held.emplace_back(ev.t, INFINITY);
    if (ev.kind == ContactEvent::Kind::lift_off && !held.empty()) held.back().second = ev.t;
  }
  // an impact separates at e times its approach speed, but the last one of an accumulation,
  // perfectly inelastic (docs/contact.md), at 0
  int impacts = 0;
  double lost = 0;
  for (const ContactEvent& ev : run.events) {
    if (ev.kind != ContactEvent::Kind::impact) continue;
    ++impacts;
    lost += ev.energy_lost;
    bool last = false;
    for (const auto& [from, to] : held) last = last || ev.t == from;
    EXPECT_NEAR(ev.speed_after, last ? 0 : e * ev.speed, 1e-9 * ev.speed) << "impact at " << ev.t;
  }
  ASSERT_GT(impacts, 100);
  ASSERT_GE(held.size(), 2U);
  double worst = 0;
  int in_contact = 0;
  for (Eigen::Index k = 0; k < tr.time.size(); ++k) {
    const double t = tr.time[k], th = omega * t, s = r * std::sin(th);
    const double ideal = r * std::cos(th) + std::sqrt(L * L - s * s);
    worst = std::max(worst, std::abs(tr.q0(k, tr.column("slider.B.x")) - ideal));
    const double d = pin_offset(tr, k);
    EXPECT_LE(d, c + 1e-9) << "t = " << t;
    for (const auto& [from, to] : held)
      if (t > from && t < to) {
        EXPECT_NEAR(d, c, 1e-9) << "t = " << t << ", held from " << from;
        ++in_contact;
      }
  }
  EXPECT_GT(in_contact, 50);
  EXPECT_LE(worst, reach * (1 + 1e-3));
  EXPECT_GE(worst, 0.5 * reach);  // the clearance shows: the mechanism is not the ideal one
  // the impacts' losses are the run's dissipation, and the balance with the drive's work closes
  const Eigen::Index n = tr.time.size() - 1;
  EXPECT_NEAR(tr.dissipated[n], lost, 1e-12 + 1e-9 * lost);
  EXPECT_LT(energy_balance_error(tr), 1e-9 * tr.kinetic.maxCoeff());
}

}  // namespace
}  // namespace mo2d
