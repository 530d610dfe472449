// The shaking force and moment (mo2d/design.hpp): the force and moment the moving links exert on
// the frame, summed over what joins them to it. A joint's reaction (Fx, Fy) is the force of body 1
// on body 2 (include/mo2d/system.hpp), so a joint whose body 1 is the ground loads the frame with
// -(Fx, Fy) at the joint, one whose body 2 is the ground with +(Fx, Fy); likewise the lock torque
// T of a prismatic joint, the actuator torque of a revolute joint or pin-in-slot (u on body 2, -u
// on body 1), a torsional spring's torque (on body 2, its opposite on body 1), and a spring's
// tension at its ground end. A prismatic's (Fx, Fy) includes its actuator's force. Gravity and
// the applied forces and torques act on the links from outside, not through the frame.
#include <cmath>

#include "design/design_internal.hpp"
#include "dynamics/points.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d::design_detail {

namespace {

// A force on the frame: sign * (reaction fx, fy) at a node; a couple: sign * reaction or effort.
struct FrameForce {
  int fx = -1;  // reaction column of Fx (Fy follows)
  NodeRef at{};
  double sign = 1;
};
struct FrameCouple {
  int column = -1;
  bool effort = false;  // an effort column (else a reaction column)
  double sign = 1;
};
struct FramePlan {
  std::vector<FrameForce> forces;
  std::vector<FrameCouple> couples;
  std::vector<int> springs, torsional;  // ground-anchored, Model::springs / torsional_springs
};

[[noreturn]] void refuse_frame(const std::string& kind, const std::string& name, const char* why) {
  throw Error("frame loads: " + kind + " '" + name + "' " + why +
                  ": the shaking force and moment are not computed for it (docs/design.md)",
              name);
}

bool user_row_of_load(const Model& m, int ci) {
  for (const ReducedSpring& s : m.reduced_springs)
    if (s.constraint == ci) {
      if (s.spring.a.body < 0 || s.spring.b.body < 0)
        refuse_frame("spring", s.spring.name,
                     "is anchored to the ground and reduced to a constraint");
      return true;
    }
  for (const ReducedTorsional& s : m.reduced_torsional)
    if (s.constraint == ci) {
      if (s.spring.body1 < 0 || s.spring.body2 < 0)
        refuse_frame("torsional spring", s.spring.name, "acts on the ground and is reduced");
      return true;
    }
  for (const ChainLoad& c : m.chains)
    if (c.constraint == ci) return true;
  return false;
}

// The joints of the model and what they pass to the frame.
void plan_constraints(const Model& m, const Trajectory& r, FramePlan& p) {
  for (int ci = 0; ci < static_cast<int>(m.constraints.size()); ++ci) {
    const Constraint& c = m.constraints[ci];
    switch (c.kind()) {
      case ConstraintKind::revolute: {
        const auto& d = c.as<Constraint::Revolute>();
        if (d.body1 >= 0 && d.body2 >= 0) break;
        p.forces.push_back(
            {r.reaction(c.name + ".Fx"), d.body1 < 0 ? d.a : d.b, d.body1 < 0 ? -1.0 : 1.0});
        break;
      }
      case ConstraintKind::prismatic:
      case ConstraintKind::slot: {
        const Constraint::Slider& d = *c.slider();
        if (d.body1 >= 0 && d.body2 >= 0) break;
        const double sign = d.body1 < 0 ? -1.0 : 1.0;
        p.forces.push_back({r.reaction(c.name + ".Fx"), d.s, sign});
        if (c.kind() == ConstraintKind::prismatic) {
          const auto& pr = c.as<Constraint::Prismatic>();
          // a lock kept as a row: its torque here; a merged one comes with the merge edges
          if (pr.lock_velocity) p.couples.push_back({r.reaction(c.name + ".T"), false, sign});
        }
        break;
      }
      case ConstraintKind::gear:
        refuse_frame("gear", c.name, "passes torques through its carrier");
      case ConstraintKind::user_position:
      case ConstraintKind::user_velocity:
        if (!user_row_of_load(m, ci))
          refuse_frame("constraint", c.name, "may act between the links and the world");
        break;
      case ConstraintKind::rigid:
      case ConstraintKind::coordinate:
        break;
    }
  }
}

FramePlan frame_plan(const Model& m, const Trajectory& r) {
  FramePlan p;
  plan_constraints(m, r, p);
  for (const MergeEdge& e : m.merge_edges) {  // joints eliminated by variable reduction
    if (e.parent_body >= 0) continue;
    // reaction = sign * (force of the parent, the ground, on the child): the frame gets its
    // opposite
    if (e.rotation)
      p.couples.push_back({e.reaction, false, -e.sign});
    else
      p.forces.push_back({e.reaction, m.bodies[e.child_body].nodes[e.child_slot / 2], -e.sign});
  }
  for (int k = 0; k < m.n_inputs(); ++k) {  // torques of actuators at ground joints
    const Input& in = m.inputs[k];
    if (in.terms.size() != 1 || in.terms[0].first.body < 0) continue;  // internal, or a slide
    const VarRef& v = in.terms[0].first;
    if (m.bodies[v.body].omega.var != v.var) continue;
    p.couples.push_back({r.effort(in.label), true, -in.terms[0].second});
  }
  for (int k = 0; k < static_cast<int>(m.springs.size()); ++k)
    if (m.springs[k].a.body < 0 || m.springs[k].b.body < 0) p.springs.push_back(k);
  for (int k = 0; k < static_cast<int>(m.torsional_springs.size()); ++k)
    if (m.torsional_springs[k].body1 < 0 || m.torsional_springs[k].body2 < 0)
      p.torsional.push_back(k);
  for (const ChainLoad& c : m.chains)
    if (c.body_a < 0 || c.body_b < 0) refuse_frame("chain", c.name, "has a sprocket on the ground");
  for (const FrictionLoad& f : m.frictions)
    for (const FrameForce& ff : p.forces)
      if (r.reaction_labels[ff.fx] == f.joint + ".Fx")
        refuse_frame("friction", f.name, "acts in a joint to the ground");
  return p;
}

}  // namespace

