// Random valid mechanisms for the metamorphic tests (generator.hpp).
#include "generator.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d::meta {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

Vec2 polar(double r, double a) {
  return {r * std::cos(a), r * std::sin(a)};
}
Vec2 perp(const Vec2& v) {
  return {-v.y(), v.x()};
}
Vec2 rotate(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

// ---- random numbers
// ------------------------------------------------------------------------------
double Rng::uniform() {
  return static_cast<double>(g_() >> 11) * 0x1.0p-53;
}
double Rng::uniform(double a, double b) {
  return a + (b - a) * uniform();
}
double Rng::log_uniform(double a, double b) {
  return std::exp(uniform(std::log(a), std::log(b)));
}
int Rng::integer(int lo, int hi) {  // rejection sampling: no modulo bias
  const std::uint64_t n = static_cast<std::uint64_t>(hi - lo) + 1;
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() / n * n;
  std::uint64_t x;
  do x = g_();
  while (x >= limit);
  return lo + static_cast<int>(x % n);
}
bool Rng::chance(double p) {
  return uniform() < p;
}
Vec2 Rng::direction(double lo, double hi) {
  return polar(1.0, uniform(lo, hi));
}

double Wave::operator()(double t) const {
  return a0 + a1 * std::sin(omega * t + phase);
}
Vec2 VecWave::operator()(double t) const {
  return a0 + a1 * std::sin(omega * t + phase);
}
Jet MotionSpec::operator()(Jet t) const {
  return s0 + amp * (sin(omega * t + phase) - std::sin(phase)) + drift * t;
}

bool Mechanism::has_springs() const {
  auto any = [](const SystemSpec& s) { return !s.springs.empty() || !s.torsionals.empty(); };
  return any(root) || std::any_of(subs.begin(), subs.end(), any);
}
bool Mechanism::has_external_loads() const {
  auto any = [](const SystemSpec& s) { return !s.forces.empty() || !s.torques.empty(); };
  return any(root) || std::any_of(subs.begin(), subs.end(), any);
}

// ---- to System
// -----------------------------------------------------------------------------------
namespace {

System system_of(const SystemSpec& s, const std::vector<System>& subs) {
  System out(s.name);
  for (const auto& g : s.ground) out.add_ground_node(g.name, g.position);
  for (const auto& b : s.bodies) {
    BodyDef d{.name = b.name, .nodes = b.nodes, .mass = b.mass, .inertia = b.inertia, .com = {}};
    switch (b.com.kind) {
      case CenterOfMass::Kind::node:
        d.com = CenterOfMass::at_node(b.com.ni);
        break;
      case CenterOfMass::Kind::nodes:
        d.com = CenterOfMass::between(b.com.ni, b.com.nj, b.com.gamma, b.com.rho);
        break;
      case CenterOfMass::Kind::point:
        d.com = CenterOfMass::at_point(b.com.point);
        break;
    }
    out.add_body(std::move(d));
  }
  for (const auto& j : s.revolutes) out.add_revolute(j);
  for (const auto& j : s.prismatics) out.add_prismatic(j);
  for (const auto& j : s.slots) out.add_pin_in_slot(j);
  for (const auto& c : s.coords)
    out.add_coordinate({.name = c.name, .rate = c.rate, .initial = 0.0});
  for (const auto& f : s.forces) {
    const VecWave w = f.f;
    out.add_force({.name = f.name,
                   .body = f.body,
                   .point = f.point,
                   .fx = [w](double t) { return w(t).x(); },
                   .fy = [w](double t) { return w(t).y(); }});
  }
  for (const auto& t : s.torques) {
    const Wave w = t.tau;
    out.add_torque({.name = t.name, .body = t.body, .torque = [w](double x) { return w(x); }});
  }
  for (const auto& sp : s.springs)
    out.add_spring({.name = sp.name,
                    .body_a = sp.body_a,
                    .point_a = sp.point_a,
                    .body_b = sp.body_b,
                    .point_b = sp.point_b,
                    .rest_length = sp.rest,
                    .stiffness = sp.k,
                    .damping = sp.c});
  for (const auto& ts : s.torsionals)
    out.add_torsional_spring(
        {.name = ts.name, .joint = ts.joint, .stiffness = ts.k, .damping = ts.c});
  for (const auto& in : s.instances) out.add_instance(in.name, subs[in.sub], in.placement);
  if (s.gravity != Vec2(0, 0)) out.set_gravity(s.gravity);
  return out;
}

}  // namespace

System to_system(const Mechanism& m) {
  std::vector<System> subs;
  for (const auto& s : m.subs) subs.push_back(system_of(s, {}));
  return system_of(m.root, subs);
}

std::vector<Prescribed> prescribed(const Mechanism& m) {
  std::vector<Prescribed> out;
  for (const auto& ms : m.motion) out.push_back({ms.coordinate, [ms](Jet t) { return ms(t); }});
  return out;
}

// ---- transformations
// -----------------------------------------------------------------------------
namespace {

// Apply a point map P, a vector map V (forces, gravity), the sign of pure torques and of rho
// (the perpendicular coordinate of a centre of mass) to one System's data.
template <class P, class V>
void map_system(SystemSpec& s, P point, V vec, double torque_sign) {
  for (auto& g : s.ground) g.position = point(g.position);
  for (auto& b : s.bodies) {
    for (auto& n : b.nodes) n.position = point(n.position);
    b.com.point = point(b.com.point);
    b.com.rho *= torque_sign;  // a reflection moves z x d to the other side
  }
  for (auto& f : s.forces) {
    f.point = point(f.point);
    f.f.a0 = vec(f.f.a0);
    f.f.a1 = vec(f.f.a1);
  }
  for (auto& t : s.torques) t.tau.a0 *= torque_sign, t.tau.a1 *= torque_sign;
  for (auto& sp : s.springs) sp.point_a = point(sp.point_a), sp.point_b = point(sp.point_b);
  s.gravity = vec(s.gravity);
}

template <class T>
void shuffle(std::vector<T>& v, Rng& r) {  // Fisher-Yates with the portable integer()
  for (int i = static_cast<int>(v.size()) - 1; i > 0; --i) std::swap(v[i], v[r.integer(0, i)]);
}

void shuffle_system(SystemSpec& s, Rng& r) {
  shuffle(s.ground, r);
  for (auto& b : s.bodies) shuffle(b.nodes, r);
  shuffle(s.bodies, r);
  shuffle(s.revolutes, r);
  shuffle(s.prismatics, r);
  shuffle(s.slots, r);
  shuffle(s.coords, r);
  shuffle(s.forces, r);
  shuffle(s.torques, r);
  shuffle(s.springs, r);
  shuffle(s.torsionals, r);
  shuffle(s.instances, r);
}

}  // namespace

Mechanism translated(const Mechanism& m, Vec2 d) {
  Mechanism out = m;
  map_system(
      out.root, [d](Vec2 p) { return Vec2(p + d); }, [](Vec2 v) { return v; }, 1.0);
  for (auto& in : out.root.instances) in.placement.offset += d;
  return out;
}

Mechanism rotated(const Mechanism& m, double a) {
  Mechanism out = m;
  auto R = [a](Vec2 p) { return rotate(p, a); };
  map_system(out.root, R, R, 1.0);
  for (auto& in : out.root.instances) {
    in.placement.offset = rotate(in.placement.offset, a);
    in.placement.angle += a;
  }
  return out;
}

Mechanism mirrored(const Mechanism& m) {
  Mechanism out = m;
  auto X = [](Vec2 p) { return Vec2(-p.x(), p.y()); };
  map_system(out.root, X, X, -1.0);
  for (auto& s : out.subs) map_system(s, X, X, -1.0);
  // X (R(a) p + o) = R(-a) (X p) + X o
  for (auto& in : out.root.instances) {
    in.placement.offset = X(in.placement.offset);
    in.placement.angle = -in.placement.angle;
  }
  for (auto& ms : out.motion)
    if (ms.angle) ms.s0 = -ms.s0, ms.amp = -ms.amp, ms.drift = -ms.drift;
  return out;
}

Mechanism scaled(const Mechanism& m, double L, double M, double T) {
  Mechanism out = m;
  const double force = M * L / (T * T), torque = M * L * L / (T * T);
  auto scale_system = [&](SystemSpec& s) {
    map_system(
        s, [L](Vec2 p) { return Vec2(L * p); }, [force](Vec2 v) { return Vec2(force * v); }, 1.0);
    s.gravity *= 1.0 / M;  // map_system multiplied it by M L / T^2; gravity is L / T^2
    for (auto& b : s.bodies) b.mass *= M, b.inertia *= M * L * L;
    for (auto& f : s.forces) f.f.omega /= T;
    for (auto& t : s.torques) t.tau.a0 *= torque, t.tau.a1 *= torque, t.tau.omega /= T;
    for (auto& sp : s.springs) sp.rest *= L, sp.k *= M / (T * T), sp.c *= M / T;
    for (auto& ts : s.torsionals) ts.k *= torque, ts.c *= torque * T;
    for (auto& in : s.instances) in.placement.offset *= L;
  };
  scale_system(out.root);
  for (auto& s : out.subs) scale_system(s);
  for (auto& ms : out.motion) {
    const double len = ms.angle ? 1.0 : L;
    ms.s0 *= len, ms.amp *= len, ms.drift *= len / T, ms.omega /= T;
  }
  out.t1 *= T;
  out.length *= L;
  out.time *= T;
  return out;
}

Mechanism reordered(const Mechanism& m, std::uint64_t seed) {
  Mechanism out = m;
  Rng r(seed);
  shuffle_system(out.root, r);
  for (auto& s : out.subs) shuffle_system(s, r);
  shuffle(out.motion, r);
  return out;
}

// ---- flattened description (for the independent energy functions) -----------------------------
namespace {

Placement compose(const Placement& outer, const Placement& inner) {
  return {outer.apply(inner.offset), outer.angle + inner.angle};
}

Vec2 node_of(const BodySpec& b, const std::string& n) {
  for (const auto& x : b.nodes)
    if (x.name == n) return x.position;
  throw Error("generator: no node " + n + " in body " + b.name);
}

void flatten_into(const Mechanism& mech, const SystemSpec& s, const Placement& frame,
                  const std::string& prefix, Flat& out) {
  std::map<std::string, int> index;
  for (const auto& b : s.bodies) {
    FlatBody fb;
    fb.name = prefix + b.name;
    for (const auto& n : b.nodes) {
      fb.node_labels.push_back(fb.name + "." + n.name);
      fb.nodes.push_back(frame.apply(n.position));
    }
    fb.mass = b.mass;
    fb.inertia = b.inertia;
    Vec2 c;
    switch (b.com.kind) {
      case CenterOfMass::Kind::node:
        c = node_of(b, b.com.ni);
        break;
      case CenterOfMass::Kind::nodes: {
        const Vec2 pi = node_of(b, b.com.ni), d = node_of(b, b.com.nj) - pi;
        c = pi + b.com.gamma * d + b.com.rho * perp(d);
        break;
      }
      case CenterOfMass::Kind::point:
        c = b.com.point;
        break;
    }
    fb.com = frame.apply(c);
    index[b.name] = static_cast<int>(out.bodies.size());
    out.bodies.push_back(std::move(fb));
  }
  auto body = [&](const std::string& name) { return name == "ground" ? -1 : index.at(name); };
  auto body_of_node = [&](const std::string& ref) { return body(ref.substr(0, ref.find('.'))); };
  auto vec = [&](Vec2 v) { return rotate(v, frame.angle); };
  for (const auto& sp : s.springs)
    out.springs.push_back({{body(sp.body_a), frame.apply(sp.point_a)},
                           {body(sp.body_b), frame.apply(sp.point_b)},
                           sp.rest,
                           sp.k,
                           sp.c});
  for (const auto& f : s.forces)
    out.forces.push_back(
        {{body(f.body), frame.apply(f.point)}, {vec(f.f.a0), vec(f.f.a1), f.f.omega, f.f.phase}});
  for (const auto& t : s.torques) out.torques.push_back({body(t.body), t.tau});
  for (const auto& ts : s.torsionals)
    for (const auto& j : s.revolutes)
      if (j.name == ts.joint)
        out.torsionals.push_back({body_of_node(j.node_a), body_of_node(j.node_b), ts.k, ts.c});
  for (const auto& j : s.revolutes)
    if (j.actuated)
      out.actuators.push_back(
          {prefix + j.name + ".torque", true, body_of_node(j.node_a), body_of_node(j.node_b), ""});
  for (const auto& j : s.prismatics)
    if (j.actuated)
      out.actuators.push_back({prefix + j.name + ".force", false, -1, -1, prefix + j.name + ".v"});
  for (const auto& in : s.instances)
    flatten_into(mech, mech.subs[in.sub], compose(frame, in.placement), prefix + in.name + ".",
                 out);
}

}  // namespace

Flat flatten(const Mechanism& m) {
  Flat out;
  flatten_into(m, m.root, Placement{}, "", out);
  out.gravity = m.root.gravity;
  return out;
}

// ---- conditioning
// --------------------------------------------------------------------------------
double prescribed_conditioning(const Model& model, const Eigen::VectorXd& q0,
                               const std::vector<std::string>& labels) {
  VectorXd psi(model.m0);
  MatrixXd Psi(model.m0, model.n0);
  position_jacobian(model, q0, 0.0, psi, Psi);
  for (int j = 0; j < model.n0; ++j) {  // length columns in units of the mechanism's size
    const std::string& l = model.coordinate_labels[j];
    const std::string tail = l.substr(l.size() - 2);
    if (tail == ".x" || tail == ".y" || tail == ".q") Psi.col(j) *= model.scale;
  }
  MatrixXd K = MatrixXd::Zero(model.m0 + static_cast<int>(labels.size()), model.n0);
  for (int i = 0; i < model.m0; ++i) {
    const double n = Psi.row(i).norm();
    K.row(i) = n > 0 ? MatrixXd(Psi.row(i) / n) : MatrixXd(Psi.row(i));
  }
  for (size_t k = 0; k < labels.size(); ++k) K(model.m0 + k, model.coordinate(labels[k])) = 1;
  const Eigen::JacobiSVD<MatrixXd> svd(K);
  const VectorXd sv = svd.singularValues();
  if (sv.size() == 0 || sv[0] <= 0) return 0;
  // a non-square [Psi; E] (DOF mismatch) counts as singular
  if (K.rows() != K.cols()) return 0;
  return sv[sv.size() - 1] / sv[0];
}

// ---- generator
// -----------------------------------------------------------------------------------
namespace {

struct Builder {
  Rng& r;
  Mechanism& mech;
  double L;    // characteristic length (m)
  double tau;  // characteristic time sqrt(L / g) (s): motions, loads and springs scale with it
  int counter = 0;
  std::vector<std::string> rotating;  // root bodies a chain may hang from (body index names)

  std::string id(const char* prefix) { return prefix + std::to_string(counter++); }

  BodySpec body(SystemSpec& s, std::vector<NodeDef> nodes, bool allow_com_anywhere = true) {
    (void)s;
    BodySpec b;
    b.name = id("b");
    b.nodes = std::move(nodes);
    b.mass = r.log_uniform(0.005, 50.0);  // four decades
    if (b.nodes.size() == 1) {
      b.inertia = 0;  // a point mass (no rotation)
      b.com.kind = CenterOfMass::Kind::node;
      b.com.ni = b.nodes[0].name;
      return b;
    }
    const Vec2 p0 = b.nodes[0].position, d = b.nodes[1].position - p0;
    b.inertia = b.mass * d.squaredNorm() * r.uniform(0.02, 0.3);
    const int kind = allow_com_anywhere ? r.integer(0, 2) : 0;
    if (kind == 0) {
      b.com.kind = CenterOfMass::Kind::node;
      b.com.ni = b.nodes[r.integer(0, static_cast<int>(b.nodes.size()) - 1)].name;
    } else if (kind == 1) {
      b.com.kind = CenterOfMass::Kind::nodes;
      const int i = r.integer(0, static_cast<int>(b.nodes.size()) - 1);
      int j = r.integer(0, static_cast<int>(b.nodes.size()) - 2);
      if (j >= i) ++j;
      b.com.ni = b.nodes[i].name;
      b.com.nj = b.nodes[j].name;
      b.com.gamma = r.uniform(-0.25, 1.25);
      b.com.rho = r.uniform(-0.3, 0.3);
    } else {
      b.com.kind = CenterOfMass::Kind::point;
      b.com.point = p0 + r.uniform(-0.2, 1.2) * d + r.uniform(-0.3, 0.3) * perp(d);
    }
    return b;
  }

  // A point near a body (its node for a point mass).
  Vec2 point_on(const BodySpec& b) {
    if (b.nodes.size() == 1) return b.nodes[0].position;
    const Vec2 p0 = b.nodes[0].position, d = b.nodes[1].position - p0;
    return p0 + r.uniform(-0.3, 1.3) * d + r.uniform(-0.5, 0.5) * perp(d);
  }

  void add_angle_motion(const std::string& coordinate, bool crank = false) {
    MotionSpec ms;
    ms.coordinate = coordinate;
    ms.angle = true;
    ms.amp = r.uniform(0.15, 0.7) * r.sign();
    ms.omega = r.uniform(0.3, 1.5) / tau;
    ms.phase = r.uniform(-kPi, kPi);
    ms.drift = crank ? r.uniform(-0.3, 0.3) / tau : 0.0;
    mech.motion.push_back(ms);
  }

  // Extra coordinate: the angle of body2 relative to body1 (or to the ground), 0 at the start.
  std::string angle_coordinate(SystemSpec& s, const std::string& b2, const std::string& b1) {
    CoordSpec c{id("c"), {{b2 + ".w", 1.0}}};
    if (!b1.empty()) c.rate.push_back({b1 + ".w", -1.0});
    s.coords.push_back(c);
    return c.name;
  }

  std::string ground(SystemSpec& s, Vec2 p) {
    const std::string g = id("G");
    s.ground.push_back({g, p});
    return g;
  }

  // ---- modules (each adds as many prescribed coordinates and actuators as degrees of freedom)
  void chain(SystemSpec& s, Vec2 center, int links) {
    std::string parent, parent_node;  // parent body ("" = ground) and node reference
    Vec2 a{0, 0};
    if (!rotating.empty() && r.chance(0.35)) {  // hang from a moving body of an earlier module
      const std::string& pb = rotating[r.integer(0, static_cast<int>(rotating.size()) - 1)];
      for (const auto& b : s.bodies)
        if (b.name == pb) {
          const auto& n = b.nodes[r.integer(0, static_cast<int>(b.nodes.size()) - 1)];
          parent = pb, parent_node = pb + "." + n.name, a = n.position;
        }
    } else {
      a = center;
      parent_node = "ground." + ground(s, a);
    }
    for (int k = 0; k < links; ++k) {
      const Vec2 b = a + polar(L * r.uniform(0.5, 1.5), r.uniform(-kPi, kPi));
      std::vector<NodeDef> nodes{{"A", a}, {"B", b}};
      if (r.chance(0.3))
        nodes.push_back({"C", a + r.uniform(0.2, 0.8) * (b - a) +
                                  r.sign() * r.uniform(0.2, 0.5) * perp(b - a)});
      BodySpec body_k = body(s, nodes);
      const std::string name = body_k.name;
      s.bodies.push_back(body_k);
      s.revolutes.push_back(
          {.name = id("j"), .node_a = parent_node, .node_b = name + ".A", .actuated = true});
      add_angle_motion(angle_coordinate(s, name, parent));
      rotating.push_back(name);
      parent = name, parent_node = name + ".B", a = b;
    }
    mech.family += "chain" + std::to_string(links) + (parent.empty() ? "" : "") + "+";
  }

  // Four-bar (crank A-B, coupler B-C, rocker D-C), optionally a Watt six-bar: a dyad E-F-H from
  // a third coupler node to the ground. The angles at B, C (and F) start in [40, 140] degrees.
  void fourbar(SystemSpec& s, Vec2 center, bool six) {
    const Vec2 A = center;
    const double th = r.uniform(-kPi, kPi);
    const Vec2 B = A + polar(L * r.uniform(0.4, 0.8), th);
    const double phi = th + kPi + r.sign() * r.uniform(40, 140) * kDeg;
    const Vec2 C = B + polar(L * r.uniform(0.8, 1.5), phi);
    const Vec2 D =
        C + polar(L * r.uniform(0.6, 1.4), phi + kPi + r.sign() * r.uniform(50, 130) * kDeg);
    BodySpec crank = body(s, {{"A", A}, {"B", B}});
    std::vector<NodeDef> cn{{"B", B}, {"C", C}};
    Vec2 E{0, 0};
    if (six) {
      E = B + r.uniform(0.2, 0.8) * (C - B) + r.sign() * r.uniform(0.3, 0.8) * perp(C - B);
      cn.push_back({"E", E});
    }
    BodySpec coupler = body(s, cn);
    BodySpec rocker = body(s, {{"D", D}, {"C", C}});
    const std::string gA = ground(s, A), gD = ground(s, D);
    s.bodies.push_back(crank);
    s.bodies.push_back(coupler);
    s.bodies.push_back(rocker);
    s.revolutes.push_back(
        {.name = id("j"), .node_a = "ground." + gA, .node_b = crank.name + ".A", .actuated = true});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = crank.name + ".B", .node_b = coupler.name + ".B"});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = coupler.name + ".C", .node_b = rocker.name + ".C"});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = "ground." + gD, .node_b = rocker.name + ".D"});
    add_angle_motion(angle_coordinate(s, crank.name, ""), true);
    rotating.push_back(coupler.name);
    rotating.push_back(rocker.name);
    if (six) {
      const double al = r.uniform(-kPi, kPi);
      const Vec2 F = E + polar(L * r.uniform(0.6, 1.2), al);
      const Vec2 H =
          F + polar(L * r.uniform(0.6, 1.2), al + kPi + r.sign() * r.uniform(50, 130) * kDeg);
      BodySpec d1 = body(s, {{"E", E}, {"F", F}}), d2 = body(s, {{"F", F}, {"H", H}});
      const std::string gH = ground(s, H);
      s.bodies.push_back(d1);
      s.bodies.push_back(d2);
      s.revolutes.push_back(
          {.name = id("j"), .node_a = coupler.name + ".E", .node_b = d1.name + ".E"});
      s.revolutes.push_back({.name = id("j"), .node_a = d1.name + ".F", .node_b = d2.name + ".F"});
      s.revolutes.push_back({.name = id("j"), .node_a = "ground." + gH, .node_b = d2.name + ".H"});
    }
    mech.family += six ? "sixbar+" : "fourbar+";
  }

  // Slider-crank: crank A-B, coupler B-P, slider P on a ground axis; driven by the crank angle or
  // by the slider coordinate.
  void slider_crank(SystemSpec& s, Vec2 center) {
    const Vec2 A = center;
    const double th = r.uniform(-kPi, kPi);
    const Vec2 B = A + polar(L * r.uniform(0.3, 0.6), th);
    const double phi = th + kPi + r.sign() * r.uniform(40, 140) * kDeg;
    const Vec2 P = B + polar(L * r.uniform(1.0, 2.0), phi);
    const Vec2 e = polar(1.0, phi + r.sign() * r.uniform(30, 150) * kDeg);
    const double q = L * r.uniform(0.5, 1.5);
    const Vec2 S1 = P - q * e, S2 = S1 + L * e;
    BodySpec crank = body(s, {{"A", A}, {"B", B}});
    BodySpec coupler = body(s, {{"B", B}, {"P", P}});
    std::vector<NodeDef> sn{{"P", P}};
    if (r.chance(0.5))
      sn.push_back({"Q", P + polar(L * r.uniform(0.2, 0.5), r.uniform(-kPi, kPi))});
    BodySpec slider = body(s, sn);
    const std::string gA = ground(s, A), g1 = ground(s, S1), g2 = ground(s, S2);
    s.bodies.push_back(crank);
    s.bodies.push_back(coupler);
    s.bodies.push_back(slider);
    const bool drive_slider = r.chance(0.5);
    s.revolutes.push_back({.name = id("j"),
                           .node_a = "ground." + gA,
                           .node_b = crank.name + ".A",
                           .actuated = !drive_slider});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = crank.name + ".B", .node_b = coupler.name + ".B"});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = slider.name + ".P", .node_b = coupler.name + ".P"});
    const std::string jp = id("j");
    s.prismatics.push_back({.name = jp,
                            .axis_from = "ground." + g1,
                            .axis_to = "ground." + g2,
                            .slider = slider.name + ".P",
                            .actuated = drive_slider});
    if (drive_slider) {
      MotionSpec ms{.coordinate = jp + ".q", .angle = false, .s0 = q};
      ms.amp = L * r.uniform(0.03, 0.12) * r.sign();
      ms.omega = r.uniform(0.3, 1.5) / tau;
      ms.phase = r.uniform(-kPi, kPi);
      mech.motion.push_back(ms);
    } else {
      add_angle_motion(angle_coordinate(s, crank.name, ""), true);
    }
    rotating.push_back(coupler.name);
    mech.family += drive_slider ? "slider(q)+" : "slider+";
  }

  // Whitworth-like: a crank O2-A whose pin A slides in the slot O-B of a lever pivoted at O1.
  void pin_in_slot(SystemSpec& s, Vec2 center) {
    const Vec2 O1 = center;
    const double al = r.uniform(-kPi, kPi);
    const double Ll = L * r.uniform(1.0, 1.6);
    const Vec2 B = O1 + polar(Ll, al), A = O1 + polar(Ll * r.uniform(0.35, 0.75), al);
    const Vec2 O2 = A + polar(L * r.uniform(0.25, 0.5), al + r.sign() * r.uniform(50, 130) * kDeg);
    BodySpec lever = body(s, {{"O", O1}, {"B", B}});
    BodySpec crank = body(s, {{"O", O2}, {"A", A}});
    const std::string g1 = ground(s, O1), g2 = ground(s, O2);
    s.bodies.push_back(lever);
    s.bodies.push_back(crank);
    s.revolutes.push_back({.name = id("j"), .node_a = "ground." + g1, .node_b = lever.name + ".O"});
    s.revolutes.push_back(
        {.name = id("j"), .node_a = "ground." + g2, .node_b = crank.name + ".O", .actuated = true});
    s.slots.push_back({.name = id("j"),
                       .axis_from = lever.name + ".O",
                       .axis_to = lever.name + ".B",
                       .pin = crank.name + ".A"});
    add_angle_motion(angle_coordinate(s, crank.name, ""), true);
    rotating.push_back(lever.name);
    mech.family += "slot+";
  }

  // A two-link leg defined once (with its own loads) and placed 1-3 times.
  void legs(Vec2 center) {
    SystemSpec leg;
    leg.name = id("leg");
    Builder sub{r, mech, L, tau, 0, {}};
    const Vec2 O = polar(L * r.uniform(0, 0.5), r.uniform(-kPi, kPi));
    const Vec2 E = O + polar(L * r.uniform(0.6, 1.2), r.uniform(-kPi, kPi));
    const Vec2 T = E + polar(L * r.uniform(0.6, 1.2), r.uniform(-kPi, kPi));
    BodySpec p = sub.body(leg, {{"O", O}, {"E", E}}), d = sub.body(leg, {{"E", E}, {"T", T}});
    p.name = "p", d.name = "d";
    leg.ground.push_back({"O", O});
    leg.bodies = {p, d};
    leg.revolutes.push_back(
        {.name = "j1", .node_a = "ground.O", .node_b = "p.O", .actuated = true});
    leg.revolutes.push_back({.name = "j2", .node_a = "p.E", .node_b = "d.E", .actuated = true});
    leg.coords.push_back({"a1", {{"p.w", 1.0}}});
    leg.coords.push_back({"a2", {{"d.w", 1.0}, {"p.w", -1.0}}});
    const double W = (p.mass + d.mass) * 9.81;
    if (r.chance(0.4))
      leg.springs.push_back({"s", "d", sub.point_on(d), "ground",
                             O + polar(L * r.uniform(0.5, 1.5), r.uniform(-kPi, kPi)), 0,
                             W / L * r.log_uniform(0.1, 10),
                             r.chance(0.5) ? 0.0 : W / L * tau * r.uniform(0.05, 1)});
    if (!leg.springs.empty()) {
      auto& sp = leg.springs.back();
      sp.rest = (sp.point_b - sp.point_a).norm() * r.uniform(0.5, 1.5);
    }
    if (r.chance(0.3)) leg.torsionals.push_back({"ts", "j2", W * L * r.log_uniform(0.1, 10), 0});
    if (r.chance(0.3))
      leg.forces.push_back(
          {"f",
           "d",
           sub.point_on(d),
           {W * r.uniform(0, 1) * r.direction(), W * r.uniform(0, 1) * r.direction(),
            r.uniform(0.3, 2.0) / tau, r.uniform(-kPi, kPi)}});
    if (r.chance(0.3))
      leg.torques.push_back({"t",
                             "p",
                             {W * L * r.uniform(-1, 1), W * L * r.uniform(-1, 1),
                              r.uniform(0.3, 2.0) / tau, r.uniform(-kPi, kPi)}});
    const int sub_index = static_cast<int>(mech.subs.size());
    mech.subs.push_back(leg);
    const int count = r.integer(1, 3);
    for (int k = 0; k < count; ++k) {
      const std::string name = id("leg");
      mech.root.instances.push_back(
          {name, sub_index,
           Placement{center + polar(L * r.uniform(0, 3), r.uniform(-kPi, kPi)),
                     r.uniform(-kPi, kPi)}});
      for (const char* c : {".a1", ".a2"}) {
        add_angle_motion(name + c);
      }
    }
    mech.family += "legs" + std::to_string(count) + "+";
  }

  // Five-bar: two instances of a one-crank subsystem joined by two coupler bodies in the root.
  void fivebar(Vec2 center) {
    SystemSpec crank;
    crank.name = id("crank");
    Builder sub{r, mech, L, tau, 0, {}};
    const Vec2 O = polar(L * r.uniform(0, 0.5), r.uniform(-kPi, kPi));
    const Vec2 T = O + polar(L * r.uniform(0.4, 0.8), r.uniform(-kPi, kPi));
    BodySpec k = sub.body(crank, {{"O", O}, {"T", T}});
    k.name = "k";
    crank.ground.push_back({"O", O});
    crank.bodies = {k};
    crank.revolutes.push_back(
        {.name = "j", .node_a = "ground.O", .node_b = "k.O", .actuated = true});
    crank.coords.push_back({"a", {{"k.w", 1.0}}});
    const int sub_index = static_cast<int>(mech.subs.size());
    mech.subs.push_back(crank);
    const Placement P1{center, r.uniform(-kPi, kPi)};
    const Placement P2{center + polar(L * r.uniform(0.8, 1.5), r.uniform(-kPi, kPi)),
                       r.uniform(-kPi, kPi)};
    const Vec2 T1 = P1.apply(T), T2 = P2.apply(T);
    const Vec2 J =
        0.5 * (T1 + T2) + r.sign() * r.uniform(0.6, 1.2) * L * perp(T2 - T1).normalized();
    const std::string i1 = id("five"), i2 = id("five");
    mech.root.instances.push_back({i1, sub_index, P1});
    mech.root.instances.push_back({i2, sub_index, P2});
    BodySpec c1 = body(mech.root, {{"T", T1}, {"J", J}}),
             c2 = body(mech.root, {{"T", T2}, {"J", J}});
    mech.root.bodies.push_back(c1);
    mech.root.bodies.push_back(c2);
    mech.root.revolutes.push_back(
        {.name = id("j"), .node_a = i1 + ".k.T", .node_b = c1.name + ".T"});
    mech.root.revolutes.push_back(
        {.name = id("j"), .node_a = i2 + ".k.T", .node_b = c2.name + ".T"});
    mech.root.revolutes.push_back(
        {.name = id("j"), .node_a = c1.name + ".J", .node_b = c2.name + ".J"});
    add_angle_motion(i1 + ".a");
    add_angle_motion(i2 + ".a");
    rotating.push_back(c1.name);
    mech.family += "fivebar+";
  }

  // Springs, dampers, torsional springs, point forces, torques and gravity on the root's bodies.
  void loads(SystemSpec& s) {
    if (s.bodies.empty()) return;
    double mass = 0;
    for (const auto& b : s.bodies) mass += b.mass;
    const double g = 9.81, W = mass * g;
    if (r.chance(0.75)) s.gravity = g * r.uniform(0.5, 1.5) * r.direction();
    auto any_body = [&]() -> const BodySpec& {
      return s.bodies[r.integer(0, static_cast<int>(s.bodies.size()) - 1)];
    };
    if (r.chance(0.5)) {
      const int n = r.integer(1, 2);
      for (int k = 0; k < n; ++k) {
        SpringSpec sp;
        sp.name = id("s");
        const BodySpec& a = any_body();
        sp.body_a = a.name;
        sp.point_a = point_on(a);
        if (r.chance(0.3)) {
          sp.body_b = "ground";
          sp.point_b = sp.point_a + polar(L * r.uniform(0.5, 1.5), r.uniform(-kPi, kPi));
        } else {
          const BodySpec& b = any_body();
          sp.body_b = b.name;
          sp.point_b = point_on(b);
          if (b.name == a.name) continue;
          if ((sp.point_b - sp.point_a).norm() < 0.2 * L) continue;
        }
        sp.rest = (sp.point_b - sp.point_a).norm() * r.uniform(0.5, 1.5);
        sp.k = W / L * r.log_uniform(0.1, 10);
        sp.c = r.chance(0.5) ? W / L * tau * r.log_uniform(0.05, 1) : 0.0;
        s.springs.push_back(sp);
      }
    }
    if (r.chance(0.3) && !s.revolutes.empty()) {
      const auto& j = s.revolutes[r.integer(0, static_cast<int>(s.revolutes.size()) - 1)];
      auto one_node = [&](const std::string& ref) {  // a point mass has no angle to spring
        const std::string b = ref.substr(0, ref.find('.'));
        for (const auto& x : s.bodies)
          if (x.name == b) return x.nodes.size() < 2;
        return false;
      };
      // joints of root bodies only, between bodies with an orientation
      if (j.node_a.find("five") != 0 && j.node_b.find("five") != 0 && !one_node(j.node_a) &&
          !one_node(j.node_b))
        s.torsionals.push_back({id("ts"), j.name, W * L * r.log_uniform(0.1, 10),
                                r.chance(0.5) ? W * L * tau * r.uniform(0.05, 1) : 0.0});
    }
    if (r.chance(0.5)) {
      const int n = r.integer(1, 2);
      for (int k = 0; k < n; ++k) {
        const BodySpec& b = any_body();
        s.forces.push_back(
            {id("f"),
             b.name,
             point_on(b),
             {W * r.uniform(0, 1) * r.direction(), W * r.uniform(0, 1) * r.direction(),
              r.uniform(0.3, 2.0) / tau, r.uniform(-kPi, kPi)}});
      }
    }
    if (r.chance(0.4)) {
      std::vector<const BodySpec*> turning;
      for (const auto& b : s.bodies)
        if (b.rotates()) turning.push_back(&b);
      if (!turning.empty()) {
        const BodySpec& b = *turning[r.integer(0, static_cast<int>(turning.size()) - 1)];
        s.torques.push_back({id("t"),
                             b.name,
                             {W * L * r.uniform(-1, 1), W * L * r.uniform(-1, 1),
                              r.uniform(0.3, 2.0) / tau, r.uniform(-kPi, kPi)}});
      }
    }
  }
};

