#pragma once
// The geometry problem of bodies given by their shape (BodyDef::shape), internal to stage 1b of
// build_model (sketch.cpp). Each such body is a rigid shape placed by a pose (origin o, angle θ):
// its node k is at p_k = o + R(θ) s_k, s_k its shape coordinates (a one-node body has no angle).
// The joints are closure conditions g(x) = 0 on the poses x:
//   revolute:               p_a − p_b = 0                       (2 rows, m)
//   prismatic, pin-in-slot: ((p_j − p_i) × (p_s − p_i)) / |p_j − p_i| = 0   (1 row: the distance
//                           of the slider from the axis line, m)
// and the configuration sought is the nearest to the sketch p̂:
//   minimize f(x) = ½ Σ_k |p_k(x) − p̂_k|²   subject to g(x) = 0,
// over every node of every body with a shape (the ground and the bodies without a shape are held
// where they are written: they enter g as fixed points).
//
// Method (solve_sketch): every step is measured in the metric of f, i.e. by how far it moves the
// nodes: for body b, H_b = Σ_k J_kᵀ J_k with J_k = ∂p_k/∂(o, θ) = [I, z × R s_k], and the scaled
// step y = L_bᵀ Δx_b (H_b = L_b L_bᵀ) has |y|² = Σ_k |Δp_k|² to first order.
//   1. closure: Gauss-Newton on g = 0 from the best rigid fit of each shape to its sketch with
//      the minimum-norm step y = −B⁺ g, B = G L⁻ᵀ (G = ∂g/∂x), and an Armijo search on |g|₂:
//      it closes the joints moving the nodes least, so it stays on the branch of the sketch.
//      Iterated until |g| stops decreasing (round-off).
//   2. nearest: from there, Gauss-Newton for the constrained least squares: the step
//      y = −B⁺ g − N Nᵀ Qᵀ r (N: orthonormal null space of B; Qᵀ r = L⁻¹ ∂f/∂x, the gradient of f
//      in the scaled step), then closure again; far from the optimum a step is accepted when f
//      decreases, near it (|N Nᵀ Qᵀ r| < 1e-6 of the size) when the tangential gradient does
//      (f's decrease is then below its round-off). It stops where the tangential gradient is
//      below 1e-14 of the size (first-order optimality: the nodes' displacement is orthogonal
//      to every motion the joints allow) or cannot decrease.
#include <Eigen/Core>
#include <vector>

#include "mo2d/system.hpp"

namespace mo2d::build::sketch {

// A point of the problem: node `node` of free body `body`, or (body -1) the fixed point `fixed`.
struct Point {
  int body = -1;
  int node = -1;
  Vec2 fixed{0, 0};
};

// One joint's closure: a == b (revolute), or c on the line a -> b (prismatic, pin-in-slot).
struct Closure {
  bool on_line = false;
  Point a, b, c;
  int joint = -1;  // index of the joint, for the caller's messages
};

struct FreeBody {
  std::vector<Vec2> shape;   // node coordinates in the body's frame (exact)
  std::vector<Vec2> sketch;  // the same nodes' sketched positions (world)
  bool rotates() const { return shape.size() >= 2; }
};

struct Pose {
  Vec2 origin{0, 0};
  double angle = 0;
  Vec2 apply(const Vec2& s) const { return Placement{origin, angle}.apply(s); }
};

struct Problem {
  std::vector<FreeBody> bodies;
  std::vector<Closure> closures;
  double size = 1;       // the mechanism's size (m): the scale of the stopping tests
  double tolerance = 0;  // a joint is closed when its gap is at most this (m)
};

struct Result {
  std::vector<Pose> poses;   // per free body
  bool closed = false;       // every gap <= Problem::tolerance
  std::vector<double> gaps;  // per closure: its gap at `poses` (m; |p_a - p_b| or the distance)
  bool nearest = false;      // the nearest configuration was reached (see above)
  double tangential = 0;     // the last tangential gradient |N Nᵀ Qᵀ r| (m)
};

// The rigid placement of `shape` nearest to `sketch` (least squares, rotation without mirror).
Pose best_fit(const std::vector<Vec2>& shape, const std::vector<Vec2>& sketch);

Result solve_sketch(const Problem& problem);

}  // namespace mo2d::build::sketch
