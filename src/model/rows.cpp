// Stage 5 of build_model: the constraint rows (constraints/constraints.hpp gives their equations),
// numbered in this order: rigid bodies (Example 2.6), revolute joints that are not eliminated,
// prismatic joints (eq. 5.31, with the rotation lock of eq. 5.30 unless it is eliminated),
// pin-in-slot joints, extra coordinates, gears and racks (gears.cpp), user position and velocity
// constraints. Each row has a label (constraint name + suffix). With them: the reactions (which
// velocity row's multiplier gives each joint force; eliminated joints get theirs from the merge
// edges) and the inputs (columns of B: the generalized force per unit actuator effort).
#include <cmath>

#include "constraints/constraints.hpp"
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

bool is_integer(double w) {
  return std::abs(w - std::round(w)) < 1e-12;
}

}  // namespace

int add_constraint(Model& m, Constraint c, int nrow0, int nrow1,
                   const std::vector<std::string>& labels0,
                   const std::vector<std::string>& labels1) {
  c.row0 = m.m0;
  c.nrow0 = nrow0;
  c.row1 = m.m1;
  c.nrow1 = nrow1;
  m.m0 += nrow0;
  m.m1 += nrow1;
  for (int k = 0; k < nrow0; ++k)
    m.position_row_labels.push_back(c.name + (k < (int)labels0.size() ? labels0[k] : ""));
  for (int k = 0; k < nrow1; ++k)
    m.velocity_row_labels.push_back(c.name + (k < (int)labels1.size() ? labels1[k] : ""));
  for (int k = 0; k < nrow1; ++k) m.tree[c.owner].rows.push_back(c.row1 + k);
  m.constraints.push_back(std::move(c));
  return static_cast<int>(m.constraints.size()) - 1;
}

