// Metamorphic tests over generated mechanisms (docs/testing.md): relations that must hold on any
// valid mechanism without a reference solution. The generator (tests/metamorphic/generator.hpp)
// writes random valid mechanisms (open chains, four-bars, Watt six-bars, slider-cranks, pins in
// slots, subsystems placed several times, five-bars closed across subsystems; springs, dampers,
// torsional springs, point forces, torques, gravity; masses over four decades, sizes from 2 cm
// to 5 m, placed up to 20 sizes from the origin). For each one:
//   translate, rotate, mirror, reorder, scale (L, M, T): exact relations between two inverse runs;
//   Lagrange vs null space, flattened vs recursive complement: two formulations;
//   power balance: d/dt (kinetic + potential) = input + load power - dissipation, with energy
//     functions written here from the generator's data (not from mo2d's Model);
//   round trip: the inverse efforts fed to forward dynamics reproduce the motion;
//   forward energy: kinetic + potential + dissipated - input, load and constraint work constant
//     (all loads, every mechanism), and the forward energies equal the independent ones;
//   Box2D: the cross-check agrees (springs and loads translated, issue 32).
//
// Count and seed: MO2D_META_COUNT (default 300, 40 in a sanitizer build), MO2D_META_SEED
// (default 1; mechanism k has seed SEED + k). A failure prints the seed: reproduce it alone with
// MO2D_META_SEED=<seed> MO2D_META_COUNT=1. scripts/metamorphic.sh runs thousands.
//
// Tolerances (relative; documented in docs/testing.md, derived, not tuned):
//  - each quantity is compared relative to the largest value of its unit in the run (positions
//    relative to the mechanism's size), with dimensionally consistent floors (a force floor is
//    the largest torque over the size, ...);
//  - exact relations (transformations, formulations): 1e-8. The inverse solves positions to
//    1e-12 of the size by Newton; the generator rejects configurations whose dimensionless
//    conditioning sigma_min / sigma_max of [Psi; E] falls below 1e-2, so velocities,
//    accelerations and efforts (two more linear solves) carry at most ~(1/1e-2)^2 * 1e-12 = 1e-8;
//  - power balance: 1e-8 (the same bound: the balance is an identity of the solved quantities);
//  - round trip and forward energy: 1e-6: CVODE BDF at rtol 1e-10 (global error up to ~100 rtol)
//    times the measured amplification A <= 1e2 of the replay (more unstable replays are skipped
//    by the round trip; their energy relations run at rtol 1e-11, see check_mechanism);
//  - Box2D: its own tolerances (CrosscheckOptions, docs/crosscheck.md), default start and
//    feedback, the step scaled with the mechanism's time (h = tau / 640, i.e. 1/2000 s for a 1 m
//    mechanism), over [0, tau], on a variant of each mechanism with a damper, a drag law and
//    joint friction added and its masses compressed to a ratio <= 3 (check_box2d).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "metamorphic/generator.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;
using namespace mo2d::meta;

