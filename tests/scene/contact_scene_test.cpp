// Contacts in scene files (issue 35; docs/scene-format.md, "Contacts"): the shipped bouncing ball
// run through the scene path (parse_scene, scene_forward, as `mo2d forward` and Python run it)
// against the closed forms, with the same events as the C++ core's contact_dynamics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double scene_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

std::vector<ContactEvent> scene_events_of_kind(const SceneRun& r, ContactEvent::Kind k) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& e : r.events)
    if (e.kind == k) out.push_back(e);
  return out;
}

// mechanisms/bouncing_ball.yaml: dropped with its centre at h, radius r, restitution e. Impact k
// (k = 0, 1, ...) at t1 + 2 v1 (e + ... + e^k) / g, t1 = sqrt(2 (h - r) / g), v1 = g t1, at the
// approach speed v1 e^k and the separation speed v1 e^(k+1); the flight after it rises to the
// rebound height (h - r) e^(2(k+1)) above the floor, read from every sample inside that flight as
// y - r + vy^2 / (2 g) (ballistic). The impulse is m (1 + e) v1 e^k, the loss (1 - e^2) m (v1
// e^k)^2 / 2.
TEST(ContactScene, BouncingBallFollowsTheClosedForms) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/bouncing_ball.yaml");
  ASSERT_EQ(scene.contacts.size(), 1U);
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  check_scene_options(scene, model, o);
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  const double h = scene_parameter(scene, "h"), r = scene_parameter(scene, "r");
  const double m = scene_parameter(scene, "m"), e = scene_parameter(scene, "e");
  const double g = scene_parameter(scene, "g");
  const std::vector<ContactEvent> hits = scene_events_of_kind(run, ContactEvent::Kind::impact);
  ASSERT_GE(hits.size(), 20U);
  const double t1 = std::sqrt(2 * (h - r) / g), v1 = g * t1;
  const Trajectory& tr = run.trajectory;
  const int iy = tr.column("ball.C.y"), ivy = tr.rate_column("ball.C.vy");
  double t = t1;
  int flights_checked = 0;
  for (size_t k = 0; k < 20; ++k) {
    const double v = v1 * std::pow(e, static_cast<double>(k));
    EXPECT_NEAR(hits[k].t, t, 1e-9) << "impact " << k;
    EXPECT_EQ(hits[k].contact, "floor");
    EXPECT_NEAR(hits[k].speed, v, 1e-9 * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].speed_after, e * v, 1e-9 * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].impulse, m * (1 + e) * v, 1e-9 * m * v1) << "impact " << k;
    EXPECT_NEAR(hits[k].energy_lost, 0.5 * m * v * v * (1 - e * e), 1e-9 * m * v1 * v1);
    const double next = t + 2 * e * v / g;
    const double height = (h - r) * std::pow(e, 2.0 * static_cast<double>(k + 1));
    for (Eigen::Index s = 0; s < tr.time.size(); ++s) {
      if (!(tr.time[s] > t + 1e-6 && tr.time[s] < next - 1e-6)) continue;
      const double vy = tr.q1(s, ivy);
      EXPECT_NEAR(tr.q0(s, iy) - r + vy * vy / (2 * g), height, 1e-9 * (h - r))
          << "flight after impact " << k << ", t = " << tr.time[s];
      ++flights_checked;
    }
    t = next;
  }
  EXPECT_GT(flights_checked, 200);
  // the accumulation at t_inf = t1 (1 + e) / (1 - e), then at rest on the floor
  const std::vector<ContactEvent> z = scene_events_of_kind(run, ContactEvent::Kind::zeno);
  ASSERT_EQ(z.size(), 1U);
  EXPECT_NEAR(z[0].predicted_t, t1 * (1 + e) / (1 - e), 1e-9);
  EXPECT_NEAR(tr.dissipated[tr.time.size() - 1], m * g * (h - r), 1e-9 * m * g * h);
}

