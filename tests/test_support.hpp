#pragma once
// Shared helpers for the validation tests: an energy function written independently of the
// solver (centre of mass and rotation rate recomputed from node positions and velocities).
#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <string>
#include <vector>

#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/system.hpp"

namespace mo2d::test {

struct NodeState {
  Eigen::Vector2d p, v, a;
};

// Position, velocity, acceleration of node k of body b at sample i of a result.
inline NodeState node_state(const Model& m, const Trajectory& r, int i, int b, int k) {
  const NodeRef& n = m.bodies[b].nodes[k];
  if (n.var < 0) return {n.fixed, {0, 0}, {0, 0}};
  return {{r.q0(i, n.var), r.q0(i, n.var + 1)},
          {r.q1(i, n.var), r.q1(i, n.var + 1)},
          {r.a1(i, n.var), r.a1(i, n.var + 1)}};
}

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Inertial parameters taken from the user's definitions (not from the compiled Model), in the
// order build_model flattens the tree: a System's own bodies, then its instances in order.
struct Params {
  double mass = 0, inertia = 0;
  int ci = 0, cj = -1;
  double gamma = 0, rho = 0;
};

inline void collect_params(const System& s, std::vector<Params>& out,
                           std::vector<const System*>& pending) {
  for (const BodyDef& b : s.bodies()) {
    Params p{b.mass, b.inertia, 0, -1, 0, 0};
    auto index = [&](const std::string& n) {
      for (size_t k = 0; k < b.nodes.size(); ++k)
        if (b.nodes[k].name == n) return static_cast<int>(k);
      return -1;
    };
    if (b.com) {
      if (b.com->kind == CenterOfMass::Kind::node) {
        p.ci = index(b.com->node_i);
      } else if (b.com->kind == CenterOfMass::Kind::nodes) {
        p.ci = index(b.com->node_i), p.cj = index(b.com->node_j);
        p.gamma = b.com->gamma, p.rho = b.com->rho;
      } else {  // point: solve c - p0 = gamma d + rho z x d
        const Eigen::Vector2d d = b.nodes[1].position - b.nodes[0].position;
        const Eigen::Vector2d r = b.com->point - b.nodes[0].position;
        Eigen::Matrix2d G;
        G << d.x(), -d.y(), d.y(), d.x();
        const Eigen::Vector2d gr = G.inverse() * r;
        p.ci = 0, p.cj = 1, p.gamma = gr.x(), p.rho = gr.y();
      }
    }
    out.push_back(p);
  }
  for (const auto& inst : s.instances()) collect_params(*inst.system, out, pending);
}

inline std::vector<Params> params_of(const System& s) {
  std::vector<Params> out;
  std::vector<const System*> pending;
  collect_params(s, out, pending);
  return out;
}

struct BodyMotion {
  Eigen::Vector2d c, vc, ac;  // centre of mass
  double w = 0, wdot = 0;     // rotation rate from two nodes: w = (r x r') / |r|^2
};

// Centre of mass from its defining nodes (Example 2.6 (b)), rotation from nodes 0 and 1.
inline BodyMotion body_motion(const Model& m, const Trajectory& r, int i, int b,
                              const Params* par = nullptr) {
  const Body& body = m.bodies[b];
  Params own{body.mass, body.inertia, body.ci, body.cj, body.gamma, body.rho};
  const Params& P = par ? *par : own;
  BodyMotion out;
  const NodeState ni = node_state(m, r, i, b, P.ci);
  if (P.cj < 0) {
    out.c = ni.p, out.vc = ni.v, out.ac = ni.a;
  } else {
    const NodeState nj = node_state(m, r, i, b, P.cj);
    auto perp = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); };
    const Eigen::Vector2d d = nj.p - ni.p, dv = nj.v - ni.v, da = nj.a - ni.a;
    out.c = ni.p + P.gamma * d + P.rho * perp(d);
    out.vc = ni.v + P.gamma * dv + P.rho * perp(dv);
    out.ac = ni.a + P.gamma * da + P.rho * perp(da);
  }
  if (body.nodes.size() >= 2) {
    const NodeState n0 = node_state(m, r, i, b, 0), n1 = node_state(m, r, i, b, 1);
    const Eigen::Vector2d d = n1.p - n0.p, dv = n1.v - n0.v, da = n1.a - n0.a;
    out.w = cross(d, dv) / d.squaredNorm();
    out.wdot = cross(d, da) / d.squaredNorm();  // |d| is constant
  }
  return out;
}

inline int body_index(const Model& m, const std::string& name) {
  for (size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].name == name) return static_cast<int>(b);
  return -1;
}

// dE/dt = sum m vc.ac + I w wdot - m g.vc  (kinetic + potential energy rate), with the
// parameters of the definitions and the gravity g.
inline double energy_rate(const Model& m, const Trajectory& r, int i,
                          const std::vector<Params>& par, const Eigen::Vector2d& g) {
  double p = 0;
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyMotion bm = body_motion(m, r, i, static_cast<int>(b), &par[b]);
    p += par[b].mass * bm.vc.dot(bm.ac) + par[b].inertia * bm.w * bm.wdot;
    p -= par[b].mass * g.dot(bm.vc);
  }
  return p;
}

inline double energy(const Model& m, const Trajectory& r, int i) {
  double e = 0;
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyMotion bm = body_motion(m, r, i, static_cast<int>(b));
    e += 0.5 * m.bodies[b].mass * bm.vc.squaredNorm() + 0.5 * m.bodies[b].inertia * bm.w * bm.w;
    e -= m.bodies[b].mass * m.gravity.dot(bm.c);
  }
  return e;
}

// Largest |a - b| over all entries, relative to the largest |b| of each column (floor: abs).
inline double max_relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                      double floor = 1e-12) {
  double worst = 0;
  for (int j = 0; j < a.cols(); ++j) {
    const double scale = std::max(b.col(j).cwiseAbs().maxCoeff(), floor);
    worst = std::max(worst, (a.col(j) - b.col(j)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

// A parallelogram four-bar lying flat (ground, crank, coupler and rocker on the x axis, unit
// links): the constraint Jacobian loses rank there (the DOF jumps from 1 to 2). Not assembled.
inline System flat_parallelogram() {
  System s("flat");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {1, 0});
  s.add_body({.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {1, 0}}}, .mass = 1, .inertia = 1});
  s.add_body({.name = "coupler", .nodes = {{"A", {1, 0}}, {"B", {2, 0}}}, .mass = 1, .inertia = 1});
  s.add_body({.name = "rocker", .nodes = {{"O", {1, 0}}, {"B", {2, 0}}}, .mass = 1, .inertia = 1});
  s.add_revolute({.name = "p1", .node_a = "ground.A0", .node_b = "crank.O"});
  s.add_revolute({.name = "p2", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "p3", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "p4", .node_a = "ground.B0", .node_b = "rocker.O"});
  return s;
}

}  // namespace mo2d::test
