#pragma once
// Body points as functions of the coordinates of their nodes, on Jets (Example 2.6 (b); the
// double version is detail::combine_point): the arguments of user position constraints built
// from body points (reduced springs, reduced_springs.cpp; inextensible chains,
// inextensible_chains.cpp).
#include <span>
#include <vector>

#include "constraints/common.hpp"

namespace mo2d::build {

// One node of a point: its x argument (y is the next one), or -1 and its fixed position.
struct NodeArg {
  int arg = -1;
  Vec2 fixed{0, 0};
};
struct JetPoint {
  Jet x, y;
};

// A point of the psi function: ground (fixed), one node, or two nodes with (gamma, rho).
struct PointArgs {
  NodeArg i, j;
  bool two = false;
  double gamma = 0, rho = 0;
};

inline JetPoint node_jet(const NodeArg& n, std::span<const Jet> x) {
  if (n.arg < 0) return {Jet(n.fixed.x()), Jet(n.fixed.y())};
  return {x[n.arg], x[n.arg + 1]};
}

// Example 2.6 (b) on Jets (detail::combine_point on doubles).
inline JetPoint point_jet(const PointArgs& p, std::span<const Jet> x) {
  const JetPoint a = node_jet(p.i, x);
  if (!p.two) return a;
  const JetPoint b = node_jet(p.j, x);
  const Jet g(p.gamma), r(p.rho), one_g(1 - p.gamma);
  return {one_g * a.x + r * a.y + g * b.x - r * b.y, -r * a.x + one_g * a.y + r * b.x + g * b.y};
}

inline NodeArg node_arg(const NodeRef& n, std::vector<VarRef>& args) {
  if (n.var < 0) return {-1, n.fixed};
  const int at = static_cast<int>(args.size());
  args.push_back(detail::ref_x(n));
  args.push_back(detail::ref_y(n));
  return {at, {0, 0}};
}

inline PointArgs point_args(const Model& m, const BodyPoint& bp, std::vector<VarRef>& args) {
  PointArgs p;
  if (bp.body < 0) {
    p.i.fixed = bp.fixed;
    return p;
  }
  const Body& b = m.bodies[bp.body];
  p.i = node_arg(b.nodes[bp.ci], args);
  if (bp.cj < 0) return p;
  p.two = true;
  p.j = node_arg(b.nodes[bp.cj], args);
  p.gamma = bp.gamma;
  p.rho = bp.rho;
  return p;
}

}  // namespace mo2d::build