// The scene path runs exactly the core's contact run: the same events as contact_dynamics with
// the scene's contacts and the method scene_forward reports.
TEST(ContactScene, SceneRunIsTheCoreContactRun) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/bouncing_ball.yaml");
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  const State initial = initial_state(scene, model);
  const SceneRun run = scene_forward(scene, model, initial, o);
  ContactOptions co = scene.contact;
  co.forward = o;
  const ContactRun core = contact_dynamics(model, scene.contacts, initial, co);
  ASSERT_EQ(run.events.size(), core.events.size());
  for (size_t k = 0; k < core.events.size(); ++k) {
    EXPECT_EQ(run.events[k].t, core.events[k].t) << k;
    EXPECT_EQ(run.events[k].speed, core.events[k].speed) << k;
  }
  EXPECT_NE(run.trajectory.stats.method.find("with contacts"), std::string::npos);
}

// mechanisms/cam_follower.yaml at omega: one turn of the cam through the scene path.
SceneRun cam_follower_at(double omega, Scene& scene) {
  char set[64];
  std::snprintf(set, sizeof set, "omega=%.17g", omega);
  const ParameterOverride o[] = {parse_override(set)};
  scene = load_scene(MO2D_MECHANISMS_DIR "/cam_follower.yaml", o);
  const Model model = build_scene_model(scene);
  const ForwardOptions run = forward_options(scene, model);
  check_scene_options(scene, model, run);
  return scene_forward(scene, model, initial_state(scene, model), run);
}

// The cam follower (see the scene's header): the contact force N = m g + P0 + ecc (k - m w^2)
// sin(w t) reaches 0 at the top of the lift at the critical speed w_c = sqrt((P0 + k ecc + m g) /
// (m ecc)), where the spring force and the weight equal the follower's mass times the cam's
// demanded acceleration ecc w^2. Below it: no event in a turn, the follower's face on the cam at
// y = R + ecc sin(w t) at every sample; above it: one lift-off in the turn, where sin(w t) = (m g +
// P0) / (ecc (m w^2 - k)), and each landing on the driven cam dissipates (1 - e^2) m v^2 / 2 (the
// cam's speed is imposed: the follower's mass alone) and leaves at e v.
TEST(ContactScene, CamFollowerLiftsOffAboveTheCriticalSpeed) {
  Scene scene;
  (void)cam_follower_at(100, scene);
  const double ecc = scene_parameter(scene, "ecc"), R = scene_parameter(scene, "R");
  const double m = scene_parameter(scene, "m"), k = scene_parameter(scene, "k");
  const double P0 = scene_parameter(scene, "P0"), g = scene_parameter(scene, "g");
  const double e = scene_parameter(scene, "e");
  const double wc = std::sqrt((P0 + k * ecc + m * g) / (m * ecc));
  for (const double ratio : {0.5, 0.9, 0.995, 1.005, 1.1, 1.5, 2.0}) {
    const double w = ratio * wc;
    const SceneRun run = cam_follower_at(w, scene);
    const std::vector<ContactEvent> off = scene_events_of_kind(run, ContactEvent::Kind::lift_off);
    const Trajectory& tr = run.trajectory;
    EXPECT_LT(std::abs(energy_balance_error(tr)), 1e-9) << "w / w_c = " << ratio;
    if (ratio < 1) {
      EXPECT_TRUE(run.events.empty()) << "w / w_c = " << ratio << ": " << run.events.size();
      const int iy = tr.column("follower.P.y");
      for (Eigen::Index s = 0; s < tr.time.size(); ++s)
        EXPECT_NEAR(tr.q0(s, iy), R + ecc * std::sin(w * tr.time[s]), 1e-9 * ecc)
            << "w / w_c = " << ratio << ", t = " << tr.time[s];
      continue;
    }
    ASSERT_EQ(off.size(), 1U) << "w / w_c = " << ratio;
    const double t_off = std::asin((m * g + P0) / (ecc * (m * w * w - k))) / w;
    EXPECT_NEAR(off[0].t, t_off, 1e-10) << "w / w_c = " << ratio;
    for (const ContactEvent& hit : scene_events_of_kind(run, ContactEvent::Kind::impact)) {
      const double v = hit.speed;
      EXPECT_GT(hit.t, off[0].t);
      // the Zeno accumulation's last impact is perfectly inelastic (e = 0, nothing after)
      const double ek = hit.speed_after == 0 ? 0 : e;
      EXPECT_NEAR(hit.energy_lost, (1 - ek * ek) * m * v * v / 2, 1e-9 * m * v * v + 1e-15)
          << "w / w_c = " << ratio << ", t = " << hit.t;
      EXPECT_NEAR(hit.speed_after, ek * v, 1e-9 * v) << "w / w_c = " << ratio << ", t = " << hit.t;
    }
  }
}

