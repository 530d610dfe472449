// Stage 6 of build_model: applied loads. A point is stored by local nodes like the centre of mass
// (Example 2.6 (b): p = p_0 + gamma d + rho z x d, d = p_1 - p_0) so that it moves with its body;
// point forces and torques take their values from signals, springs and torsional springs from
// their stiffness and damping (dynamics/ evaluates them).
#include <cmath>

#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

int find_body(const Model& m, const std::string& prefix, const std::string& name,
              const std::string& what) {
  for (int bi = 0; bi < static_cast<int>(m.bodies.size()); ++bi)
    if (m.bodies[bi].name == prefix + name) return bi;
  std::vector<std::string> names;
  for (const auto& b : m.bodies) names.push_back(b.name);
  throw Error(what + ": unknown body '" + prefix + name + "'" + did_you_mean(prefix + name, names),
              prefix + name);
}

void add_forces(const Flat& flat, Model& m) {
  for (const auto& f : flat.forces) {
    const std::string what = "force '" + f.prefix + f.def.name + "'";
    PointLoad l;
    l.name = f.prefix + f.def.name;
    l.body = find_body(m, f.prefix, f.def.body, what);
    const Body& b = m.bodies[l.body];
    if (b.nodes.size() >= 2) {
      const Vec2 gr = on_first_two_nodes(b.geometry, f.def.point);
      l.ci = 0;
      l.cj = 1;
      l.gamma = gr.x();
      l.rho = gr.y();
    } else if ((f.def.point - b.geometry[0]).norm() > 1e-12 * m.scale) {
      throw Error(what + ": body '" + b.name + "' has one node: the force must act at it", l.name);
    }
    const double angle = flat.force_angle[&f - flat.forces.data()];
    l.cos = std::cos(angle);
    l.sin = std::sin(angle);
    m.forces.push_back(std::move(l));
  }
  for (const auto& t : flat.torques) {
    const std::string what = "torque '" + t.prefix + t.def.name + "'";
    TorqueLoad l;
    l.name = t.prefix + t.def.name;
    l.body = find_body(m, t.prefix, t.def.body, what);
    if (!m.bodies[l.body].has_omega)
      throw Error(what + ": body '" + m.bodies[l.body].name + "' has no rotation", l.name);
    m.torques.push_back(std::move(l));
  }
}

void nonnegative(double v, const std::string& what, const char* field, const std::string& el) {
  if (!std::isfinite(v) || v < 0)
    throw Error(what + ": " + field + " must be finite and >= 0 (got " + std::to_string(v) + ")",
                el);
}

void add_springs(const Flat& flat, Model& m) {
  for (const auto& sp : flat.springs) {
    const std::string name = sp.prefix + sp.def.name;
    const std::string what = "spring '" + name + "'";
    check_name(sp.def.name, "spring");
    nonnegative(sp.def.rest_length, what, "rest_length", name);
    nonnegative(sp.def.stiffness, what, "stiffness", name);
    nonnegative(sp.def.damping, what, "damping", name);
    SpringLoad l;
    l.name = name;
    l.a = body_point(m, sp.prefix, sp.def.body_a, sp.def.point_a, what);
    l.b = body_point(m, sp.prefix, sp.def.body_b, sp.def.point_b, what);
    if (l.a.body < 0 && l.b.body < 0) throw Error(what + " joins two ground points", name);
    l.rest_length = sp.def.rest_length;
    l.stiffness = sp.def.stiffness;
    l.damping = sp.def.damping;
    l.acts = sp.def.acts;
    if (sp.def.tension && (l.stiffness != 0 || l.damping != 0))
      throw Error(what + ": a tension law replaces stiffness and damping (give one or the other)",
                  name);
    if (sp.def.reduce == SpringReduce::quasi_steady && !sp.def.tension && !(l.stiffness > 0))
      throw Error(what +
                      " (reduce: quasi_steady): needs stiffness > 0 or a tension law (its "
                      "equilibrium length under the tension is the length held)",
                  name);
    if (sp.def.reduce != SpringReduce::none)  // reduced_springs.cpp
      add_reduced_spring(l, sp.owner, m, sp.def.reduce == SpringReduce::quasi_steady);
    else
      m.springs.push_back(std::move(l));
  }
}

