#pragma once
// The measures a designer reads off a mechanism and its runs (issue 36, docs/design.md): closed
// forms of four-bar loops (Grashof class, transmission angle, limit and dead positions), and the
// columns and summary values of a recorded run (inverse or forward, post-processing of its
// samples):
//
//   four-bar loop L    L.input_angle, L.output_angle (rad, from the ground line A0 -> B0),
//                      L.transmission_angle (rad in [0, pi], between coupler and output link),
//                      L.velocity_ratio (omega_out / omega_in; the mechanical advantage of a
//                      lossless loop, T_out / T_in, is its inverse), and per coupler point P
//                      L.other.P.x, L.other.P.y: P on the other assembly branch at the same
//                      input angle (the run's branch is P.x, P.y, mo2d/output_columns.hpp)
//   frame              frame.shaking.Fx, .Fy (N), .F (magnitude), .M (N m, about a point): the
//                      force and moment the moving links exert on the frame (ground) through
//                      its joints, ground-anchored springs and actuators at ground joints
//   joint J            J.load (N, |(J.Fx, J.Fy)|), J.load_angle (rad, direction of the force of
//                      body 1 on body 2): the bearing load
//
// By the balance of momentum of the moving links, shaking force = sum m_i g + external loads -
// sum m_i a_Gi (tests/design/frame_loads_test.cpp checks it, and the moment against the rate of
// the angular momentum).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// ---- four-bar closed forms (lengths only)

// The four link lengths of a four-bar loop (m): ground A0-B0, input A0-A, coupler A-B, output
// B0-B.
struct FourBarLengths {
  // the four link lengths (m)
  double ground = 0, input = 0, coupler = 0, output = 0;
};

// Grashof's classification (s + l against p + q: shortest, longest and the other two links).
enum class GrashofClass {
  crank_rocker,   // s + l < p + q, shortest link the input: the input turns fully, the output rocks
  double_crank,   // s + l < p + q, shortest the ground: both turn fully (drag link)
  rocker_crank,   // s + l < p + q, shortest the output: the output turns fully
  double_rocker,  // s + l < p + q, shortest the coupler: the coupler turns fully, neither side
  change_point,   // s + l = p + q (to 1e-12 of l): the loop can fold flat (change of branch)
  triple_rocker,  // s + l > p + q (non-Grashof): no link turns fully relative to another
};
// "crank-rocker", "double-crank", "rocker-crank", "double-rocker", "change-point",
// "triple-rocker"
const char* to_string(GrashofClass k);
// Throws Error when a length is not finite and > 0, or when one is longer than the sum of the
// others (the loop cannot close).
GrashofClass grashof_class(const FourBarLengths& l);

// Transmission angle mu (rad, in [0, pi]) at input angle theta (rad, from A0 -> B0,
// counter-clockwise), by the cosine law: z^2 = a^2 + d^2 - 2 a d cos theta (z = |A - B0|),
// cos mu = (b^2 + c^2 - z^2) / (2 b c); the same on both branches. NaN where the loop does not
// close at theta.
double transmission_angle(const FourBarLengths& l, double theta);

// Limit and dead positions of a four-bar loop, from its lengths (closed forms, docs/design.md).
// Angles in rad from the ground line A0 -> B0, counter-clockwise, on the branch with B on the
// clockwise side of B0 -> A (theta_B0A - angle at B0; for the mirror branch negate every angle).
struct FourBarPositions {
  // Whether the input turns fully. If not, it moves in [input_min, input_max] (its dead
  // positions, where coupler and output are in line: mu = 0 or pi; the output cannot drive it
  // past them), and in the mirror interval on the other branch.
  bool input_rotates = true;
  double input_min = 0, input_max = 0;
  // Limit (toggle) positions of the output: input and coupler in line, extended (|A0 B| = a + b)
  // and folded (|A0 B| = |b - a|); input angles there and the output angle (B0 -> B) there. NaN
  // where the input cannot reach it. At them the output's velocity is zero (its extremes when it
  // rocks), and an input driven from the output is at a dead point.
  double limit_extended = 0, limit_folded = 0, output_extended = 0, output_folded = 0;
  // Smallest and largest transmission angle over the input's range (rad).
  double min_transmission = 0, max_transmission = 0;
};
// Throws Error as grashof_class.
FourBarPositions four_bar_positions(const FourBarLengths& l);