// A slider body's rotation is eliminated by its prismatic joint: a chain may not hang from it
// (its "w" label does not exist) and a torque on it would be carried by the axis.
bool is_slider(const SystemSpec& s, const std::string& body) {
  for (const auto& p : s.prismatics)
    if (p.slider.substr(0, p.slider.find('.')) == body) return true;
  return false;
}

Mechanism candidate(std::uint64_t seed, int attempt) {
  Mechanism m;
  m.seed = seed;
  m.attempt = attempt;
  Rng r(seed * 7919 + static_cast<std::uint64_t>(attempt));
  m.length = r.log_uniform(0.02, 5.0);
  m.root.name = "meta";
  const double tau = std::sqrt(m.length / 9.81);
  Builder b{r, m, m.length, tau, 0, {}};
  const Vec2 base = m.length * r.uniform(0, 20) * r.direction();  // away from the origin
  const int modules = r.integer(1, 3);
  for (int k = 0; k < modules; ++k) {
    const Vec2 center = base + polar(m.length * r.uniform(0, 3), r.uniform(-kPi, kPi));
    switch (r.integer(0, 7)) {
      case 0:
        b.chain(m.root, center, r.integer(1, 3));
        break;
      case 1:
        b.fourbar(m.root, center, false);
        break;
      case 2:
        b.fourbar(m.root, center, true);
        break;
      case 3:
        b.slider_crank(m.root, center);
        break;
      case 4:
        b.pin_in_slot(m.root, center);
        break;
      case 5:
        b.legs(center);
        break;
      case 6:
        b.fivebar(center);
        break;
      default:
        b.chain(m.root, center, 1);
        break;
    }
    b.rotating.erase(std::remove_if(b.rotating.begin(), b.rotating.end(),
                                    [&](const std::string& n) { return is_slider(m.root, n); }),
                     b.rotating.end());
  }
  b.loads(m.root);
  // no pure torque on a slider (its rotation is the axis's)
  std::erase_if(m.root.torques, [&](const TorqueSpec& t) { return is_slider(m.root, t.body); });
  if (!m.family.empty()) m.family.pop_back();
  m.t1 = 3 * tau;
  m.time = tau;
  return m;
}

}  // namespace

