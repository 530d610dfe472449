// The shipped Geneva drive (mechanisms/geneva.yaml, issue 35), run through the scene path as `mo2d
// forward` runs it, against the closed form of the Geneva kinematics. With the wheel at O, the
// crank's centre at (C, 0), the crank angle alpha counterclockwise from the line of centres and
// the wheel's angle beta clockwise, the ideal wheel (its slot through the pin's centre) follows
//   tan(beta) = sin(alpha) / (C/R - cos(alpha)),   |alpha| <= alpha0 = pi/2 - pi/n,
// beta(+-alpha0) = +-pi/n: 2 pi/n per engagement for 2 alpha0 = 2 pi (1/2 - 1/n) of crank. The
// clearance bounds the real wheel's error whatever the rattling does: the slots are radial, so a
// pin whose centre is within h = w/2 - rp of the slot's centre line (no penetration) at the
// distance rho = |P - O| sees its slot's direction within asin(h / rho) of its own direction:
//   |beta - beta_ideal(alpha)| <= asin(h / rho)   while the pin is in a slot.
// The pin crosses a mouth (the line across the slot at W = sqrt(C^2 - R^2) from O) with its centre
// at most h off the centre line, so at rho in [W, sqrt(W^2 + h^2)]: the crank angle at each enter
// and leave event lies between alpha(rho = sqrt(W^2 + h^2)) and alpha(W) = -+alpha0, with
// cos(alpha(rho)) = (C^2 + R^2 - rho^2) / (2 C R).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double geneva_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

// the angle in (-pi, pi]
double wrapped(double a) {
  return std::remainder(a, 2 * std::numbers::pi);
}

