// The quantities a law may read (mo2d/law.hpp), and laws compiled against them: every label a law
// names is resolved once, at build time, to a Quantity that dynamics/laws.cpp evaluates at a state.
// Resolution order: the law's locals, coordinate labels, quasi-velocity labels, then the derived
// quantities of m.quantities (bodies, nodes, revolute joints, springs, named points).
#include <cmath>
#include <optional>
#include <tuple>
#include <unordered_set>

#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d {
namespace build {
namespace {

using K = Quantity::Kind;

// Insert a derived quantity; a label two elements define is kept as ambiguous (an error if used).
void put(Model& m, const std::string& label, const Quantity& q) {
  auto [it, inserted] = m.quantities.emplace(label, q);
  if (!inserted) it->second.var = -2;  // ambiguous: see compile_law
}

void put_point(Model& m, const std::string& label, const BodyPoint& p, bool positions,
               bool velocities) {
  Quantity q;
  q.a = p;
  for (auto [suffix, kind, pos] :
       {std::tuple{".x", K::point_x, true}, std::tuple{".y", K::point_y, true},
        std::tuple{".vx", K::point_vx, false}, std::tuple{".vy", K::point_vy, false}}) {
    if (pos ? !positions : !velocities) continue;
    q.kind = kind;
    put(m, label + suffix, q);
  }
}

void body_quantities(Model& m) {
  for (int bi = 0; bi < static_cast<int>(m.bodies.size()); ++bi) {
    const Body& b = m.bodies[bi];
    if (b.geometry.size() >= 2) {
      Quantity q;
      q.kind = K::body_angle;
      q.body1 = bi;
      put(m, b.name + ".theta", q);
    }
    put_point(m, b.name + ".com", BodyPoint{bi, b.ci, b.cj, b.gamma, b.rho, Vec2(0, 0)}, true,
              true);
    // the nodes whose coordinates are not variables (joined to the ground): constants, rate 0
    for (size_t k = 0; k < b.node_names.size(); ++k) {
      const std::string& n = b.node_names[k];
      const BodyPoint p{bi, static_cast<int>(k), -1, 0, 0, Vec2(0, 0)};
      put_point(m, n, p, !m.coordinate_index.count(n + ".x"), !m.rate_index.count(n + ".vx"));
    }
  }
  for (size_t g = 0; g < m.ground_names.size(); ++g) {
    BodyPoint p;
    p.fixed = m.ground_positions[g];
    put_point(m, m.ground_names[g], p, true, true);
  }
}

void joint_quantities(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  for (size_t k = 0; k < flat.revolutes.size(); ++k) {
    const std::string name = flat.revolutes[k].prefix + flat.revolutes[k].def.name;
    Quantity q;
    q.body1 = el.body[red.revolutes[k][0]];
    q.body2 = el.body[red.revolutes[k][1]];
    auto angle0 = [&](int body) {
      if (body < 0 || m.bodies[body].geometry.size() < 2) return 0.0;
      const Vec2 d = m.bodies[body].geometry[1] - m.bodies[body].geometry[0];
      return std::atan2(d.y(), d.x());
    };
    q.value = angle0(q.body2) - angle0(q.body1);
    q.kind = K::relative_angle;
    put(m, name + ".angle", q);
    q.kind = K::relative_rate;
    put(m, name + ".rate", q);
  }
}

void spring_quantity(Model& m, const SpringLoad& s) {
  Quantity q;
  q.a = s.a;
  q.b = s.b;
  q.kind = K::distance;
  put(m, s.name + ".length", q);
  q.value = s.rest_length;
  put(m, s.name + ".extension", q);
  q.kind = K::distance_rate;
  put(m, s.name + ".rate", q);
}

void spring_quantities(Model& m) {
  for (const SpringLoad& s : m.springs) spring_quantity(m, s);
  for (const ReducedSpring& s : m.reduced_springs) spring_quantity(m, s.spring);
  for (const NamedPoint& p : m.points) put_point(m, p.name, p.point, true, true);
}

}  // namespace

void add_quantities(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  body_quantities(m);
  joint_quantities(flat, el, red, m);
  spring_quantities(m);
}

}  // namespace build

namespace {

std::vector<std::string> law_candidates(
    const Model& m, const std::string& prefix,
    const std::vector<std::pair<std::string, Quantity>>& locals) {
  std::vector<std::string> c;
  c.reserve(locals.size() + m.coordinate_labels.size() + m.rate_labels.size() +
            m.quantities.size());
  for (const auto& [name, q] : locals) c.push_back(name);
  for (const auto* labels : {&m.coordinate_labels, &m.rate_labels})
    for (const auto& l : *labels)
      if (l.rfind(prefix, 0) == 0) c.push_back(l.substr(prefix.size()));
  for (const auto& [l, q] : m.quantities)
    if (l.rfind(prefix, 0) == 0) c.push_back(l.substr(prefix.size()));
  return c;
}

// The quantity `label` names, seen from the instance `prefix`; nullopt if none.
std::optional<Quantity> resolve(const Model& m, const std::string& label, const std::string& prefix,
                                const std::vector<std::pair<std::string, Quantity>>& locals,
                                const std::string& what, const std::string& element) {
  for (const auto& [name, q] : locals)
    if (name == label) return q;
  const std::string full = prefix + label;
  Quantity q;
  if (auto it = m.coordinate_index.find(full); it != m.coordinate_index.end()) {
    q.kind = Quantity::Kind::coordinate;
    q.var = it->second;
    return q;
  }
  if (auto it = m.rate_index.find(full); it != m.rate_index.end()) {
    q.kind = Quantity::Kind::rate;
    q.var = it->second;
    return q;
  }
  if (auto it = m.quantities.find(full); it != m.quantities.end()) {
    if (it->second.var == -2)
      throw Error(what + ": '" + label + "' is ambiguous (two elements of that name define it)",
                  element);
    return it->second;
  }
  return std::nullopt;
}

}  // namespace

CompiledLaw compile_law(const Model& m, const Law& law, const std::string& what,
                        const std::string& element, const std::string& prefix,
                        const std::vector<std::pair<std::string, Quantity>>& locals) {
  CompiledLaw c;
  if (!law.f) {
    if (!law.args.empty()) throw Error(what + ": a law with arguments but no function", element);
    return c;
  }
  if (law.args.size() > static_cast<size_t>(kMaxLawArgs))
    throw Error(what + ": " + std::to_string(law.args.size()) + " arguments, at most " +
                    std::to_string(kMaxLawArgs),
                element);
  for (const std::string& label : law.args) {
    auto q = resolve(m, label, prefix, locals, what, element);
    if (!q)
      throw Error(what + ": unknown quantity '" + label + "'" +
                      did_you_mean(label, law_candidates(m, prefix, locals)),
                  element);
    c.args.push_back(*q);
    c.labels.push_back(prefix + label);
  }
  c.f = law.f;
  return c;
}

}  // namespace mo2d