// ---- measures of a run

// A four-bar loop of a model by its four joint nodes (node labels: "ground.A0", "coupler.A",
// "coupler.B", "ground.B0"; the two pins should be nodes of the coupler when coupler points are
// asked for).
struct FourBarDef {
  std::string name{};  // prefix of its columns
  // input pivot (a ground node), input pin (A), output pin (B), output pivot (a ground node)
  std::string input_pivot{}, input_pin{}, output_pin{}, output_pivot{};
  // named points (Model::points) on the coupler whose other-branch positions are written
  std::vector<std::string> coupler_points{};
};

// What add_design_columns computes (the `design:` block of a scene, docs/design.md).
struct DesignRequest {
  std::vector<FourBarDef> four_bars{};  // four-bar loops whose columns are written
  bool frame = false;                   // frame.shaking.* columns
  Vec2 moment_about{0, 0};              // the point of frame.shaking.M (m)
  bool bearings = false;                // J.load, J.load_angle of every joint with Fx, Fy reactions
  double speed_fluctuation = 0;         // > 0: the flywheel for this coefficient Cs (DesignSummary)
  // Whether nothing is requested.
  bool empty() const { return four_bars.empty() && !frame && !bearings && speed_fluctuation <= 0; }
};

// Lengths of a four-bar loop at the model's initial configuration. Throws Error naming a node the
// model does not have, or a pivot that is not a ground node.
FourBarLengths four_bar_lengths(const Model& m, const FourBarDef& f);

// Appends the requested columns to r.outputs (see the file's description). Throws Error naming
// the element when the request cannot be met (unknown nodes, a frame load the model's elements
// transmit in a way not computed: gears, chains, user constraints, joint friction at the frame)
// or a value is not finite (with the time).
void add_design_columns(const Model& m, Trajectory& r, const DesignRequest& request);

// Summary values of one input effort over a run.
struct EffortMeasures {
  std::string input;                           // "crank_pivot.torque"
  double mean = 0, rms = 0, peak_to_peak = 0;  // of the samples (trapezoid rule in time)
  // The input's rate: mean over the run (rad/s or m/s; B^T q1) and its travel (rad or m).
  double mean_speed = 0, travel = 0;
  // Largest swing of the energy the input delivers relative to its mean power:
  // E(t) = int (P - P_mean) dt with P = u (B^T q1), dE_max = max E - min E (J). Over whole cycles
  // at near-constant speed it is the energy fluctuation of int (u - u_mean) d theta.
  double energy_fluctuation = 0;
  // The flywheel inertia (kg m^2) that keeps the speed fluctuation (w_max - w_min) / w_mean of a
  // torque input within Cs: I = dE_max / (Cs w_mean^2). NaN unless Cs > 0 and w_mean != 0.
  double flywheel_inertia = 0;
};
// A four-bar loop of a run: its lengths at the initial configuration and their closed forms, and
// the extremes of its transmission angle in the run.
struct FourBarSummary {
  std::string name;        // FourBarDef::name
  FourBarLengths lengths;  // at the model's initial configuration
  // Grashof's class and the limit and dead positions of those lengths
  GrashofClass grashof = GrashofClass::crank_rocker;
  FourBarPositions positions;
  // over the run's samples (rad; NaN without the L.transmission_angle column)
  double run_min_transmission = 0, run_max_transmission = 0;
};
// Summary of a run's design measures: every input's effort measures and the four-bar loops.
struct DesignSummary {
  std::vector<EffortMeasures> efforts;    // one per input, in the order of Model::inputs
  std::vector<FourBarSummary> four_bars;  // in the order of DesignRequest::four_bars
  double speed_fluctuation = 0;           // the Cs used (0: none)
};
// The summary of run r (after add_design_columns for the four-bars' run extremes). Throws Error
// for fewer than two samples.
DesignSummary design_summary(const Model& m, const Trajectory& r, const DesignRequest& request);

}  // namespace mo2d