// A scene without contacts runs forward_dynamics as before: no events.
TEST(ContactScene, SceneWithoutContactsHasNoEvents) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/mass_spring_mass.yaml");
  ASSERT_TRUE(scene.contacts.empty());
  const Model model = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, model);
  o.t1 = o.t0 + 0.1;
  o.samples = 3;
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  EXPECT_TRUE(run.events.empty());
  EXPECT_EQ(run.trajectory.time.size(), 3);
}

}  // namespace
}  // namespace mo2d

// Cam profiles in scenes (issue 35; docs/contact.md, "Cam profiles"): the shipped
// mechanisms/cam_profile.yaml (a disc cam r(phi) = base + the lift law of cam_lift.csv under a
// knife-edge follower on a radial guide) against its closed forms, the lift law and the lift-off
// speed; and a second formulation: the eccentric circle cam of cam_follower.yaml as a `circle`
// target and as a profile table sampled from it, with the same events.
namespace mo2d {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kPhi0 = 330 * kPi / 180;  // cam_profile.yaml's start on its profile

double param(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

SceneRun run_scene(const Scene& scene) {
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  check_scene_options(scene, model, o);
  return scene_forward(scene, model, initial_state(scene, model), o);
}

int count(const SceneRun& r, ContactEvent::Kind k) {
  int n = 0;
  for (const ContactEvent& e : r.events) n += e.kind == k ? 1 : 0;
  return n;
}

Scene cam_profile(double omega) {
  const std::vector<ParameterOverride> set{{"omega", std::to_string(omega)}};
  return load_scene(MO2D_MECHANISMS_DIR "/cam_profile.yaml", set);
}

// The lift-off speed of cam_profile.yaml from the closed form (its description): the least over
// the cycle, where s'' < 0, of sqrt((m g + P0 + k s) / (-m s'')), s = r - base from the scene's
// spline itself (its exact s''), on a grid of 0.01 deg refined by golden section.
struct LiftOff {
  double omega = 0, phi = 0;
};
LiftOff lift_off_speed(const Scene& s) {
  const LookupTable& r = *s.contacts.at(0).profile;
  const double m = param(s, "m"), g = param(s, "g"), P0 = param(s, "P0"), k = param(s, "k");
  const double base = param(s, "base");
  auto w2 = [&](double phi) {
    const Jet j = r(Jet(phi, 1.0, 0.0));
    return j.dd < 0 ? (m * g + P0 + k * (j.v - base)) / (-m * j.dd) : 1e300;
  };
  double best = 1e300, at = 0;
  for (int i = 0; i < 36000; ++i) {
    const double phi = 2 * kPi * i / 36000;
    if (w2(phi) < best) {
      best = w2(phi);
      at = phi;
    }
  }
  double lo = at - 2 * kPi / 36000, hi = at + 2 * kPi / 36000;
  for (int i = 0; i < 60; ++i) {
    const double a = hi - 0.618 * (hi - lo), b = lo + 0.618 * (hi - lo);
    if (w2(a) < w2(b))
      hi = b;
    else
      lo = a;
  }
  return {std::sqrt(w2(0.5 * (lo + hi))), 0.5 * (lo + hi)};
}

// A knife-edge follower on the eccentric circle cam of cam_follower.yaml (the circle of radius R
// around cam.C, ecc off the shaft, pointing down at t = 0 with the follower at rest at its lowest),
// with a `circle` target.
constexpr const char* kEccentricKnife = R"(
name: eccentric_knife
parameters: {omega: 100, ecc: 0.01, R: 0.03, m: 0.5, k: 2000, P0: 10, H: 0.2, e: 0.3, g: 9.81}
ground: {O: [0, 0], G1: [0, 0.1], G2: [0, 0.2]}
bodies:
  cam: {nodes: {O: [0, 0], C: [0, -ecc]}, mass: 1.0, inertia: 4.5e-4, com: O}
  follower: {nodes: {P: [0, R - ecc]}, mass: m}
joints:
  cam_shaft: {type: revolute, node_a: ground.O, node_b: cam.O}
  guide: {type: prismatic, axis_from: ground.G1, axis_to: ground.G2, slider: follower.P}
coordinates:
  cam.angle: {rate: {cam.w: 1}}
constraints:
  drive: {psi: cam.angle + pi / 2 - omega * t}
loads:
  gravity: [0, -g]
  springs:
    return: {body_a: ground, point_a: [0, H], body_b: follower, point_b: [0, R - ecc],
             rest_length: H - R + ecc + P0 / k, stiffness: k}
contacts:
  cam: {point: follower.P, circle: cam.C, target_radius: R, law: rigid, restitution: e}
initial: {velocities: {follower.P.vy: 0}}
run: {solve: forward, duration: 2 * pi / omega, samples: 201, integrator: dopri5, rtol: 1e-10,
      atol: 1e-12}
)";

// The eccentric circle as a polar table about the shaft, phi from the axis O -> C:
// r(phi) = ecc cos phi + sqrt(R^2 - ecc^2 sin^2 phi), n + 1 points over a turn.
std::shared_ptr<const LookupTable> eccentric_table(double ecc, double R, int n) {
  std::vector<double> x, y;
  for (int i = 0; i <= n; ++i) {
    const double phi = 2 * kPi * i / n, s = std::sin(phi);
    x.push_back(phi);
    y.push_back(ecc * std::cos(phi) + std::sqrt(R * R - ecc * ecc * s * s));
  }
  return std::make_shared<const LookupTable>(
      "eccentric", x, y, TableOptions{Interpolation::cubic, Extrapolation::periodic});
}

// The largest |spline - r| and |spline'' - r''| over a fine grid.
struct SplineError {
  double r = 0, r2 = 0;
};
SplineError spline_error(const LookupTable& t, double ecc, double R) {
  SplineError out;
  for (int i = 0; i < 20000; ++i) {
    const double phi = 2 * kPi * i / 20000;
    auto exact = [&](double p) {
      const double s = std::sin(p);
      return ecc * std::cos(p) + std::sqrt(R * R - ecc * ecc * s * s);
    };
    const double h = 1e-4;
    const double r2 = (exact(phi + h) - 2 * exact(phi) + exact(phi - h)) / (h * h);
    const Jet j = t(Jet(phi, 1.0, 0.0));
    out.r = std::max(out.r, std::abs(j.v - exact(phi)));
    out.r2 = std::max(out.r2, std::abs(j.dd - r2));
  }
  return out;
}

}  // namespace

