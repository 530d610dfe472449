#pragma once
// Points fixed in bodies (Example 2.6 (b): p = (1 - gamma) p_i + gamma p_j + rho z x (p_j - p_i)):
// their positions, velocities and the generalized force J^T F of a force applied at them
// (internal header of src/dynamics/).
#include <Eigen/Core>

#include "mo2d/model.hpp"

namespace mo2d::detail {

using Eigen::VectorXd;

// Generalized force of a force F applied at the point (ci, cj, gamma, rho): J^T F.
inline void add_point_force(const Body& b, int ci, int cj, double gamma, double rho, const Vec2& F,
                            double* local) {
  if (cj < 0) {
    local[2 * ci] += F.x();
    local[2 * ci + 1] += F.y();
    return;
  }
  // J_i^T F, J_j^T F
  local[2 * ci] += (1 - gamma) * F.x() - rho * F.y();
  local[2 * ci + 1] += rho * F.x() + (1 - gamma) * F.y();
  local[2 * cj] += gamma * F.x() + rho * F.y();
  local[2 * cj + 1] += -rho * F.x() + gamma * F.y();
  (void)b;
}

// J (x_i, x_j) of Example 2.6 (b): the point (ci, cj, gamma, rho) from its two nodes' values.
inline Vec2 combine_point(const Vec2& xi, const Vec2& xj, double gamma, double rho) {
  return {(1 - gamma) * xi.x() + rho * xi.y() + gamma * xj.x() - rho * xj.y(),
          -rho * xi.x() + (1 - gamma) * xi.y() + rho * xj.x() + gamma * xj.y()};
}

// Velocity (or acceleration, for x = q1 rates) of a body point: a fixed node contributes 0.
inline Vec2 local_velocity_of_point(const Body& b, const Eigen::Ref<const VectorXd>& x, int ci,
                                    int cj, double gamma, double rho) {
  Vec2 vi = node_velocity(b.nodes[ci], x);
  if (cj < 0) return vi;
  return combine_point(vi, node_velocity(b.nodes[cj], x), gamma, rho);
}

// Position of a body point: a fixed node (joined to the ground) sits at its fixed position, which
// is why positions must never go through the velocity helper above.
inline Vec2 local_position_of_point(const Body& b, const Eigen::Ref<const VectorXd>& q0, int ci,
                                    int cj, double gamma, double rho) {
  Vec2 pi = node_position(b.nodes[ci], q0);
  if (cj < 0) return pi;
  return combine_point(pi, node_position(b.nodes[cj], q0), gamma, rho);
}

struct PointState {
  Vec2 p, v;
};
inline PointState point_state(const Model& m, const BodyPoint& bp,
                              const Eigen::Ref<const VectorXd>& q0,
                              const Eigen::Ref<const VectorXd>& q1) {
  if (bp.body < 0) return {bp.fixed, Vec2(0, 0)};
  const Body& b = m.bodies[bp.body];
  return {local_position_of_point(b, q0, bp.ci, bp.cj, bp.gamma, bp.rho),
          local_velocity_of_point(b, q1, bp.ci, bp.cj, bp.gamma, bp.rho)};
}

}  // namespace mo2d::detail