Block frame_columns(const Model& m, const Trajectory& r, const Vec2& about) {
  const FramePlan p = frame_plan(m, r);
  Block out{{"frame.shaking.Fx", "frame.shaking.Fy", "frame.shaking.F", "frame.shaking.M"}, {}};
  const Eigen::Index N = r.time.size();
  out.values.resize(N, 4);
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = r.q0.row(k).transpose(), q1 = r.q1.row(k).transpose();
    Vec2 F(0, 0);
    double M = 0;
    auto add = [&](const Vec2& f, const Vec2& at) {
      F += f;
      M += cross_z(at - about, f);
    };
    for (const FrameForce& f : p.forces)
      add(f.sign * Vec2(r.reactions(k, f.fx), r.reactions(k, f.fx + 1)), node_position(f.at, q0));
    for (const FrameCouple& c : p.couples)
      M += c.sign * (c.effort ? r.efforts(k, c.column) : r.reactions(k, c.column));
    for (int s : p.springs) {  // tension > 0 pulls each end towards the other
      const SpringLoad& sp = m.springs[s];
      const double T = spring_value(m, sp, q0, q1, r.time[k]).tension;
      const Vec2 a = detail::point_state(m, sp.a, q0, q1).p,
                 b = detail::point_state(m, sp.b, q0, q1).p;
      const Vec2 e = (b - a).normalized();
      if (sp.a.body < 0) add(T * e, a);
      if (sp.b.body < 0) add(-T * e, b);
    }
    for (int s : p.torsional) {
      const TorsionalLoad& t = m.torsional_springs[s];
      const double tau = torsional_value(m, t, q0, q1, r.time[k]).torque;
      M += t.body1 < 0 ? -tau : tau;
    }
    out.values.row(k) << F.x(), F.y(), F.norm(), M;
  }
  return out;
}

}  // namespace mo2d::design_detail