namespace {

// A body with n >= 2 nodes: 1 + 2 (n - 2) position rows, 2 (n - 1) velocity rows.
void add_rigid_rows(Model& m) {
  for (int bi = 0; bi < static_cast<int>(m.bodies.size()); ++bi) {
    const Body& b = m.bodies[bi];
    const int n = static_cast<int>(b.nodes.size());
    if (n < 2) continue;
    Constraint c{.name = b.name, .owner = b.owner, .def = Constraint::Rigid{bi}};
    std::vector<std::string> l0{".rigid(d01)"}, l1;
    for (int k = 2; k < n; ++k) {
      l0.push_back(".rigid(" + std::to_string(k) + "x)");
      l0.push_back(".rigid(" + std::to_string(k) + "y)");
    }
    for (int k = 1; k < n; ++k) {
      l1.push_back(".rigid(v" + std::to_string(k) + "x)");
      l1.push_back(".rigid(v" + std::to_string(k) + "y)");
    }
    add_constraint(m, std::move(c), 1 + 2 * (n - 2), 2 * (n - 1), l0, l1);
  }
}

// The torque input of a joint between body1 and body2: u on body 2, -u on body 1. `no_rotation`
// words the error for a body without a rotation.
template <class NoRotation>
Input joint_torque(const Model& m, const std::string& name, int body1, int body2,
                   NoRotation&& no_rotation) {
  Input in;
  in.label = name + ".torque";
  in.joint = name;
  for (auto [body, sgn] : {std::pair{body2, 1.0}, std::pair{body1, -1.0}}) {
    if (body < 0) continue;
    if (!m.bodies[body].has_omega) throw Error(no_rotation(m.bodies[body].name), name);
    in.terms.push_back({detail::ref_w(m, m.bodies[body].omega), sgn});
  }
  return in;
}

void add_revolute_rows(const Flat& flat, const Elements& el, const Reduced& red, Model& m,
                       JointReactions& out) {
  for (size_t k = 0; k < flat.revolutes.size(); ++k) {
    const auto& j = flat.revolutes[k];
    const std::string name = j.prefix + j.def.name;
    const auto [ea, eb] = red.revolutes[k];
    const int reaction = m.n_reactions();
    out.revolute.push_back(reaction);
    m.reactions.push_back({name + ".Fx", -1, -1});
    m.reactions.push_back({name + ".Fy", -1, -1});
    if (!red.revolute_merged[k]) {
      Constraint::Revolute d;
      d.a = node_ref(m, el, ea);
      d.b = node_ref(m, el, eb);
      d.body1 = el.body[ea];
      d.body2 = el.body[eb];
      Constraint c{.name = name, .owner = j.owner, .def = d};
      const int ci = add_constraint(m, std::move(c), 2, 2, {".x", ".y"}, {".vx", ".vy"});
      m.reactions[reaction].row = m.constraints[ci].row1;
      m.reactions[reaction + 1].row = m.constraints[ci].row1 + 1;
    }
    if (j.def.actuated)
      m.inputs.push_back(
          joint_torque(m, name, el.body[ea], el.body[eb], [&](const std::string& body) {
            return "actuated revolute joint '" + name + "': body '" + body +
                   "' has no rotation (a one-node body without inertia)";
          }));
  }
}

// The part of a prismatic joint or pin-in-slot that they share: the slider on its axis.
Constraint::Slider slider(const AxisJoint& p, int q, const Elements& el, const Model& m) {
  Constraint::Slider d;
  d.i = node_ref(m, el, p.ei);
  d.j = node_ref(m, el, p.ej);
  d.s = node_ref(m, el, p.es);
  d.q = q;
  d.length = (el.position[p.ej] - el.position[p.ei]).norm();
  d.body1 = p.body1;
  d.body2 = p.body2;
  return d;
}

void add_prismatic_rows(const Flat& flat, const Elements& el, const Reduced& red,
                        const Numbering& num, Model& m, JointReactions& out) {
  for (size_t k = 0; k < flat.prismatics.size(); ++k) {
    const auto& j = flat.prismatics[k];
    const AxisJoint& p = red.prismatics[k];
    const std::string name = j.prefix + j.def.name;
    Constraint::Prismatic d;
    static_cast<Constraint::Slider&>(d) = slider(p, num.prismatic_q[k], el, m);
    const bool oriented1 = p.body1 < 0 || m.bodies[p.body1].nodes.size() >= 2;
    const bool oriented2 = p.body2 < 0 || m.bodies[p.body2].nodes.size() >= 2;
    d.lock_position = p.lock && oriented1 && oriented2;
    d.lock_velocity = p.lock && !p.merged;
    if (p.lock) {
      d.w1 = p.body1 < 0 ? OmegaRef{} : m.bodies[p.body1].omega;
      d.w2 = p.body2 < 0 ? OmegaRef{} : m.bodies[p.body2].omega;
    }
    if (d.lock_position) d.lock_angle = initial_angle(m, p.body2) - initial_angle(m, p.body1);
    std::vector<std::string> l0{".x", ".y"}, l1{".vx", ".vy"};
    if (d.lock_position) l0.push_back(".angle");
    if (d.lock_velocity) l1.push_back(".w");
    const int nr0 = 2 + (d.lock_position ? 1 : 0), nr1 = 2 + (d.lock_velocity ? 1 : 0);
    Constraint c{.name = name, .owner = j.owner, .def = std::move(d)};
    const int ci = add_constraint(m, std::move(c), nr0, nr1, l0, l1);
    const int reaction = m.n_reactions();
    m.reactions.push_back({name + ".Fx", m.constraints[ci].row1, -1});
    m.reactions.push_back({name + ".Fy", m.constraints[ci].row1 + 1, -1});
    out.prismatic.push_back(p.lock ? reaction + 2 : -1);
    if (p.lock)
      m.reactions.push_back({name + ".T", p.merged ? -1 : m.constraints[ci].row1 + 2, -1});
    if (j.def.actuated)
      m.inputs.push_back({name + ".force", name, {{VarRef{num.prismatic_q[k], -1, -1}, 1.0}}});
  }
}

void add_slot_rows(const Flat& flat, const Elements& el, const Reduced& red, const Numbering& num,
                   Model& m) {
  for (size_t k = 0; k < flat.slots.size(); ++k) {
    const auto& j = flat.slots[k];
    const AxisJoint& p = red.slots[k];
    const std::string name = j.prefix + j.def.name;
    Constraint c{.name = name, .owner = j.owner, .def = slider(p, num.slot_q[k], el, m)};
    const int ci = add_constraint(m, std::move(c), 2, 2, {".x", ".y"}, {".vx", ".vy"});
    m.reactions.push_back({name + ".Fx", m.constraints[ci].row1, -1});
    m.reactions.push_back({name + ".Fy", m.constraints[ci].row1 + 1, -1});
    if (j.def.actuated_slide)
      m.inputs.push_back({name + ".force", name, {{VarRef{num.slot_q[k], -1, -1}, 1.0}}});
    if (j.def.actuated_rotation)
      m.inputs.push_back(joint_torque(m, name, p.body1, p.body2, [&](const std::string& body) {
        return "pin-in-slot joint '" + name + "': torque on body '" + body +
               "', which has no rotation";
      }));
  }
}

// Variable named by a label seen from the instance `prefix`, for an extra coordinate or a user
// constraint called `what`.
int find_coordinate(const Model& m, const std::string& prefix, const std::string& label,
                    const std::string& what) {
  auto it = m.coordinate_index.find(prefix + label);
  if (it != m.coordinate_index.end()) return it->second;
  if (m.fixed_coordinates.count(prefix + label))
    throw Error(what + ": coordinate '" + prefix + label + "' is fixed (joined to the ground)",
                prefix + label);
  std::vector<std::string> names;
  for (const auto& [k, v] : m.coordinate_index) names.push_back(k);
  throw Error(
      what + ": unknown coordinate '" + prefix + label + "'" + did_you_mean(prefix + label, names),
      prefix + label);
}
int find_rate(const Model& m, const std::string& prefix, const std::string& label,
              const std::string& what) {
  auto it = m.rate_index.find(prefix + label);
  if (it != m.rate_index.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& [k, v] : m.rate_index) names.push_back(k);
  throw Error(what + ": unknown quasi-velocity '" + prefix + label + "'" +
                  did_you_mean(prefix + label, names),
              prefix + label);
}

// Extra coordinate: d/dt q_e = sum w v; holonomic (one position row) if every term is a
// coordinate or an integer multiple of a body angle. Its initial value defaults to the one the
// terms imply at the given configuration.
void add_coordinate_rows(const Flat& flat, Numbering& num, Model& m) {
  for (size_t k = 0; k < flat.coordinates.size(); ++k) {
    const auto& cd = flat.coordinates[k];
    const std::string name = cd.prefix + cd.def.name;
    const std::string what = "coordinate '" + name + "'";
    if (cd.def.rate.empty()) throw Error(what + " has no rate terms", name);
    Constraint::Coordinate c;
    c.coord = num.coordinate_q[k];
    double implied = 0;
    for (const auto& [label, w] : cd.def.rate) {
      if (!std::isfinite(w)) throw Error(what + ": non-finite weight for '" + label + "'", name);
      const int v = find_rate(m, cd.prefix, label, what);
      if (v == c.coord) throw Error(what + " is defined by its own rate", name);
      c.rate_terms.push_back({m.rate_refs[v], w});
      if (v < m.n0) {
        c.coord_terms.push_back({v, w});
        implied += w * num.q0[v];
      } else {
        const int body = m.rate_refs[v].body;
        if (m.bodies[body].nodes.size() < 2 || !is_integer(w)) {
          c.holonomic = false;
        } else {
          c.angle_terms.push_back({body, w});
          const Vec2 d = m.bodies[body].geometry[1] - m.bodies[body].geometry[0];
          implied += w * std::atan2(d.y(), d.x());
        }
      }
    }
    if (!c.holonomic) {
      c.coord_terms.clear();
      c.angle_terms.clear();
    }
    if (cd.def.initial && !std::isfinite(*cd.def.initial))
      throw Error(what + ": initial value is not finite", name);
    num.q0[c.coord] = cd.def.initial.value_or(implied);
    c.offset = num.q0[c.coord] - implied;
    if (!cd.def.input.empty())  // power u * rate: u times each weight on its term
      m.inputs.push_back({cd.prefix + cd.def.input, name, c.rate_terms});
    const int nrow0 = c.holonomic ? 1 : 0;
    add_constraint(m, Constraint{.name = name, .owner = cd.owner, .def = std::move(c)}, nrow0, 1,
                   {""}, {".rate"});
  }
}

void add_user_rows(const Flat& flat, const Numbering& num, Model& m) {
  for (const auto& pc : flat.pos) {
    const std::string name = pc.prefix + pc.def.name;
    const std::string what = "constraint '" + name + "'";
    if (!pc.def.psi) throw Error(what + " has no function", name);
    if (pc.def.args.size() > static_cast<size_t>(detail::kMaxUserArgs))
      throw Error(what + " has more than 32 arguments", name);
    Constraint::UserPosition d;
    d.psi = pc.def.psi;
    for (const auto& a : pc.def.args)
      d.args.push_back(m.rate_refs[find_coordinate(m, pc.prefix, a, what)]);
    Constraint c{.name = name, .owner = pc.owner, .def = std::move(d)};
    const int ci = add_constraint(m, std::move(c), 1, 1, {""}, {".rate"});
    m.reactions.push_back({name + ".lambda", m.constraints[ci].row1, 1});
  }
  for (const auto& vc : flat.vel) {
    const std::string name = vc.prefix + vc.def.name;
    const std::string what = "constraint '" + name + "'";
    const VelocityConstraintDef def =
        vc.def.g_labels ? sort_velocity_labels(m, vc.prefix, vc.def, what) : vc.def;
    if (!def.g) throw Error(what + " has no function", name);
    if (def.coords.size() > static_cast<size_t>(detail::kMaxUserArgs) ||
        def.rates.size() > static_cast<size_t>(detail::kMaxUserArgs))
      throw Error(what + " has more than 32 arguments", name);
    Constraint::UserVelocity d;
    d.g = def.g;
    for (const auto& a : def.coords)
      d.args.push_back(m.rate_refs[find_coordinate(m, vc.prefix, a, what)]);
    for (const auto& a : def.rates)
      d.rates.push_back(m.rate_refs[find_rate(m, vc.prefix, a, what)]);
    check_linear_in_rates(d, def, num.q0, what, name);
    Constraint c{.name = name, .owner = vc.owner, .def = std::move(d)};
    const int ci = add_constraint(m, std::move(c), 0, 1, {}, {""});
    m.reactions.push_back({name + ".lambda", m.constraints[ci].row1, 1});
  }
}

}  // namespace

JointReactions add_rows(const Flat& flat, const Elements& el, const Reduced& red, Numbering& num,
                        Model& m) {
  JointReactions out;
  add_rigid_rows(m);
  add_revolute_rows(flat, el, red, m, out);
  add_prismatic_rows(flat, el, red, num, m, out);
  add_slot_rows(flat, el, red, num, m);
  add_coordinate_rows(flat, num, m);
  add_gear_rows(flat, num, m);
  add_user_rows(flat, num, m);
  return out;
}

double initial_angle(const Model& m, int body) {
  if (body < 0) return 0.0;
  const Vec2 d = m.bodies[body].geometry[1] - m.bodies[body].geometry[0];
  return std::atan2(d.y(), d.x());
}

}  // namespace mo2d::build
