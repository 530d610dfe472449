#pragma once
// The tangent of a contact (internal to src/contact/; Coulomb friction, docs/contact.md): the
// sliding rate v_t, the relative velocity along the tangent t of the two bodies' material points
// at the contact point Q,
//
//   v_t = t . (v_P - v_A) + w1 ((Q - P) x t) - w2 ((Q - A) x t)     (a x b = a_x b_y - a_y b_x)
//
// (a rigid body's point X moves at v_O + w z x (X - O), and t . (z x r) = r x t), with P the
// contact's point on body 1 (rotation rate w1), A the target's point a on body 2 (w2; a line's b
// on the same body), n the gap's unit normal and
//
//   line:    t = (B - A) / |B - A|,  n = z x t,  Q = P - r n
//   circle:  n = s (P - A) / |P - A| (s = +1 outside, -1 a hole),  t = (n_y, -n_x),  Q = P - r n
//
// (so n x t = -1 and (Q - P) x t = r for every kind: a ball of radius r rolling on a line has
// v_t = v_P . t + r w1 = 0). v_t is linear in the velocities: J_t = dv_t/dq1 (n1, the rotation
// rates' entries included) is t mapped by the body points' linear maps plus the lever arms on the
// rotation rates. The bias dv_t/dt - J_t a = (d J_t/ds along q0 + s q0') q1 comes from the same
// expression on Jets (mo2d/jet.hpp), the points moving at their velocities and the velocities held.
// tests/contact/tangent_test.cpp checks v_t against the central difference of the material points'
// relative displacement along t under rigid motions, and the bias against the central difference
// of v_t along q1.
#include <cmath>

#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

// The tangent's geometry at one configuration: t, and the lever arms (Q - P) x t, (Q - A) x t.
template <class T>
struct TangentGeometry {
  T tx, ty, arm1, arm2;
};

// kind: 0 line (through A, B), +1 circle from outside, -1 hole (around A)
template <class T>
TangentGeometry<T> tangent_geometry(T px, T py, T ax, T ay, T bx, T by, double r, int kind) {
  using std::hypot;
  T nx, ny, tx, ty;
  if (kind == 0) {
    const T L = hypot(bx - ax, by - ay);
    tx = (bx - ax) / L;
    ty = (by - ay) / L;
    nx = -ty;
    ny = tx;
  } else {
    const T D = hypot(px - ax, py - ay);
    nx = static_cast<double>(kind) * (px - ax) / D;
    ny = static_cast<double>(kind) * (py - ay) / D;
    tx = ny;
    ty = -nx;
  }
  const T qx = px - r * nx, qy = py - r * ny;  // the contact point Q
  return {tx, ty, (qx - px) * ty - (qy - py) * tx, (qx - ax) * ty - (qy - ay) * tx};
}

}  // namespace mo2d::detail