// The second formulation: the same cam as a profile table (n = 72 and 144 points) against the
// circle target. Along the circle run's samples the gaps differ by at most the spline's largest
// radial error (the two curves are that close), and the runs' events (a lift-off, impacts, ...)
// agree in kind and order, their times to within the lift-off's shift that the spline's r''
// error can cause (docs/contact.md, "Cam profiles").
TEST(CamProfile, EccentricTableAgreesWithTheCircleTarget) {
  const Scene circle = parse_scene(kEccentricKnife, "eccentric_knife.yaml");
  const double ecc = param(circle, "ecc"), R = param(circle, "R");
  const Model model = build_scene_model(circle);
  const SceneRun ref = run_scene(circle);
  ASSERT_GE(count(ref, ContactEvent::Kind::lift_off), 1);
  ASSERT_GE(count(ref, ContactEvent::Kind::impact), 1);
  for (int n : {72, 144}) {
    Scene profile = circle;
    ContactDef& c = profile.contacts[0];
    c.target = ContactDef::Target::profile;
    c.b = "cam.C";
    c.a = "cam.O";
    c.target_radius = 0;
    c.profile = eccentric_table(ecc, R, n);
    const SplineError err = spline_error(*c.profile, ecc, R);
    const Trajectory& tr = ref.trajectory;
    const Eigen::VectorXd v = Eigen::VectorXd::Zero(model.n1);
    for (Eigen::Index i = 0; i < tr.time.size(); ++i) {
      const Eigen::VectorXd q = tr.q0.row(i).transpose();
      const double dg = contact_gap(model, profile.contacts[0], q, v).g -
                        contact_gap(model, circle.contacts[0], q, v).g;
      EXPECT_LE(std::abs(dg), err.r * (1 + 1e-6) + 1e-15) << "n " << n << " t " << tr.time[i];
    }
    const SceneRun run = run_scene(profile);
    ASSERT_EQ(run.events.size(), ref.events.size()) << "n " << n;
    double worst = 0;
    for (size_t k = 0; k < run.events.size(); ++k) {
      EXPECT_EQ(run.events[k].kind, ref.events[k].kind) << "event " << k;
      worst = std::max(worst, std::abs(run.events[k].t - ref.events[k].t));
    }
    // the bound: the first event is the lift-off, where the contact force N = m (y'' + g) + P0 +
    // k (y - (R - ecc)) reaches 0; the spline's r'' error moves N by m omega^2 err.r2, so the
    // lift-off by at most that over |dN/dt| (from the exact y(t) = r(pi - omega t)), and the
    // flight carries that shift to the impacts
    const double w = param(circle, "omega"), m = param(circle, "m"), k = param(circle, "k");
    auto y = [&](double t) {
      const double s = std::sin(w * t);
      return -ecc * std::cos(w * t) + std::sqrt(R * R - ecc * ecc * s * s);
    };
    const double t0 = ref.events[0].t, h = 1e-4 / w;
    const double y1 = (y(t0 + h) - y(t0 - h)) / (2 * h);
    const double y3 =
        (y(t0 + 2 * h) - 2 * y(t0 + h) + 2 * y(t0 - h) - y(t0 - 2 * h)) / (2 * h * h * h);
    const double bound = m * w * w * err.r2 / std::abs(m * y3 + k * y1);
    std::printf(
        "n %d: spline error r %.3g m, r'' %.3g m/rad^2; event times differ by %.3g s "
        "(bound %.3g s)\n",
        n, err.r, err.r2, worst, bound);
    EXPECT_EQ(ref.events[0].kind, ContactEvent::Kind::lift_off);
    EXPECT_LT(worst, bound) << "n " << n;
  }
}