namespace {

constexpr double kExact = 1e-8;        // transformations and second formulations
constexpr double kPower = 1e-8;        // power balance of the inverse solution
constexpr double kForward = 1e-6;      // round trip and forward energy balance
constexpr int kSamples = 21;           // samples per run
constexpr double kBox2dMassRatio = 3;  // Box2D: largest body mass over the smallest
constexpr double kBox2dSpan = 1;       // Box2D: compared over [0, kBox2dSpan * Mechanism::time]
constexpr double kBox2dVelocityIterations = 50;
// Open disagreements of the Box2D relation on seeds 1..300 (default settings), listed so that they
// stay visible (printed as UNRESOLVED, counted as failures in the table) and the test fails when
// one of them starts agreeing or another one disagrees. Measured with
// MO2D_META_SEED=<seed> MO2D_META_COUNT=1 and MO2D_META_BOX2D_STEPS_PER_TAU=640/1280/2560,
// MO2D_META_BOX2D_VELOCITY_ITERATIONS=50/200 (docs/testing.md).
constexpr std::pair<std::uint64_t, const char*> kBox2dUnresolved[] = {
    {172,
     "Box2D's step: j19.torque RMS error 1.6 % of peak at tau/640, agrees at tau/2560 (first-order "
     "convergence of Box2D, not a mo2d error)"},
    {203,
     "not resolved: five26.j.torque RMS error 1.9 % at tau/640, 3.7 % at tau/1280, 1.1 % at "
     "tau/2560; 2.8 % with 200 velocity sweeps; the same without the added damper, drag, friction"},
    {276,
     "not resolved: j21.torque RMS error 1.5 % at tau/640, 3.0 % at tau/1280, 6.1 % at tau/2560 "
     "(grows as Box2D's step shrinks: the two models differ); 2.4 % with 200 velocity sweeps; the "
     "same without the added damper, drag, friction; all masses equal: 1.7 % at tau/640, 7.2 % at "
     "tau/2560"},
};

// ---- observations
// --------------------------------------------------------------------------------
enum class Unit { length, velocity, acceleration, rate, rate_dot, force, torque, energy };

struct Quantity {
  Unit unit = Unit::length;
  bool vector = false;
  bool axial = false;  // a pseudo-scalar: changes sign under a reflection (angles, rates, torques)
  bool position = false;  // a point: moves with a translation
  std::vector<Vec2> v{};  // per sample (y unused for scalars)
};
using Obs = std::map<std::string, Quantity>;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
Vec2 perp(const Vec2& v) {
  return {-v.y(), v.x()};
}
Vec2 rot(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
double wrap(double a) {
  return std::remainder(a, 2 * std::numbers::pi);
}

// Rigid motion of one body at one sample, from its nodes 0 and 1 (written here, not mo2d's).
struct BodyKin {
  Vec2 p0{0, 0}, v0{0, 0}, a0{0, 0}, P0{0, 0};
  double theta = 0, w = 0, wd = 0;  // rotation from the initial configuration, rate, its rate
  bool rigid = false;               // >= 2 nodes
  struct Point {
    Vec2 x, v, a;
  };
  Point at(const Vec2& X) const {  // a point given at the initial configuration
    const Vec2 r = rigid ? rot(X - P0, theta) : Vec2(0, 0);
    return {p0 + r, v0 + w * perp(r), a0 + wd * perp(r) - w * w * r};
  }
};

struct Kin {
  std::vector<BodyKin> bodies;
};

template <class R>
Kin kinematics(const Model& model, const Flat& flat, const R& r, int i,
               const std::map<std::string, NodeRef>& refs) {
  Kin k;
  const VectorXd q0 = r.q0.row(i).transpose(), q1 = r.q1.row(i).transpose(),
                 a1 = r.a1.row(i).transpose();
  (void)model;
  for (const FlatBody& b : flat.bodies) {
    BodyKin bk;
    const NodeRef& n0 = refs.at(b.node_labels[0]);
    bk.p0 = node_position(n0, q0), bk.v0 = node_velocity(n0, q1), bk.a0 = node_velocity(n0, a1);
    bk.P0 = b.nodes[0];
    if (b.nodes.size() >= 2) {
      const NodeRef& n1 = refs.at(b.node_labels[1]);
      const Vec2 d = node_position(n1, q0) - bk.p0, dv = node_velocity(n1, q1) - bk.v0,
                 da = node_velocity(n1, a1) - bk.a0, D = b.nodes[1] - b.nodes[0];
      bk.rigid = true;
      bk.theta = std::atan2(cross(D, d), D.dot(d));
      bk.w = cross(d, dv) / d.squaredNorm();
      bk.wd = cross(d, da) / d.squaredNorm();  // |d| is constant
    }
    k.bodies.push_back(bk);
  }
  return k;
}

BodyKin::Point point_of(const Kin& k, const FlatPoint& p) {
  if (p.body < 0) return {p.p, {0, 0}, {0, 0}};
  return k.bodies[p.body].at(p.p);
}
double rate_of(const Kin& k, int body) {
  return body < 0 ? 0.0 : k.bodies[body].w;
}
double angle_of(const Kin& k, int body) {
  return body < 0 ? 0.0 : k.bodies[body].theta;
}

struct Energy {
  double kinetic = 0, potential = 0;
  double power_residual = 0, power_scale = 0;  // inverse power balance at the sample
};

// Energies and the power balance of one sample from the generator's data.
template <class R>
Energy energy(const Model& model, const Flat& flat, const R& r, int i, const Kin& k) {
  Energy e;
  double dE = 0, scale = 0;
  auto add = [&](double p) {
    scale += std::abs(p);
    return p;
  };
  for (size_t b = 0; b < flat.bodies.size(); ++b) {
    const FlatBody& fb = flat.bodies[b];
    const auto c = k.bodies[b].at(fb.com);
    const double w = k.bodies[b].w;
    e.kinetic += 0.5 * fb.mass * c.v.squaredNorm() + 0.5 * fb.inertia * w * w;
    e.potential -= fb.mass * flat.gravity.dot(c.x);
    dE += add(fb.mass * c.v.dot(c.a) + fb.inertia * w * k.bodies[b].wd);
    dE += add(-fb.mass * flat.gravity.dot(c.v));
  }
  double P = 0;  // input + load power - dissipation
  for (const FlatSpring& s : flat.springs) {
    const auto a = point_of(k, s.a), b = point_of(k, s.b);
    const Vec2 d = b.x - a.x;
    const double l = d.norm(), ldot = d.dot(b.v - a.v) / l;
    e.potential += 0.5 * s.k * (l - s.rest) * (l - s.rest);
    dE += add(s.k * (l - s.rest) * ldot);
    P -= add(s.c * ldot * ldot);
  }
  for (const FlatTorsion& t : flat.torsionals) {
    const double th = wrap(angle_of(k, t.body2) - angle_of(k, t.body1));
    const double wr = rate_of(k, t.body2) - rate_of(k, t.body1);
    e.potential += 0.5 * t.k * th * th;
    dE += add(t.k * th * wr);
    P -= add(t.c * wr * wr);
  }
  const double time = r.time[i];
  for (const FlatForce& f : flat.forces) P += add(f.f(time).dot(point_of(k, f.at).v));
  for (const FlatTorque& t : flat.torques) P += add(t.tau(time) * rate_of(k, t.body));
  for (const FlatActuator& a : flat.actuators) {
    const int col = [&] {
      for (size_t c = 0; c < r.input_labels.size(); ++c)
        if (r.input_labels[c] == a.input) return static_cast<int>(c);
      throw Error("test: no input " + a.input);
    }();
    const double u = r.efforts(i, col);
    const double rate =
        a.revolute ? rate_of(k, a.body2) - rate_of(k, a.body1) : r.q1(i, model.rate(a.rate));
    P += add(u * rate);
  }
  e.power_residual = dE - P;
  e.power_scale = scale;
  return e;
}

std::map<std::string, NodeRef> node_refs(const Model& m) {
  std::map<std::string, NodeRef> out;
  for (const Body& b : m.bodies)
    for (size_t k = 0; k < b.nodes.size(); ++k) out[b.node_names[k]] = b.nodes[k];
  return out;
}

bool ends_with(const std::string& s, const std::string& t) {
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// Every output of a run by label: node positions, velocities, accelerations; body rates; efforts;
// reactions; slider coordinates; energies (independent functions).
template <class R>
Obs observe(const Model& model, const Flat& flat, const R& r,
            std::vector<Energy>* energies = nullptr) {
  Obs o;
  const auto refs = node_refs(model);
  const int n = static_cast<int>(r.time.size());
  auto put = [&](const std::string& key, Unit u, bool vec, bool axial, bool pos, int i, Vec2 v) {
    Quantity& q = o[key];
    if (q.v.empty()) q = {u, vec, axial, pos, std::vector<Vec2>(n, Vec2(0, 0))};
    q.v[i] = v;
  };
  for (int i = 0; i < n; ++i) {
    const VectorXd q0 = r.q0.row(i).transpose(), q1 = r.q1.row(i).transpose(),
                   a1 = r.a1.row(i).transpose();
    for (const auto& [label, ref] : refs) {
      put("p:" + label, Unit::length, true, false, true, i, node_position(ref, q0));
      put("v:" + label, Unit::velocity, true, false, false, i, node_velocity(ref, q1));
      put("a:" + label, Unit::acceleration, true, false, false, i, node_velocity(ref, a1));
    }
    const Kin k = kinematics(model, flat, r, i, refs);
    for (size_t b = 0; b < flat.bodies.size(); ++b)
      if (k.bodies[b].rigid) {
        put("w:" + flat.bodies[b].name, Unit::rate, false, true, false, i, {k.bodies[b].w, 0});
        put("wd:" + flat.bodies[b].name, Unit::rate_dot, false, true, false, i,
            {k.bodies[b].wd, 0});
      }
    for (size_t c = 0; c < r.input_labels.size(); ++c) {
      const bool torque = ends_with(r.input_labels[c], ".torque");
      put("u:" + r.input_labels[c], torque ? Unit::torque : Unit::force, false, torque, false, i,
          {r.efforts(i, c), 0});
    }
    for (size_t c = 0; c < r.reaction_labels.size(); ++c) {
      const std::string& l = r.reaction_labels[c];
      const std::string joint = l.substr(0, l.rfind('.'));
      const double x = r.reactions(i, c);
      if (ends_with(l, ".Fx") || ends_with(l, ".Fy")) {
        Quantity& q = o["R:" + joint];
        if (q.v.empty()) q = {Unit::force, true, false, false, std::vector<Vec2>(n, Vec2(0, 0))};
        (ends_with(l, ".Fx") ? q.v[i].x() : q.v[i].y()) = x;
      } else {
        put("RT:" + l, Unit::torque, false, true, false, i, {x, 0});
      }
    }
    for (int c = 0; c < model.n0; ++c)
      if (ends_with(model.coordinate_labels[c], ".q"))
        put("q:" + model.coordinate_labels[c], Unit::length, false, false, false, i, {q0[c], 0});
    const Energy e = energy(model, flat, r, i, k);
    if (energies) energies->push_back(e);
    put("E:kinetic", Unit::energy, false, false, false, i, {e.kinetic, 0});
    put("E:potential change", Unit::energy, false, false, false, i, {e.potential, 0});
  }
  auto& pe = o["E:potential change"].v;
  const double pe0 = pe[0].x();
  for (auto& v : pe) v.x() -= pe0;
  return o;
}

// What the observation of the transformed mechanism must be.
struct Transform {
  Vec2 d{0, 0};
  double angle = 0;
  bool mirror = false;
  double L = 1, M = 1, T = 1;
};

double unit_factor(Unit u, const Transform& t) {
  switch (u) {
    case Unit::length:
      return t.L;
    case Unit::velocity:
      return t.L / t.T;
    case Unit::acceleration:
      return t.L / (t.T * t.T);
    case Unit::rate:
      return 1 / t.T;
    case Unit::rate_dot:
      return 1 / (t.T * t.T);
    case Unit::force:
      return t.M * t.L / (t.T * t.T);
    case Unit::torque:
    case Unit::energy:
      return t.M * t.L * t.L / (t.T * t.T);
  }
  return 1;
}

Obs expected(const Obs& o, const Transform& t) {
  Obs out = o;
  for (auto& [key, q] : out) {
    const double f = unit_factor(q.unit, t);
    for (Vec2& v : q.v) {
      if (q.vector) {
        if (t.mirror) v.x() = -v.x();
        v = rot(f * v, t.angle);
        if (q.position) v += t.d;
      } else {
        v.x() *= f * (t.mirror && q.axial ? -1 : 1);
      }
    }
  }
  return out;
}

struct Deviation {
  double worst = 0;
  long checks = 0;
  std::string where{};
  void add(double dev, const std::string& w) {
    ++checks;
    if (!(dev <= worst)) worst = dev, where = w;  // NaN counts as worst
  }
};

// got against want, each value relative to the largest of its unit in `want` (positions relative
// to `length`), with dimensionally consistent floors.
Deviation compare(const Obs& got, const Obs& want, double length, const std::string& only = "") {
  std::map<Unit, double> peak;
  for (const auto& [key, q] : want)
    for (const Vec2& v : q.v) {
      const double m = q.vector ? v.norm() : std::abs(v.x());
      if (!q.position) peak[q.unit] = std::max(peak[q.unit], m);
    }
  auto P = [&](Unit u) { return peak.count(u) ? peak[u] : 0.0; };
  std::map<Unit, double> norm{
      {Unit::length, length},
      {Unit::velocity, std::max(P(Unit::velocity), P(Unit::rate) * length)},
      {Unit::acceleration, std::max(P(Unit::acceleration), P(Unit::rate_dot) * length)},
      {Unit::rate, std::max(P(Unit::rate), P(Unit::velocity) / length)},
      {Unit::rate_dot, std::max(P(Unit::rate_dot), P(Unit::acceleration) / length)},
      {Unit::force, std::max(P(Unit::force), P(Unit::torque) / length)},
      {Unit::torque, std::max(P(Unit::torque), P(Unit::force) * length)},
      {Unit::energy, std::max({P(Unit::energy), P(Unit::torque), P(Unit::force) * length})}};
  Deviation d;
  for (const auto& [key, q] : want) {
    if (!only.empty() && key.rfind(only, 0) != 0) continue;
    auto it = got.find(key);
    if (it == got.end() || it->second.v.size() != q.v.size()) {
      d.add(INFINITY, key + " missing");
      continue;
    }
    const double s = norm[q.unit] > 0 ? norm[q.unit] : 1e-300;
    for (size_t i = 0; i < q.v.size(); ++i) {
      const Vec2 e = it->second.v[i] - q.v[i];
      d.add((q.vector ? e.norm() : std::abs(e.x())) / s, key + " at sample " + std::to_string(i));
    }
  }
  return d;
}

// ---- runs ---------------------------------------------------------------------------------------
InverseOptions run_options(const Mechanism& m) {
  return {.t0 = 0, .t1 = m.t1, .samples = kSamples};
}

Obs inverse_obs(const Mechanism& m, Reduction reduction = Reduction::flat,
                ComplementMethod complement = ComplementMethod::prescribed, bool lagrange = false) {
  const Model model = build_model(to_system(m), {.reduction = reduction});
  InverseOptions o = run_options(m);
  o.complement = complement;
  const auto p = prescribed(m);
  const Trajectory r =
      lagrange ? inverse_dynamics_lagrange(model, p, o) : inverse_dynamics(model, p, o);
  return observe(model, flatten(m), r);
}

// ---- the summary table
// ---------------------------------------------------------------------------
struct Relation {
  std::string name;
  double tolerance = 0;
  long mechanisms = 0, checks = 0, failures = 0, skipped = 0;
  double worst = 0;
  std::uint64_t worst_seed = 0;
  std::string where{};
  std::map<std::string, long> skip_reasons{};
};

// A round trip that fails on a mechanism whose inverse run warned (positions jumped to another
// assembly mode, or a singular configuration passed between two samples) is a reported result,
// not a silent one: shown in the table as a failure and printed, but not a test failure. Found
// so: seed 184 (21 samples jump to the other branch of a slider-crank between t = 0 and 0.104 s;
// 201 samples stay on it; InverseBranchJumpBetweenSamplesIsReported), seeds 1005 and 5725 of the
// nightly run. Keeping the branch between samples is still to be done.

struct Table {
  std::vector<Relation> rows;
  Relation& row(const std::string& name, double tol) {
    for (auto& r : rows)
      if (r.name == name) return r;
    rows.push_back({name, tol});
    return rows.back();
  }
  // the inverse run's first warning, for the relations that replay it ("" if it warned nothing)
  std::string inverse_warning{};
  void record(const std::string& name, double tol, const Mechanism& m, const Deviation& d,
              bool replays_inverse = false, const char* unresolved = nullptr) {
    Relation& r = row(name, tol);
    ++r.mechanisms;
    r.checks += d.checks;
    if (!(d.worst <= r.worst)) r.worst = d.worst, r.worst_seed = m.seed, r.where = d.where;
    const bool ok = d.worst <= tol;
    if (!ok) ++r.failures;
    if (unresolved) {  // a listed open disagreement: reported, and it must still disagree
      std::printf("UNRESOLVED (seed %llu): %s: deviation %g (%s): %s\n",
                  static_cast<unsigned long long>(m.seed), name.c_str(), d.worst, d.where.c_str(),
                  unresolved);
      EXPECT_FALSE(ok) << name << " now agrees on seed " << m.seed
                       << ": remove it from the list of open disagreements";
      return;
    }
    const bool known = replays_inverse && !inverse_warning.empty();
    if (!ok && known)
      std::printf("REPORTED (seed %llu): %s: deviation %g (%s); the inverse run warned: %.160s\n",
                  static_cast<unsigned long long>(m.seed), name.c_str(), d.worst, d.where.c_str(),
                  inverse_warning.c_str());
    EXPECT_TRUE(ok || known) << name << ": deviation " << d.worst << " > " << tol << " (" << d.where
                             << ") on mechanism seed " << m.seed << " [" << m.family
                             << "]; reproduce: MO2D_META_SEED=" << m.seed << " MO2D_META_COUNT=1";
  }
  void skip(const std::string& name, double tol, const std::string& reason) {
    Relation& r = row(name, tol);
    ++r.skipped;
    ++r.skip_reasons[reason];
  }
  void failure(const std::string& name, double tol, const Mechanism& m, const std::string& what) {
    Deviation d;
    d.add(INFINITY, what);
    record(name, tol, m, d);
  }
  void print() const {
    std::printf("\n%-34s %6s %7s %10s %9s %10s %10s %s\n", "relation", "mech.", "skipped", "checks",
                "failures", "worst", "tolerance", "worst at (seed: where)");
    for (const auto& r : rows)
      std::printf("%-34s %6ld %7ld %10ld %9ld %10.2e %10.1e %llu: %s\n", r.name.c_str(),
                  r.mechanisms, r.skipped, r.checks, r.failures, r.worst, r.tolerance,
                  static_cast<unsigned long long>(r.worst_seed), r.where.c_str());
    for (const auto& r : rows)
      for (const auto& [reason, n] : r.skip_reasons)
        std::printf("  %s skipped %ld: %s\n", r.name.c_str(), n, reason.c_str());
  }
};

long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}
double env_double(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtod(v, nullptr) : fallback;
}

// What the mechanisms the Box2D relation compared carried (printed after the table).
struct Box2DContent {
  long compared = 0, springs = 0, dampers = 0, torsional = 0, state_loads = 0, friction = 0;
  void count(const Model& m) {
    ++compared;
    bool k = false, c = false, law = false;
    for (const SpringLoad& sp : m.springs) {
      k = k || sp.stiffness > 0;
      c = c || (sp.stiffness == 0 && sp.damping > 0);
    }
    for (const TorqueLoad& t : m.torques) law = law || !t.torque.args.empty();
    for (const PointLoad& f : m.forces) law = law || !f.fx.args.empty() || !f.fy.args.empty();
    springs += k;
    dampers += c;
    torsional += !m.torsional_springs.empty();
    state_loads += law;
    friction += !m.frictions.empty();
  }
};
Box2DContent box2d_content;

// The generated mechanism with its body masses brought within Box2D's range (issue 32): Box2D's
// sequential-impulse solver fails on mass ratios beyond ~10 (docs/crosscheck.md), the generator
// spreads masses over four decades. Each mass m (subsystems included) becomes
// g (m / g)^a, g the geometric mean of the masses, a = min(1, log(ratio) / log(max / min)): the
// order of the masses is kept, their ratio becomes at most `ratio`; each inertia is multiplied by
// the same factor (radius of gyration, centre of mass and geometry kept; a point mass stays one).
// Then all masses and inertias are multiplied by one factor that keeps the root's total mass (the
// generator's springs, forces and torques scale with it). Loads, springs and motion are unchanged.
// Both engines then compare this same mechanism.
Mechanism mass_compressed(const Mechanism& mech, double ratio) {
  Mechanism out = mech;
  std::vector<BodySpec*> bodies;
  for (SystemSpec* s : [&] {
         std::vector<SystemSpec*> v{&out.root};
         for (auto& sub : out.subs) v.push_back(&sub);
         return v;
       }())
    for (BodySpec& b : s->bodies)
      if (b.mass > 0) bodies.push_back(&b);
  if (bodies.empty()) return out;
  double lo = INFINITY, hi = 0, log_sum = 0;
  for (const BodySpec* b : bodies)
    lo = std::min(lo, b->mass), hi = std::max(hi, b->mass), log_sum += std::log(b->mass);
  if (!(hi > ratio * lo)) return out;
  const double g = std::exp(log_sum / static_cast<double>(bodies.size()));
  const double a = std::log(ratio) / std::log(hi / lo);
  auto root_mass = [&] {
    double sum = 0;
    for (const BodySpec& b : out.root.bodies) sum += b.mass;
    return sum;
  };
  const double before = root_mass();
  for (BodySpec* b : bodies) {
    const double m = g * std::pow(b->mass / g, a);
    b->inertia *= m / b->mass;
    b->mass = m;
  }
  // The generator's springs, forces and torques scale with the root's weight: keep it.
  const double after = root_mass(), f = after > 0 && before > 0 ? before / after : 1.0;
  for (BodySpec* b : bodies) b->mass *= f, b->inertia *= f;
  return out;
}

// An error planted in mo2d's side of the Box2D relation only (MO2D_META_BOX2D_PLANT), to show
// that the relation can fail: "inertia" (the first rotating root body's inertia 20 % high),
// "mass" (its mass 20 % high), "drag" (the drag law of box2d_variant with its sign flipped).
enum class Plant { none, inertia, mass, drag };

// The mechanism the Box2D relation compares (issue 32): the generated one plus, on its root, a
// pure damper (k = 0) from a ground point to the first rotating body's first node, a drag torque
// -c w on that body (a law of the state) and viscous and Coulomb friction in the first unactuated
// revolute joint. Magnitudes from the body's mass, the mechanism's length L and time tau: damper
// 0.5 m / tau, drag 0.2 m L^2 / tau, friction viscous 0.05 m L^2 / tau, mu 0.1 with a pin radius
// of L / 50. *added counts the elements added.
System box2d_variant(const Mechanism& generated, int* added, Plant plant = Plant::none) {
  Mechanism mech = generated;
  if (plant == Plant::inertia || plant == Plant::mass)
    for (BodySpec& b : mech.root.bodies) {
      if (!b.rotates() || !(b.mass > 0)) continue;
      (plant == Plant::mass ? b.mass : b.inertia) *= 1.2;
      break;
    }
  System sys = to_system(mech);
  *added = 0;
  const double L = mech.length, tau = mech.time;
  for (const BodySpec& b : generated.root.bodies) {  // magnitudes from the unplanted masses
    if (!b.rotates() || b.nodes.empty() || !(b.mass > 0)) continue;
    const Vec2 p = b.nodes.front().position;
    sys.add_spring({.name = "box2d_damper",
                    .body_a = "ground",
                    .point_a = p + Vec2(0.3 * L, -0.4 * L),
                    .body_b = b.name,
                    .point_b = p,
                    .rest_length = 0.5 * L,
                    .damping = 0.5 * b.mass / tau});
    const double c = (plant == Plant::drag ? -0.2 : 0.2) * b.mass * L * L / tau;
    sys.add_torque(
        {.name = "box2d_drag",
         .body = b.name,
         .torque = Law({b.name + ".w"}, [c](std::span<const Jet> x, Jet) { return -c * x[0]; })});
    *added += 2;
    break;
  }
  for (const RevoluteDef& j : mech.root.revolutes) {
    if (j.actuated) continue;
    double m = 0;
    for (const BodySpec& b : generated.root.bodies) m = std::max(m, b.mass);
    sys.add_friction({.name = "box2d_friction",
                      .joint = j.name,
                      .viscous = 0.05 * m * L * L / tau,
                      .mu = 0.1,
                      .radius = L / 50});
    ++*added;
    break;
  }
  return sys;
}

// Box2D relation (issue 32): springs as distance joints or forces, torsional springs and loads
// translated (crosscheck/box2d_loads.cpp), the library's default start (settling on the motion
// before t0) and feedback, the step scaled with the mechanism's time (tau / 640), compared over
// [0, min(t1, tau)] (kBox2dSpan: the whole run, 3 tau, costs 3x as much; CI's time). Compared:
//  - the mass-compressed variant (mass_compressed, box2d_variant): Box2D's sequential impulses
//    fail on mass ratios beyond ~10 (seeds 1..300 as generated, no limit: 295 compared, 77
//    disagree, the smallest ratio among them 68.8; more velocity sweeps made it worse), the
//    generator spreads masses over four decades. Ratio 3 (kBox2dMassRatio): at 10, chain3 seeds
//    53 and 262 still disagree (j2.torque max 4.1 %, RMS 26 %) and 7 in all over [0, tau]; at 3
//    with 50 sweeps, the three listed in kBox2dUnresolved; 20 sweeps: 6, 30 sweeps: 4.
//  - Box2D settled before t0: where the motion cannot be solved before t0 (it leaves the
//    workspace just before the start), the cross-check starts cold and skips 10 steps; that
//    start is not what its tolerances were measured for (seed 204, ratio 22: 17 % RMS). Those
//    are skipped and counted.
// Knobs (to measure, not for CI): MO2D_META_BOX2D_COMPRESS (target ratio, 0: as generated),
// MO2D_META_BOX2D_RATIO (refuse above), MO2D_META_BOX2D_SPAN (in tau),
// MO2D_META_BOX2D_STEPS_PER_TAU, MO2D_META_BOX2D_VELOCITY_ITERATIONS, MO2D_META_BOX2D_PLAIN (no
// added damper, drag, friction), MO2D_META_BOX2D_PLANT (an error in mo2d's side only).
void check_box2d(const Mechanism& mech, const Flat& flat, std::span<const Prescribed> motion,
                 Table& table, bool verbose) {
  double generated_ratio = 0;
  {
    double lo = INFINITY, hi = 0;
    for (const FlatBody& b : flat.bodies) lo = std::min(lo, b.mass), hi = std::max(hi, b.mass);
    generated_ratio = hi / lo;
  }
  const double target = env_double("MO2D_META_BOX2D_COMPRESS", kBox2dMassRatio);
  const Mechanism compressed = target > 0 ? mass_compressed(mech, target) : mech;
  double mmin = INFINITY, mmax = 0;
  for (const FlatBody& b : flatten(compressed).bodies)
    mmin = std::min(mmin, b.mass), mmax = std::max(mmax, b.mass);
  const double ratio_limit = env_double("MO2D_META_BOX2D_RATIO", kBox2dMassRatio);
  const std::string box2d = "Box2D cross-check";
  if (mmax > ratio_limit * mmin * (1 + 1e-12)) {
    table.skip(box2d, 1.0, "mass ratio > limit");
    return;
  }
  CrosscheckOptions c;  // the library's defaults, but the step
  c.step = mech.time / env_double("MO2D_META_BOX2D_STEPS_PER_TAU", 640);
  c.velocity_iterations =
      static_cast<int>(env_double("MO2D_META_BOX2D_VELOCITY_ITERATIONS", kBox2dVelocityIterations));
  const double t1 = std::min(mech.t1, env_double("MO2D_META_BOX2D_SPAN", kBox2dSpan) * mech.time);
  CrosscheckReport r;
  int added = 0;
  const char* plant_name = std::getenv("MO2D_META_BOX2D_PLANT");
  const std::string pn = plant_name ? plant_name : "";
  const Plant plant = pn == "inertia" ? Plant::inertia
                      : pn == "mass"  ? Plant::mass
                      : pn == "drag"  ? Plant::drag
                                      : Plant::none;
  const bool plain = env_double("MO2D_META_BOX2D_PLAIN", 0) != 0;
  const System variant = plain ? to_system(compressed) : box2d_variant(compressed, &added);
  try {
    if (plant == Plant::none) {
      r = crosscheck_inverse(variant, motion, {.t0 = 0, .t1 = t1}, c);
    } else {  // mo2d's reference carries the planted error, Box2D simulates the variant
      int unused = 0;
      const Model reference = build_model(box2d_variant(compressed, &unused, plant));
      const Model simulated = build_model(variant, {.reduction = Reduction::none});
      r = crosscheck_inverse(reference, simulated, motion, {.t0 = 0, .t1 = t1}, c);
    }
  } catch (const std::exception& e) {
    table.failure(box2d, 1.0, mech, std::string("threw: ") + e.what());
    return;
  }
  if (r.settle_steps == 0) {
    table.skip(box2d, 1.0, "Box2D cannot settle (motion not solvable before t0)");
    return;
  }
  Deviation d;
  // deviation: the worst error over its tolerance (agreement <=> <= 1)
  d.add(std::max({r.effort_rms / c.effort_rms_tolerance, r.effort_max / c.effort_max_tolerance,
                  r.reaction_rms / c.reaction_rms_tolerance,
                  r.reaction_max / c.reaction_max_tolerance}),
        (r.failures.empty() ? "agree" : r.failures.front()) + ", mass ratio " +
            std::to_string(mmax / mmin) + " (generated " + std::to_string(generated_ratio) + ")");
  d.checks = r.compared_steps;
  if (verbose)
    std::printf("  Box2D: mass ratio %.3g, %d compared steps, deviation %.3g (%s)\n", mmax / mmin,
                r.compared_steps, d.worst, d.where.c_str());
  const char* unresolved = nullptr;
  for (const auto& [seed, why] : kBox2dUnresolved)
    if (seed == mech.seed && plant == Plant::none) unresolved = why;
  table.record(box2d, 1.0, mech, d, false, unresolved);
  box2d_content.count(build_model(variant, {.reduction = Reduction::none}));
}

// ---- relations on one mechanism -----------------------------------------------------------------
void check_mechanism(const Mechanism& mech, Table& table) {
  Rng rng(mech.seed ^ 0x9e3779b97f4a7c15ull);
  const System sys = to_system(mech);
  const Model model = build_model(sys);
  const Flat flat = flatten(mech);
  const auto motion = prescribed(mech);
  const Trajectory base = inverse_dynamics(model, motion, run_options(mech));
  table.inverse_warning = base.stats.warnings.empty() ? "" : base.stats.warnings.front();
  std::vector<Energy> energies;
  const Obs o = observe(model, flat, base, &energies);
  const double L = mech.length;

  const bool verbose = std::getenv("MO2D_META_VERBOSE") != nullptr;
  if (verbose) {
    std::printf("mechanism %llu [%s]\n", static_cast<unsigned long long>(mech.seed),
                mech.family.c_str());
    for (const std::string& w : base.stats.warnings)
      std::printf("  inverse warning: %s\n", w.c_str());
  }
  auto relation = [&](const std::string& name, double tol, auto&& run) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      table.record(name, tol, mech, run(), name == "inverse -> forward round trip");
    } catch (const std::exception& e) {
      table.failure(name, tol, mech, std::string("threw: ") + e.what());
    }
    if (verbose)
      std::printf("  %-36s %8.3f s\n", name.c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::fflush(stdout);
  };

  relation("translate (ground included)", kExact, [&] {
    Transform t;
    t.d = L * rng.uniform(5, 50) * rng.direction();
    return compare(inverse_obs(translated(mech, t.d)), expected(o, t), L);
  });
  relation("rotate (gravity, loads too)", kExact, [&] {
    Transform t;
    t.angle = rng.uniform(-3.14159, 3.14159);
    return compare(inverse_obs(rotated(mech, t.angle)), expected(o, t), L);
  });
  relation("mirror x -> -x", kExact, [&] {
    Transform t;
    t.mirror = true;
    return compare(inverse_obs(mirrored(mech)), expected(o, t), L);
  });
  relation("reorder nodes, bodies, joints", kExact,
           [&] { return compare(inverse_obs(reordered(mech, rng.integer(0, 1 << 30))), o, L); });
  relation("scale L, M, T", kExact, [&] {
    Transform t;
    t.L = rng.log_uniform(0.1, 10), t.M = rng.log_uniform(0.1, 10), t.T = rng.log_uniform(0.1, 10);
    return compare(inverse_obs(scaled(mech, t.L, t.M, t.T)), expected(o, t), t.L * L);
  });
  relation("Lagrange vs null space", kExact, [&] {
    return compare(inverse_obs(mech, Reduction::none, ComplementMethod::prescribed, true), o, L);
  });
  relation("recursive vs flattened complement", kExact, [&] {
    return compare(
        inverse_obs(mech, mech.has_subsystems() ? Reduction::subsystems : Reduction::flat,
                    ComplementMethod::recursive),
        o, L);
  });
  relation("power balance (all loads)", kPower, [&] {
    Deviation d;
    double scale = 0;
    for (const Energy& e : energies) scale = std::max(scale, e.power_scale);
    for (size_t i = 0; i < energies.size(); ++i)
      d.add(std::abs(energies[i].power_residual) / scale, "sample " + std::to_string(i));
    return d;
  });

  // inverse -> forward: the efforts of the inverse solution reproduce its motion. Replaying
  // efforts open loop is unstable on some mechanisms (a spring pulling a driven slider-crank
  // away, a light chain under gravity): an error of the integrator grows like a perturbation.
  // The amplification A is measured first (cheap runs at rtol 1e-7, efforts scaled by 1 + 1e-6):
  // if a 1e-6 relative change of the efforts moves the motion (positions or velocities) by more
  // than 1e-4 (A > 1e2), the round trip cannot be resolved to 1e-6 (BDF's global error at rtol
  // 1e-10 is up to ~100 rtol, times A) and the mechanism is counted as skipped ("unstable
  // replay").
  const State s0{0, base.q0.row(0).transpose(), base.q1.row(0).transpose()};
  auto replay = [&](double rtol, double factor, long max_steps) {
    ForwardOptions fo{.t0 = 0,
                      .t1 = mech.t1,
                      .samples = kSamples,
                      .integrator = Integrator::cvode_bdf,
                      .rtol = rtol,
                      .atol = rtol * std::min(1.0, L)};
    fo.max_steps = max_steps;  // a stall is a result, not a hang
    for (auto& f : efforts_from_inverse(model, motion, run_options(mech)))
      fo.efforts.push_back([f, factor](double t) { return factor * f(t); });
    return forward_dynamics(model, s0, fo);
  };
  double amplification = INFINITY;
  try {
    const Trajectory a = replay(1e-7, 1.0, 20000), b = replay(1e-7, 1.0 + 1e-6, 20000);
    // positions and velocities: the relation compares both (velocities amplify more on some
    // mechanisms: seed 124, positions 1e2, velocities 2e5 x rtol)
    const auto ob = observe(model, flat, b), oa = observe(model, flat, a);
    amplification = std::max(compare(ob, oa, L, "p:").worst, compare(ob, oa, L, "v:").worst) / 1e-6;
  } catch (const Error&) {  // the cheap runs ran out of steps: treated as unstable
  }
  // The replay itself (CVODE BDF, the default integrator) runs on every mechanism: an unstable
  // replay leaves the inverse motion, but whatever motion it follows must still balance its
  // energy and have the independent energies. The balance error is the sum of the local errors
  // of the steps (a perturbation is not amplified: the perturbed motion balances too), about
  // N rtol of the energy scale after N steps. A resolvable replay takes a few hundred steps at
  // rtol 1e-10 (at most 9383 on seeds 1..300); an unstable one can take 1e4-1e5 (seed 163:
  // 33856 steps, balance 1.4e-6 of the scale; 1.9e-7 at rtol 1e-11, 3e-8 at 1e-12: integration
  // error, not a missing term), so it runs at rtol 1e-11 with a budget of 20000 steps
  // (N rtol <= 2e-7; rtol 1e-12 is beyond what BDF holds in double precision: seed 129's step
  // collapses at t = 2e-4 s). Where the budget runs out (the open-loop motion nears a singular
  // configuration, seed 129 at rtol 1e-10: the step collapses to 1e-7 s at t = 0.025 s and dopri5
  // reports a singular configuration at t = 0.022 s), the forward relations are skipped and
  // counted. dopri5 at rtol 1e-10 stalls on some mechanisms (seed 15: more than 200000 steps
  // where BDF needs 315; docs/testing.md).
  const bool resolvable = amplification <= 1e2;
  Trajectory fr;
  bool forward_ok = false;
  std::string forward_error;
  try {
    fr = replay(env_double("MO2D_META_RTOL", resolvable ? 1e-10 : 1e-11), 1.0,
                resolvable ? 100000 : 20000);
    forward_ok = true;
    if (verbose)
      std::printf("  replay: amplification %g, %ld steps\n", amplification, fr.stats.steps);
  } catch (const Error& e) {
    forward_error = e.what();
  }
  if (!resolvable) {
    table.skip("inverse -> forward round trip", kForward, "unstable replay (amplification > 1e2)");
  } else {
    relation("inverse -> forward round trip", kForward, [&] {
      if (!forward_ok) throw Error(forward_error);
      Deviation d = compare(observe(model, flat, fr), o, L, "p:");
      const Deviation dv = compare(observe(model, flat, fr), o, L, "v:");
      if (!(dv.worst <= d.worst)) d.worst = dv.worst, d.where = dv.where;
      d.checks += dv.checks;
      return d;
    });
  }
  if (!forward_ok && resolvable) {
    const std::string why = "forward run failed: " + forward_error;
    table.failure("forward energies = independent ones", kForward, mech, why);
    table.failure("forward energy balance (all loads)", kForward, mech, why);
  } else if (!forward_ok) {
    const std::string why = "unstable replay ran out of its step budget";
    table.skip("forward energies = independent ones", kForward, why);
    table.skip("forward energy balance (all loads)", kForward, why);
    if (verbose) std::printf("  %s\n", forward_error.c_str());
  }
  if (forward_ok) {
    relation("forward energies = independent ones", kForward, [&] {
      std::vector<Energy> mine;
      observe(model, flat, fr, &mine);
      Deviation d;
      double scale = 0;
      for (int i = 0; i < fr.time.size(); ++i)
        scale = std::max(
            {scale, std::abs(mine[i].kinetic), std::abs(mine[i].potential - mine[0].potential)});
      for (int i = 0; i < fr.time.size(); ++i) {
        d.add(std::abs(fr.kinetic[i] - mine[i].kinetic) / scale, "kinetic at " + std::to_string(i));
        d.add(std::abs(fr.potential[i] - mine[i].potential) / scale,
              "potential at " + std::to_string(i));
      }
      return d;
    });
    // kinetic + potential (the independent functions of this file, not mo2d's) - the works of
    // the inputs, loads and moving constraints + the dissipation, all integrated by the run, is
    // constant; and so is mo2d's energy_balance(fr) (its own energies). On every mechanism, with
    // every load.
    relation("forward energy balance (all loads)", kForward, [&] {
      std::vector<Energy> mine;
      observe(model, flat, fr, &mine);
      auto at = [](const VectorXd& v, int i) { return v.size() > i ? v[i] : 0.0; };
      const VectorXd lib = energy_balance(fr);
      double scale = 0;
      for (int i = 0; i < fr.time.size(); ++i)
        scale = std::max({scale, std::abs(mine[i].kinetic),
                          std::abs(mine[i].potential - mine[0].potential),
                          std::abs(at(fr.input_work, i)), std::abs(at(fr.load_work, i)),
                          std::abs(at(fr.constraint_work, i)), std::abs(at(fr.dissipated, i))});
      auto balance = [&](int i) {
        return mine[i].kinetic + mine[i].potential - at(fr.input_work, i) - at(fr.load_work, i) -
               at(fr.constraint_work, i) + at(fr.dissipated, i);
      };
      Deviation d;
      for (int i = 0; i < fr.time.size(); ++i) {
        d.add(std::abs(balance(i) - balance(0)) / scale, "independent at " + std::to_string(i));
        d.add(std::abs(lib[i] - lib[0]) / scale, "energy_balance() at " + std::to_string(i));
      }
      return d;
    });
  }

  check_box2d(mech, flat, motion, table, verbose);
}

}  // namespace

