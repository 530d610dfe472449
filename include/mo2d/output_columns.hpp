#pragma once
// Columns a run may add on request (post-processing of its recorded samples t, q0, q1; the
// solvers are not involved): every load's value and power, named points (System::add_point) and
// centres of mass. add_output_columns() appends them to Trajectory::output_labels / outputs, which
// trajectory_csv() writes after the other columns; a run asked for nothing has none of them.
//
// Labels (element names as in the model, with their instance prefixes):
//   force F            F.fx, F.fy (world frame, N), F.power (F . v of its point, W)
//   torque T           T.torque (N m), T.power (torque x omega of its body)
//   spring S           S.length (m), S.rate (m/s), S.tension (N, > 0 pulls its ends together),
//                      S.power (-tension x rate: the power of its forces on the mechanism);
//                      a spring reduced to a constraint: S.length, S.rate (its tension is the
//                      reaction column S.tension)
//   torsional spring K K.torque (on body 2, N m), K.rate (w2 - w1), K.power (torque x rate);
//                      reduced to a constraint: K.angle (from rest, rad), K.rate (its torque is
//                      the reaction column K.torque)
//   named point P      P.x, P.y, P.vx, P.vy
//   body B             B.com.x, B.com.y, B.com.vx, B.com.vy (centre of mass)
//   column NAME        NAME: the value of a law of t and the state (OutputRequest::columns; a
//                      scene's `outputs: columns:`), e.g. a squared distance from a point
// The powers of the forces, torques and springs given by a law sum to load_power (what the energy
// balance integrates as work.loads); a linear spring's (or torsional spring's) power is minus the
// rate of its potential energy less what its damper dissipates.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mo2d/law.hpp"
#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// The optional columns of a run's CSV (Trajectory::outputs): load values and powers, centres of
// mass, named points.
struct OutputRequest {
  bool loads = false;  // every force, torque, spring and torsional spring
  bool com = false;    // every body's centre of mass
  // Named points (Model::points) by name; all_points: every named point of the model.
  std::vector<std::string> points{};
  bool all_points = false;
  // Columns of laws (label, law of t and the quantities of the state, mo2d/law.hpp), last.
  std::vector<std::pair<std::string, Law>> columns{};
  // Whether nothing is requested.
  bool empty() const { return !loads && !com && points.empty() && !all_points && columns.empty(); }
};

// The labels of the requested columns, in order (loads: forces, torques, springs, torsional
// springs; then points; then centres of mass; then the law columns). Throws Error naming a point
// the model does not have (with a suggestion).
std::vector<std::string> output_column_labels(const Model& m, const OutputRequest& request);
// Their values at one state (out: one per label). Throws Error (named, with the time) when a
// value is not finite, or naming a law column's unknown quantity.
void output_column_values(const Model& m, const OutputRequest& request,
                          const Eigen::Ref<const Eigen::VectorXd>& q0,
                          const Eigen::Ref<const Eigen::VectorXd>& q1, double t,
                          Eigen::Ref<Eigen::VectorXd> out);
// Appends the requested columns to r (computed at every sample from r.time, r.q0, r.q1). A
// column already in r.output_labels is an Error.
void add_output_columns(const Model& m, Trajectory& r, const OutputRequest& request);

}  // namespace mo2d