namespace {

// Metamorphic (as ContactMetamorphic.*): cam_profile.yaml in a frame rotated by a and translated
// by (dx, dy) (every point p -> R(a) p + d, gravity R(a) g, the drive's angle offset by a) runs
// with the same events: kinds, times, speeds and impulses. At omega = 70 rad/s: lift-offs and
// impacts.
std::string cam_in_frame(double a, double dx, double dy, const std::string& rtol = "1e-10") {
  auto at = [](const std::string& x, const std::string& y) {
    return "[dx + (" + x + ") * cos(a) - (" + y + ") * sin(a), dy + (" + x + ") * sin(a) + (" + y +
           ") * cos(a)]";
  };
  return "name: cam_frame\n"
         "parameters: {omega: 70, base: 0.04, m: 0.5, k: 2000, P0: 10, H: 0.2, e: 0.3, g: 9.81, "
         "a: " +
         std::to_string(a) + ", dx: " + std::to_string(dx) + ", dy: " + std::to_string(dy) +
         "}\n"
         "tables:\n"
         "  profile: {file: " MO2D_MECHANISMS_DIR
         "/cam_profile.csv, x: angle_deg, y: radius_mm, "
         "scale_x: pi / 180, scale_y: 1e-3, extrapolate: periodic}\n"
         "ground: {O: " +
         at("0", "0") + ", G1: " + at("0", "0.1") + ", G2: " + at("0", "0.2") +
         "}\n"
         "bodies:\n"
         "  cam: {nodes: {O: " +
         at("0", "0") + ", A: " + at("-0.015", "0.015 * sqrt(3)") +
         "}, mass: 1.0, inertia: 1e-3, com: O}\n"
         "  follower: {nodes: {P: " +
         at("0", "base") +
         "}, mass: m}\n"
         "joints:\n"
         "  cam_shaft: {type: revolute, node_a: ground.O, node_b: cam.O}\n"
         "  guide: {type: prismatic, axis_from: ground.G1, axis_to: ground.G2, slider: "
         "follower.P}\n"
         "coordinates:\n"
         "  cam.angle: {rate: {cam.w: 1}}\n"
         "constraints:\n"
         "  drive: {psi: cam.angle - 2 * pi / 3 - a + omega * t}\n"
         "loads:\n"
         "  gravity: [g * sin(a), -g * cos(a)]\n"
         "  springs:\n"
         "    return: {body_a: ground, point_a: " +
         at("0", "H") + ", body_b: follower, point_b: " + at("0", "base") +
         ", rest_length: H - base + P0 / k, stiffness: k}\n"
         "contacts:\n"
         "  cam: {point: follower.P, profile: [cam.O, cam.A], table: profile, law: rigid, "
         "restitution: e}\n"
         "initial: {velocities: {follower.P.vy: 0}}\n"
         "run: {solve: forward, duration: 2 * pi / omega, samples: 101, integrator: dopri5, "
         "rtol: " +
         rtol + ", atol: 1e-12}\n";
}

}  // namespace