Mechanism generate(std::uint64_t seed, GeneratorStats& stats, const GeneratorOptions& o) {
  for (int attempt = 0; attempt < o.max_attempts; ++attempt) {
    ++stats.candidates;
    Mechanism m = candidate(seed, attempt);
    std::string reason;
    try {
      const System sys = to_system(m);
      const Model model = build_model(sys);
      if (model.dof != static_cast<int>(m.motion.size())) {
        reason = "generator: DOF differs from the prescribed coordinates";
      } else {
        const auto p = prescribed(m);
        const Trajectory r =
            inverse_dynamics(model, p, {.t0 = 0, .t1 = m.t1, .samples = o.samples});
        std::vector<std::string> labels;
        for (const auto& ms : m.motion) labels.push_back(ms.coordinate);
        double worst = 1;
        for (int i = 0; i < r.time.size(); ++i)
          worst = std::min(worst, prescribed_conditioning(model, r.q0.row(i).transpose(), labels));
        if (worst < o.min_sigma_ratio) reason = "near-singular over the run (sigma ratio < 1e-2)";
        if (!r.efforts.allFinite() || !r.reactions.allFinite()) reason = "non-finite result";
      }
    } catch (const Error& e) {
      const std::string w = e.what();
      if (w.find("singular") != std::string::npos)
        reason = "inverse: singular configuration";
      else if (w.find("positions not found") != std::string::npos)
        reason = "inverse: positions not found (leaves the workspace)";
      else if (w.find("cannot produce") != std::string::npos)
        reason = "inverse: actuators cannot produce the motion";
      else
        reason = "error: " + w.substr(0, 60);
    }
    if (reason.empty()) {
      ++stats.accepted;
      std::string fam = m.family;
      size_t pos = 0;
      while (pos != std::string::npos) {
        const size_t next = fam.find('+', pos);
        ++stats.families[fam.substr(pos, next == std::string::npos ? next : next - pos)];
        pos = next == std::string::npos ? next : next + 1;
      }
      return m;
    }
    ++stats.rejected[reason];
  }
  throw Error("generator: no valid mechanism for seed " + std::to_string(seed));
}

}  // namespace mo2d::meta
