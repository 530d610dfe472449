#pragma once
// Constraint rows of every kind, at position, velocity and acceleration level (internal header):
// the one dispatch over ConstraintKind. Constraint (mo2d/model.hpp) holds the rows and, in `def`,
// one struct per kind; the maths of each kind opens its own file:
//   rigid.hpp           rigid body (Example 2.6)
//   revolute.hpp        revolute joint kept as rows (5.27)
//   prismatic_slot.hpp  prismatic joint, pin-in-slot (5.31) and the rotation lock (5.30)
//   coordinate.hpp      extra coordinates (AddCoordinate)
//   user.hpp            user position psi(x, t) and velocity g(x, v, t) constraints (2.4, Def. 2.1)
//   gear.hpp            gear pair and rack and pinion on carrier-relative rates
// common.hpp holds the shared helpers and the entry adapters, sinks.hpp the sinks.
#include "constraints/common.hpp"
#include "constraints/coordinate.hpp"
#include "constraints/gear.hpp"
#include "constraints/prismatic_slot.hpp"
#include "constraints/revolute.hpp"
#include "constraints/rigid.hpp"
#include "constraints/sinks.hpp"
#include "constraints/user.hpp"
#include "mo2d/error.hpp"

namespace mo2d::detail {

// Each level switches on the kind, then takes the kind's struct out of c.def (std::get on the kind
// just tested: no allocation, one index check) and the first row of the level.

// Position rows: residual into res[row], Jacobian entries jac.add(row, q0 index, value).
template <class Sink>
void position_rows(const Model& m, const Constraint& c, const Eigen::Ref<const VectorXd>& q0,
                   double t, Eigen::Ref<VectorXd> res, Sink& jac) {
  PositionEntries<Sink> rows{jac};
  const int r = c.row0;
  switch (c.kind()) {
    case ConstraintKind::rigid:
      rigid_position(m, std::get<Constraint::Rigid>(c.def), r, q0, res, rows);
      break;
    case ConstraintKind::revolute:
      revolute_position(std::get<Constraint::Revolute>(c.def), r, q0, res, rows);
      break;
    case ConstraintKind::prismatic:
      prismatic_position(m, std::get<Constraint::Prismatic>(c.def), r, q0, res, rows);
      break;
    case ConstraintKind::slot:
      slot_position(std::get<Constraint::Slider>(c.def), r, q0, res, rows);
      break;
    case ConstraintKind::coordinate:
      coordinate_position(m, std::get<Constraint::Coordinate>(c.def), r, q0, res, rows);
      break;
    case ConstraintKind::user_position:
      user_psi_position(std::get<Constraint::UserPosition>(c.def), r, q0, t, res, rows);
      break;
    case ConstraintKind::user_velocity:
      break;
    case ConstraintKind::gear:
      gear_position(m, std::get<Constraint::Gear>(c.def), r, q0, res, rows);
      break;
  }
}

// Velocity rows A(q0, t) q1 = b: entries A.add(row, VarRef, value) (VarRef.var may be -1: a fixed
// variable, still reported with its body slot for the reaction bookkeeping), b into rhs[row].
template <class Sink>
void velocity_rows(const Model& m, const Constraint& c, const Eigen::Ref<const VectorXd>& q0,
                   double t, Eigen::Ref<VectorXd> rhs, Sink& A) {
  VelocityEntries<Sink> rows{A};
  const int r = c.row1;
  switch (c.kind()) {
    case ConstraintKind::rigid:
      rigid_velocity(m, std::get<Constraint::Rigid>(c.def), r, q0, rhs, rows);
      break;
    case ConstraintKind::revolute:
      revolute_velocity(std::get<Constraint::Revolute>(c.def), r, rhs, rows);
      break;
    case ConstraintKind::prismatic:
      prismatic_velocity(m, std::get<Constraint::Prismatic>(c.def), r, q0, rhs, rows);
      break;
    case ConstraintKind::slot:
      slot_velocity(std::get<Constraint::Slider>(c.def), r, q0, rhs, rows);
      break;
    case ConstraintKind::coordinate:
      coordinate_velocity(std::get<Constraint::Coordinate>(c.def), r, rhs, rows);
      break;
    case ConstraintKind::user_position:
      user_psi_velocity(std::get<Constraint::UserPosition>(c.def), r, q0, t, rhs, rows);
      break;
    case ConstraintKind::user_velocity:
      user_g_velocity(std::get<Constraint::UserVelocity>(c.def), r, q0, t, rhs, rows);
      break;
    case ConstraintKind::gear:
      gear_velocity(std::get<Constraint::Gear>(c.def), r, rhs, rows);
      break;
  }
}

// Acceleration right-hand side: A a1 = rhs - (terms of d/dt A q1 with a1 = 0) (exact).
inline void acceleration_rows(const Model& m, const Constraint& c,
                              const Eigen::Ref<const VectorXd>& q0,
                              const Eigen::Ref<const VectorXd>& q1, double t,
                              Eigen::Ref<VectorXd> rhs) {
  const int r = c.row1;
  switch (c.kind()) {
    case ConstraintKind::rigid:
      rigid_acceleration(m, std::get<Constraint::Rigid>(c.def), r, q1, rhs);
      break;
    case ConstraintKind::revolute:
      revolute_acceleration(r, rhs);
      break;
    case ConstraintKind::prismatic:
      prismatic_acceleration(std::get<Constraint::Prismatic>(c.def), r, q1, rhs);
      break;
    case ConstraintKind::slot:
      slot_acceleration(std::get<Constraint::Slider>(c.def), r, q1, rhs);
      break;
    case ConstraintKind::coordinate:
      coordinate_acceleration(r, rhs);
      break;
    case ConstraintKind::user_position:
      user_psi_acceleration(std::get<Constraint::UserPosition>(c.def), r, q0, q1, t, rhs);
      break;
    case ConstraintKind::user_velocity:
      user_g_acceleration(std::get<Constraint::UserVelocity>(c.def), r, q0, q1, t, rhs);
      break;
    case ConstraintKind::gear:
      gear_acceleration(r, rhs);
      break;
  }
}

}  // namespace mo2d::detail