// At a low speed the follower stays on the cam and its height is the table's law,
// y = base + s(phi0 + omega t) (phi0 = 330 deg) with s read from cam_lift.csv (the same spline up
// to round-off).
TEST(CamProfile, LiftAtLowSpeedIsTheTablesLaw) {
  const Scene scene = cam_profile(5);
  const SceneRun run = run_scene(scene);
  EXPECT_EQ(count(run, ContactEvent::Kind::lift_off), 0);
  EXPECT_EQ(count(run, ContactEvent::Kind::impact), 0);
  const LookupTable lift = read_table_csv(MO2D_MECHANISMS_DIR "/cam_lift.csv", "lift",
                                          {"angle_deg", "lift_mm", kPi / 180, 1e-3},
                                          {Interpolation::cubic, Extrapolation::periodic});
  const Trajectory& tr = run.trajectory;
  const int iy = tr.column("follower.P.y");
  const double base = param(scene, "base"), omega = param(scene, "omega");
  double worst = 0;
  for (Eigen::Index i = 0; i < tr.time.size(); ++i)
    worst = std::max(worst, std::abs(tr.q0(i, iy) - base - lift(kPhi0 + omega * tr.time[i])));
  EXPECT_LT(worst, 1e-9) << "largest |y - base - s(omega t)|";
  EXPECT_GT(tr.time.size(), 300);
}

