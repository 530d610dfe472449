// Stage 4 of build_model: number the variables and give every one a label (model.hpp, §5.3).
// q0 = two coordinates per independent node group (labelled by its first element), one slider
// coordinate per prismatic then per pin-in-slot joint, one per extra coordinate; q1 = their rates
// in the same order, then one rotation rate per independent rotation group (labelled by its first
// body). Every element of a group is an alias of the group's labels.
#include <set>

#include "mo2d/error.hpp"
#include "model/build_stages.hpp"

namespace mo2d::build {
namespace {

// Node coordinates: one pair per node group that does not touch the ground.
void number_nodes(const Elements& el, const Reduced& red, Numbering& num, Model& m) {
  const int E = el.count();
  num.node_var.assign(E, -2);  // by root element: -1 fixed, >= 0 var of x
  for (int e = 0; e < E; ++e) {
    const int r = red.node_root[e];
    if (num.node_var[r] != -2) continue;
    if (el.body[r] < 0) {
      num.node_var[r] = -1;
      continue;
    }
    num.node_var[r] = m.n0;
    m.coordinate_labels.push_back(el.label[e] + ".x");
    m.coordinate_labels.push_back(el.label[e] + ".y");
    m.rate_labels.push_back(el.label[e] + ".vx");
    m.rate_labels.push_back(el.label[e] + ".vy");
    m.rate_refs.push_back({m.n0, el.body[e], 2 * el.local[e]});
    m.rate_refs.push_back({m.n0 + 1, el.body[e], 2 * el.local[e] + 1});
    m.n0 += 2;
  }
  std::set<std::string> fixed_labels;
  for (int e = 0; e < E; ++e) {
    const int v = num.node_var[red.node_root[e]];
    if (v < 0) {
      if (el.body[e] >= 0) {
        fixed_labels.insert(el.label[e] + ".x");
        fixed_labels.insert(el.label[e] + ".y");
      }
      continue;
    }
    m.coordinate_index[el.label[e] + ".x"] = v;
    m.coordinate_index[el.label[e] + ".y"] = v + 1;
    m.rate_index[el.label[e] + ".vx"] = v;
    m.rate_index[el.label[e] + ".vy"] = v + 1;
  }
  for (int bi = 0; bi < static_cast<int>(m.bodies.size()); ++bi) {
    Body& b = m.bodies[bi];
    for (size_t k = 0; k < b.geometry.size(); ++k) {
      const int e = el.index.at(b.node_names[k]);
      const int r = red.node_root[e];
      NodeRef n;
      n.var = num.node_var[r];
      n.fixed = el.position[r];
      n.body = bi;
      n.local = static_cast<int>(k);
      b.nodes.push_back(n);
    }
  }
  m.fixed_coordinates.insert(fixed_labels.begin(), fixed_labels.end());
}

// A coordinate without a body slot (slider, extra coordinate) and its rate.
int new_var(Model& m, const std::string& label, const std::string& rate_label) {
  const int v = m.n0++;
  m.coordinate_labels.push_back(label);
  m.rate_labels.push_back(rate_label);
  m.rate_refs.push_back({v, -1, -1});
  m.coordinate_index[label] = v;
  m.rate_index[rate_label] = v;
  return v;
}

// Rotation rates: one per rotation group not locked to the ground.
void number_rotations(const Reduced& red, Model& m) {
  m.n1 = m.n0;
  const int NB = static_cast<int>(m.bodies.size());
  std::vector<int> rot_var(NB + 1, -2);
  rot_var[red.rotation_root[0]] = -1;
  for (int bi = 0; bi < NB; ++bi) {
    Body& b = m.bodies[bi];
    b.omega.body = bi;
    if (!b.has_omega) {
      b.omega.var = -1;
      continue;
    }
    const int r = red.rotation_root[bi + 1];
    if (rot_var[r] == -2) {
      rot_var[r] = m.n1++;
      m.rate_labels.push_back(b.name + ".w");
      m.rate_refs.push_back({rot_var[r], bi, b.slots() - 1});
    }
    b.omega.var = rot_var[r];
    if (rot_var[r] >= 0) m.rate_index[b.name + ".w"] = rot_var[r];
  }
  for (auto& b : m.bodies)
    if (!b.has_omega) b.omega.body = -1;  // no rotation at all: never referenced
}

// Variables owned by each subsystem: sliders, then node groups and rotations (owner of their
// first body), then extra coordinates.
void own_variables(const Flat& flat, const Numbering& num, Model& m) {
  for (size_t k = 0; k < flat.prismatics.size(); ++k)
    m.tree[flat.prismatics[k].owner].vars.push_back(num.prismatic_q[k]);
  for (size_t k = 0; k < flat.slots.size(); ++k)
    m.tree[flat.slots[k].owner].vars.push_back(num.slot_q[k]);
  for (int v = 0; v < m.n1; ++v) {
    const VarRef& r = m.rate_refs[v];
    if (r.body >= 0) m.tree[m.bodies[r.body].owner].vars.push_back(v);
  }
  for (size_t k = 0; k < flat.coordinates.size(); ++k)
    m.tree[flat.coordinates[k].owner].vars.push_back(num.coordinate_q[k]);
}

// Initial configuration as given: node positions and the slider coordinates they imply (the
// signed distance of the slider from axis_from along the axis, eq. 5.31).
void given_configuration(const Elements& el, const Reduced& red, Numbering& num, const Model& m) {
  num.q0 = Eigen::VectorXd::Zero(m.n0);
  for (int e = 0; e < el.count(); ++e) {
    const int r = red.node_root[e];
    if (r == e && num.node_var[r] >= 0) num.q0.segment<2>(num.node_var[r]) = el.position[e];
  }
  for (size_t k = 0; k < red.prismatics.size(); ++k) {
    const AxisJoint& p = red.prismatics[k];
    const Vec2 pi = el.position[p.ei], pj = el.position[p.ej];
    num.q0[num.prismatic_q[k]] = (el.position[p.es] - pi).dot((pj - pi).normalized());
  }
  for (size_t k = 0; k < red.slots.size(); ++k) {
    const AxisJoint& p = red.slots[k];
    const Vec2 pi = el.position[p.ei], pj = el.position[p.ej];
    num.q0[num.slot_q[k]] = (el.position[p.es] - pi).dot((pj - pi).normalized());
  }
}

}  // namespace

Numbering number_variables(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  Numbering num;
  number_nodes(el, red, num, m);
  for (const auto& j : flat.prismatics)
    num.prismatic_q.push_back(
        new_var(m, j.prefix + j.def.name + ".q", j.prefix + j.def.name + ".v"));
  for (const auto& j : flat.slots)
    num.slot_q.push_back(new_var(m, j.prefix + j.def.name + ".q", j.prefix + j.def.name + ".v"));
  for (const auto& c : flat.coordinates) {
    const std::string label = c.prefix + c.def.name;
    if (m.coordinate_index.count(label))
      throw Error("coordinate '" + label + "' clashes with an existing coordinate label", label);
    num.coordinate_q.push_back(new_var(m, label, label + ".rate"));
  }
  number_rotations(red, m);
  own_variables(flat, num, m);
  given_configuration(el, red, num, m);
  return num;
}

NodeRef node_ref(const Model& m, const Elements& el, int e) {
  if (el.body[e] >= 0) return m.bodies[el.body[e]].nodes[el.local[e]];
  NodeRef n;
  n.var = -1;
  n.fixed = el.position[e];
  return n;
}

}  // namespace mo2d::build