TEST(Metamorphic, GeneratedMechanisms) {
#ifdef MO2D_SANITIZE
  const long default_count = 40;  // ~10x slower under ASan; the Release build runs 300
#else
  const long default_count = 300;
#endif
  const long count = env_long("MO2D_META_COUNT", default_count);
  const std::uint64_t seed = static_cast<std::uint64_t>(env_long("MO2D_META_SEED", 1));
  GeneratorStats stats;
  Table table;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < count; ++k) {
    Mechanism m;
    try {
      m = generate(seed + static_cast<std::uint64_t>(k), stats);
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    check_mechanism(m, table);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  table.print();
  std::printf(
      "\n%ld mechanisms (seeds %llu..%llu) in %.1f s; %ld candidates generated, %ld accepted\n",
      stats.accepted, static_cast<unsigned long long>(seed),
      static_cast<unsigned long long>(seed + count - 1), seconds, stats.candidates, stats.accepted);
  for (const auto& [reason, n] : stats.rejected)
    std::printf("  rejected %6ld: %s\n", n, reason.c_str());
  std::printf(
      "Box2D compared %ld mechanisms: with linear springs %ld, dampers %ld, torsional springs %ld, "
      "loads of the state %ld, joint friction %ld\n",
      box2d_content.compared, box2d_content.springs, box2d_content.dampers, box2d_content.torsional,
      box2d_content.state_loads, box2d_content.friction);
  std::printf("modules:");
  for (const auto& [f, n] : stats.families) std::printf(" %s %ld,", f.c_str(), n);
  std::printf("\n");
  EXPECT_EQ(stats.accepted, count);
}

// Known bug found by the round trip (generated mechanism seed 184: slot + five-bar + slider-crank,
// size 4.75 m): inverse dynamics solves the positions of each sample by Newton from the previous
// sample; with 21 samples over 2.09 s the slider of the slider-crank (b17.P, not prescribed) jumps
// from x = 4.946 m to the other assembly branch (3.476 m instead of 5.670 m) between the first two
// samples, with exit 0 and no warning. With 201 samples it stays on the branch, and forward
// dynamics driven by the same efforts follows the 201-sample solution to 1e-9 m. A branch switch
// between samples must be detected (issue 10 item 5: singularity / branch helper).
// Seed 184 (a slot, a five-bar and a slider-crank): at 21 samples inverse dynamics converges to
// the slider-crank's other assembly mode between the first two samples (b17.P.x 3.48 m instead of
// 5.67 m at t = 0.104 s); at 201 samples it stays on its branch. Found by the round trip. Not a
// silent wrong answer any more: the jump is reported with its time and coordinate. (Keeping the
// branch, e.g. by time continuation between samples, is still to be done.)
TEST(Metamorphic, InverseBranchJumpBetweenSamplesIsReported) {
  GeneratorStats stats;
  const Mechanism mech = generate(184, stats);
  const Model model = build_model(to_system(mech));
  const auto motion = prescribed(mech);
  const Trajectory coarse =
      inverse_dynamics(model, motion, {.t0 = 0, .t1 = mech.t1, .samples = 21});
  const Trajectory fine = inverse_dynamics(model, motion, {.t0 = 0, .t1 = mech.t1, .samples = 201});
  const int c = model.coordinate("b17.P.x");
  bool jumped = false;
  for (int i = 0; i < 21; ++i)
    jumped |= std::abs(coarse.q0(i, c) - fine.q0(10 * i, c)) > 1e-9 * mech.length;
  ASSERT_TRUE(jumped) << "the coarse run kept its branch: turn this into a branch-keeping test";
  bool reported = false;
  for (const std::string& w : coarse.stats.warnings)
    reported |= w.find("the positions jumped between t = 0 s") != std::string::npos;
  EXPECT_TRUE(reported) << "the branch jump of seed 184 is not reported";
  EXPECT_TRUE(fine.stats.warnings.empty()) << fine.stats.warnings.front();
}