// The closed form's lift-off speed separates the runs 1 % below (no lift-off in a turn) and 1 %
// above it (a lift-off, where the closed form's contact force N(phi) is 0: its multiplier).
TEST(CamProfile, LiftOffSpeedSeparatesStayingOnFromLiftingOff) {
  const LiftOff c = lift_off_speed(cam_profile(40));
  EXPECT_NEAR(c.omega, 59.58, 0.01) << "the value cam_profile.yaml and docs/contact.md give";
  const SceneRun below = run_scene(cam_profile(0.99 * c.omega));
  EXPECT_EQ(count(below, ContactEvent::Kind::lift_off), 0);
  const SceneRun above = run_scene(cam_profile(1.01 * c.omega));
  ASSERT_GE(count(above, ContactEvent::Kind::lift_off), 1);
  const Scene s = cam_profile(1.01 * c.omega);
  const LookupTable& r = *s.contacts.at(0).profile;
  const double m = param(s, "m"), g = param(s, "g"), P0 = param(s, "P0"), k = param(s, "k");
  const double w = param(s, "omega"), base = param(s, "base");
  for (const ContactEvent& e : above.events)
    if (e.kind == ContactEvent::Kind::lift_off) {
      const Jet j = r(Jet(kPhi0 + w * e.t, 1.0, 0.0));
      const double N = m * j.dd * w * w + m * g + P0 + k * (j.v - base);
      EXPECT_NEAR(N, 0, 1e-6 * (m * g + P0)) << "the closed form's force at the lift-off";
      break;
    }
}

TEST(CamProfile, EventsFollowRotationAndTranslation) {
  const SceneRun ref = run_scene(parse_scene(cam_in_frame(0, 0, 0), "cam_frame.yaml"));
  ASSERT_GE(count(ref, ContactEvent::Kind::lift_off), 1);
  ASSERT_GE(count(ref, ContactEvent::Kind::impact), 1);
  // the integration's own error is not invariant under the map (its step sequence changes): the
  // tolerances are 4 times the differences of the run given from the same run at rtol 1e-11
  const SceneRun tight = run_scene(parse_scene(cam_in_frame(0, 0, 0, "1e-11"), "cam_frame.yaml"));
  ASSERT_EQ(tight.events.size(), ref.events.size());
  double dt = 1e-12, dv = 1e-12, dp = 1e-12;
  for (size_t k = 0; k < ref.events.size(); ++k) {
    dt = std::max(dt, 4 * std::abs(tight.events[k].t - ref.events[k].t));
    dv = std::max(dv, 4 * std::abs(tight.events[k].speed - ref.events[k].speed));
    dp = std::max(dp, 4 * std::abs(tight.events[k].impulse - ref.events[k].impulse));
  }
  std::printf("tolerances: t %.3g s, speed %.3g m/s, impulse %.3g N s\n", dt, dv, dp);
  for (const auto& [a, dx, dy] : {std::tuple{0.7, 0.3, -1.2}, std::tuple{-0.6, -2.0, 0.5}}) {
    // rtol weighs the coordinates' magnitudes, which the translation raises from 0.2 m to
    // 0.2 m + |d|: scaled down by as much, so that both runs allow the same absolute error
    const double scale = 0.2 / (0.2 + std::hypot(dx, dy));
    char rtol[32];
    std::snprintf(rtol, sizeof rtol, "%.6g", 1e-10 * scale);
    const SceneRun run = run_scene(parse_scene(cam_in_frame(a, dx, dy, rtol), "cam_frame.yaml"));
    ASSERT_EQ(run.events.size(), ref.events.size()) << "a " << a;
    for (size_t k = 0; k < run.events.size(); ++k) {
      EXPECT_EQ(run.events[k].kind, ref.events[k].kind) << "a " << a << " event " << k;
      EXPECT_NEAR(run.events[k].t, ref.events[k].t, dt) << "a " << a << " event " << k;
      EXPECT_NEAR(run.events[k].speed, ref.events[k].speed, dv) << "a " << a << " event " << k;
      EXPECT_NEAR(run.events[k].impulse, ref.events[k].impulse, dp) << "event " << k;
    }
  }
}

}  // namespace mo2d