// A torsional spring acts across a revolute joint: between its two bodies, with the rest angle
// theta_2 - theta_1 of the initial configuration unless given.
void add_torsional_springs(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  for (const auto& ts : flat.torsional) {
    const std::string name = ts.prefix + ts.def.name;
    const std::string what = "torsional spring '" + name + "'";
    check_name(ts.def.name, "torsional spring");
    nonnegative(ts.def.stiffness, what, "stiffness", name);
    nonnegative(ts.def.damping, what, "damping", name);
    int found = -1;
    for (size_t k = 0; k < flat.revolutes.size(); ++k)
      if (flat.revolutes[k].prefix + flat.revolutes[k].def.name == ts.prefix + ts.def.joint)
        found = static_cast<int>(k);
    if (found < 0) {
      std::vector<std::string> names;
      for (const auto& j : flat.revolutes) names.push_back(j.prefix + j.def.name);
      throw Error(what + ": unknown revolute joint '" + ts.prefix + ts.def.joint + "'" +
                      did_you_mean(ts.prefix + ts.def.joint, names),
                  name);
    }
    TorsionalLoad l;
    l.name = name;
    l.body1 = el.body[red.revolutes[found][0]];
    l.body2 = el.body[red.revolutes[found][1]];
    auto angle0 = [&](int body) {
      if (body < 0) return 0.0;
      const Body& b = m.bodies[body];
      if (b.geometry.size() < 2)
        throw Error(what + ": body '" + b.name + "' has one node and no orientation", name);
      const Vec2 d = b.geometry[1] - b.geometry[0];
      return std::atan2(d.y(), d.x());
    };
    const double implied = angle0(l.body2) - angle0(l.body1);
    if (ts.def.rest && !std::isfinite(*ts.def.rest))
      throw Error(what + ": rest angle not finite", name);
    l.rest = ts.def.rest.value_or(implied);
    l.stiffness = ts.def.stiffness;
    l.damping = ts.def.damping;
    if (ts.def.torque && (l.stiffness != 0 || l.damping != 0))
      throw Error(what + ": a torque law replaces stiffness and damping (give one or the other)",
                  name);
    if (ts.def.reduce == SpringReduce::quasi_steady && !ts.def.torque && !(l.stiffness > 0))
      throw Error(what +
                      " (reduce: quasi_steady): needs stiffness > 0 or a torque law (its "
                      "equilibrium angle under the torque is the angle held)",
                  name);
    if (ts.def.reduce != SpringReduce::none)  // reduced_torsional.cpp
      add_reduced_torsional(l, ts.owner, m, ts.def.reduce == SpringReduce::quasi_steady);
    else
      m.torsional_springs.push_back(std::move(l));
  }
}

}  // namespace

BodyPoint body_point(const Model& m, const std::string& prefix, const std::string& body,
                     const Vec2& p, const std::string& what) {
  BodyPoint bp;
  if (body == "ground") {
    bp.fixed = p;
    return bp;
  }
  bp.body = find_body(m, prefix, body, what);
  const Body& b = m.bodies[bp.body];
  if (b.geometry.size() >= 2) {
    const Vec2 gr = on_first_two_nodes(b.geometry, p);
    bp.ci = 0;
    bp.cj = 1;
    bp.gamma = gr.x();
    bp.rho = gr.y();
  } else if ((p - b.geometry[0]).norm() > 1e-12 * m.scale) {
    throw Error(what + ": body '" + b.name + "' has one node: the point must be the node", b.name);
  }
  return bp;
}

namespace {

void add_points(const Flat& flat, Model& m) {
  for (const auto& p : flat.points) {
    const std::string name = p.prefix + p.def.name;
    check_name(p.def.name, "point");
    m.points.push_back(
        {name, body_point(m, p.prefix, p.def.body, p.def.point, "point '" + name + "'")});
  }
}

// The loads' laws, compiled once every quantity they may read is known (same order as the loads).
void compile_laws(const Flat& flat, Model& m) {
  using K = Quantity::Kind;
  for (size_t k = 0; k < flat.forces.size(); ++k) {
    const auto& f = flat.forces[k];
    const std::string what = "force '" + m.forces[k].name + "'";
    m.forces[k].fx = compile_law(m, f.def.fx, what + ".fx", m.forces[k].name, f.prefix);
    m.forces[k].fy = compile_law(m, f.def.fy, what + ".fy", m.forces[k].name, f.prefix);
  }
  for (size_t k = 0; k < flat.torques.size(); ++k)
    m.torques[k].torque =
        compile_law(m, flat.torques[k].def.torque, "torque '" + m.torques[k].name + "'",
                    m.torques[k].name, flat.torques[k].prefix);
  size_t loaded = 0, reduced = 0;  // m.springs and m.reduced_springs in the order of flat.springs
  for (const auto& sp : flat.springs) {
    SpringLoad& s = sp.def.reduce == SpringReduce::none ? m.springs[loaded++]
                                                        : m.reduced_springs[reduced++].spring;
    Quantity q;
    q.a = s.a;
    q.b = s.b;
    q.kind = K::distance;
    Quantity e = q;
    e.value = s.rest_length;
    Quantity r = q;
    r.kind = K::distance_rate;
    s.tension = compile_law(m, sp.def.tension, "spring '" + s.name + "'.tension", s.name, sp.prefix,
                            {{"length", q}, {"extension", e}, {"rate", r}});
  }
  loaded = reduced = 0;  // m.torsional_springs and m.reduced_torsional likewise
  for (size_t k = 0; k < flat.torsional.size(); ++k) {
    TorsionalLoad& l = flat.torsional[k].def.reduce == SpringReduce::none
                           ? m.torsional_springs[loaded++]
                           : m.reduced_torsional[reduced++].spring;
    Quantity a;
    a.kind = K::relative_angle;
    a.body1 = l.body1;
    a.body2 = l.body2;
    a.value = l.rest;
    Quantity r = a;
    r.kind = K::relative_rate;
    l.torque =
        compile_law(m, flat.torsional[k].def.torque, "torsional spring '" + l.name + "'.torque",
                    l.name, flat.torsional[k].prefix, {{"angle", a}, {"rate", r}});
  }
}

}  // namespace

void add_loads(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  add_forces(flat, m);
  add_springs(flat, m);
  add_torsional_springs(flat, el, red, m);
  add_points(flat, m);
  add_quantities(flat, el, red, m);
  compile_laws(flat, m);
}

}  // namespace mo2d::build