TEST(GenevaScene, WheelFollowsTheClosedFormWithinTheClearance) {
  using std::numbers::pi;
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/geneva.yaml");
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  const Trajectory& tr = run.trajectory;
  const double R = geneva_parameter(scene, "R"), C = geneva_parameter(scene, "C");
  const double rp = geneva_parameter(scene, "rp"), c = geneva_parameter(scene, "c");
  const double omega = geneva_parameter(scene, "omega"), e = geneva_parameter(scene, "e");
  const int n = static_cast<int>(geneva_parameter(scene, "n"));
  const double h = c, W = std::sqrt(C * C - R * R), alpha0 = pi / 2 - pi / n;
  ASSERT_NEAR(std::atan2(std::sin(alpha0), C / R - std::cos(alpha0)), pi / n, 1e-15);
  auto alpha_at = [&](double rho) {  // the crank angle (in (0, pi)) where |P - O| = rho
    return std::acos((C * C + R * R - rho * rho) / (2 * C * R));
  };
  const double a_lo = alpha_at(std::sqrt(W * W + h * h)), a_hi = alpha_at(W);
  // the drive; the event times are located to ~1e-10 s (docs/contact.md), 1e-9 rad of crank
  auto alpha_of = [&](double t) { return wrapped(omega * t - pi); };
  // the engagements: enter and leave of one slot, in turn
  struct Engagement {
    std::string slot;
    double from, to;
  };
  std::vector<Engagement> eng;
  double lost = 0;
  int impacts = 0;
  for (const ContactEvent& ev : run.events) {
    if (ev.kind == ContactEvent::Kind::impact) {
      ++impacts;
      lost += ev.energy_lost;
      EXPECT_NEAR(ev.speed_after, ev.speed_after == 0 ? 0 : e * ev.speed, 1e-9 * ev.speed);
    }
    if (ev.kind == ContactEvent::Kind::enter) {
      ASSERT_TRUE(eng.empty() || eng.back().to < INFINITY) << "entered twice at " << ev.t;
      eng.push_back({ev.contact, ev.t, INFINITY});
      const double a = alpha_of(ev.t);  // entering at -alpha0, a hair earlier
      EXPECT_GE(-a, a_hi - 1e-9) << ev.contact << " entered at " << ev.t;
      EXPECT_LE(-a, a_lo + 1e-9) << ev.contact << " entered at " << ev.t;
    }
    if (ev.kind == ContactEvent::Kind::leave) {
      ASSERT_FALSE(eng.empty());
      EXPECT_EQ(ev.contact, eng.back().slot);
      eng.back().to = ev.t;
      const double a = alpha_of(ev.t);
      EXPECT_GE(a, a_hi - 1e-9) << ev.contact << " left at " << ev.t;
      EXPECT_LE(a, a_lo + 1e-9) << ev.contact << " left at " << ev.t;
    }
  }
  // three turns: slots 0, 1, 2 in turn (the wheel turns clockwise, slot k + 1 comes next)
  ASSERT_EQ(eng.size(), 3U);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(eng[k].slot, "slot" + std::to_string(k));
    EXPECT_LT(eng[k].to, INFINITY);
  }
  const Eigen::Index px = tr.column("crank.P.x"), py = tr.column("crank.P.y");
  const Eigen::Index bx = tr.column("wheel.B0.x"), by = tr.column("wheel.B0.y");
  int inside = 0, ends = 0;
  for (Eigen::Index i = 0; i < tr.time.size(); ++i) {
    const double t = tr.time[i];
    const double alpha = alpha_of(t);
    // the drive: the pin at D - R (cos alpha, sin alpha)
    EXPECT_NEAR(tr.q0(i, px), C - R * std::cos(alpha), 1e-9 * R) << t;
    EXPECT_NEAR(tr.q0(i, py), -R * std::sin(alpha), 1e-9 * R) << t;
    for (size_t k = 0; k < eng.size(); ++k) {
      // (the first entry, the wheel in line, is at -alpha0 exactly: a sample's time)
      if (!(t >= eng[k].from && t <= eng[k].to)) continue;
      // slot k's direction (counterclockwise from +x): wheel.B0's direction + k pi / 2
      const double psi = std::atan2(tr.q0(i, by), tr.q0(i, bx)) + static_cast<double>(k) * pi / 2;
      const double beta = -psi, ideal = std::atan2(std::sin(alpha), C / R - std::cos(alpha));
      const double rho = std::hypot(tr.q0(i, px), tr.q0(i, py));
      EXPECT_LE(std::abs(wrapped(beta - ideal)), std::asin(h / rho) + 1e-9) << "t = " << t;
      ++inside;
      // at alpha = -+alpha0 (samples: the run's grid holds them) the wheel is at -+pi/n within
      // asin(h / W): it turns 2 pi / n per engagement, within twice that
      if (std::abs(std::abs(alpha) - alpha0) < 1e-9) {
        EXPECT_LE(std::abs(wrapped(beta - (alpha > 0 ? 1 : -1) * pi / n)), std::asin(h / W) + 1e-9)
            << "t = " << t;
        ++ends;
      }
    }
  }
  EXPECT_GT(inside, 60);
  EXPECT_EQ(ends, 6);
  // the impacts' losses are the run's dissipation, and the balance with the drive's work closes
  ASSERT_GT(impacts, 3);
  const Eigen::Index last = tr.time.size() - 1;
  EXPECT_NEAR(tr.dissipated[last], lost, 1e-12 + 1e-9 * lost);
  EXPECT_GT(lost, 0);
  EXPECT_LT(energy_balance_error(tr), 1e-9 * tr.kinetic.maxCoeff());
  (void)rp;
}

// The output grid does not change the run: at 301 and 501 samples (other legs between output
// times, other steps), the same events at the same times. At these grids a lip hit's step also
// held the pin's entry, whose root search went back to the step's start after the lip's slack
// had been dropped, and found the handled impact again until the run was refused as chattering
// (docs/contact.md, "A pin in a slot").
TEST(GenevaScene, EventsDoNotDependOnTheOutputGrid) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/geneva.yaml");
  const Model model = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, model);
  const std::vector<ContactEvent> ref =
      scene_forward(scene, model, initial_state(scene, model), o).events;
  ASSERT_GT(ref.size(), 80U);
  for (const int samples : {301, 501}) {
    o.samples = samples;
    const std::vector<ContactEvent> ev =
        scene_forward(scene, model, initial_state(scene, model), o).events;
    ASSERT_EQ(ev.size(), ref.size()) << samples << " samples";
    for (size_t k = 0; k < ev.size(); ++k) {
      EXPECT_EQ(ev[k].kind, ref[k].kind) << k;
      EXPECT_EQ(ev[k].contact, ref[k].contact) << k;
      EXPECT_NEAR(ev[k].t, ref[k].t, 1e-9) << k << ", " << samples << " samples";
    }
  }
}

}  // namespace
}  // namespace mo2d
