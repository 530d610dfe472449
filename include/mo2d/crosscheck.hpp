#pragma once
// Cross-check of mo2d against Box2D 2.4.1 (library mo2d_box2d, target mo2d::box2d).
//
// Box2D shares nothing with mo2d: absolute body coordinates instead of nodes, sequential impulses
// instead of an orthogonal complement, a first-order semi-implicit Euler step and 32-bit floats.
// Agreement is therefore real evidence, within the accuracy of Box2D's scheme (docs/crosscheck.md
// gives the convergence study the default tolerances come from).
//
// Translation (one b2Body per mo2d body, origin at its centre of mass, mass and centroidal inertia
// set by b2Body::SetMassData; joints from a Model built with Reduction::none, where every joint is
// an explicit constraint naming its two bodies):
//   revolute -> b2RevoluteJoint; prismatic -> b2PrismaticJoint (b2WheelJoint when the rotation is
//   not locked); pin-in-slot -> b2WheelJoint with zero stiffness; actuated joints -> motors;
//   gear pairs and racks -> b2GearJoint; linear springs (k > 0) -> b2DistanceJoint with their
//   stiffness and damping; gravity -> b2World gravity; every other load (spring laws, dampers,
//   torsional springs, forces and torques of time or of the state, efforts, controllers, joint
//   friction not carried by a motor) -> forces and torques each step, computed by mo2d's load
//   functions on Box2D's own state (docs/crosscheck.md, "Shared code"); joint friction in a free
//   joint -> its motor at speed 0 with the friction as its limit.
//   Extra coordinates only observe the motion and are accepted. A constant-speed drive (a user
//   position constraint angle - omega t on a body pivoted on the ground) -> the pivot's motor.
//   Contacts (crosscheck_contacts) -> b2CircleShape and one-sided b2EdgeShape fixtures with the
//   contact's restitution and friction 0 (docs/contact.md, "Box2D"). Other user constraints,
//   chains, a massless body, a driven slide of a pin-in-slot, a pin in a hole and a compliant
//   contact are refused with an Error naming the element; a rotating body without centroidal
//   inertia gets zero_inertia_fraction in both engines (0: refused).
#include <Eigen/Core>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/system.hpp"

namespace mo2d {

// Settings of the Box2D cross-check (docs/crosscheck.md): Box2D's step and solver sweeps, how its
// motors follow the prescribed motion, and the tolerances of the verdict.
struct CrosscheckOptions {
  double step = 1.0 / 2000;      // Box2D time step h (s)
  int velocity_iterations = 50;  // sequential-impulse sweeps per step
  int position_iterations = 20;  // nonlinear Gauss-Seidel position sweeps per step
  // Motor speed target of step n: (s(t_n + h) - s(t_n)) / h from the exact motion, plus
  // (s_exact(t_n) - s_box2d(t_n)) / feedback_time when feedback_time > 0 (0: no feedback).
  // 0.5 s: long against the step (the float32 noise it feeds back, M dx / (tau h), stays small)
  // and short against a run, so Box2D's position drift cannot build up over a long run (3RRR over
  // its 16 s: 1.2e-3 rad without feedback and an effort error of 4.5 % of peak; 1e-4 rad and
  // 0.8 % with it; docs/crosscheck.md).
  double feedback_time = 0.5;  // s
  // Box2D's motor impulse of step n [t_n, t_n + h] is compared with mo2d at t_n + offset h.
  double sample_offset = 0.0;
  // Box2D starts settle_steps steps before t0 on the prescribed motion (extended before t0), so
  // that its warm-started impulses have converged at t0 and every step from t0 is compared
  // (from a cold start, 50 sweeps per step leave the first steps of a chain with a 50:1 mass ratio
  // 6 % off). If the motion cannot be solved before t0, Box2D starts at t0 and the first
  // skip_steps steps are left out instead (recorded in the report's notes).
  int settle_steps = 200;
  int skip_steps = 10;
  // Fewer compared steps than this is an error, not a verdict.
  int min_compared_steps = 100;
  // A driven joint that moves more than this per step (rad, or slider travel / Model::scale) is
  // outside what the tolerances were measured for (at most 0.0063 rad per step, the slider-crank
  // at 1/2000 s): an error asking for a smaller step (0: no check).
  double max_motion_per_step = 0.01;
  // Forward cross-check: a body turning more than max_motion_per_step (rad) in one Box2D step
  // along mo2d's trajectory is an error asking for a smaller step; with refine_step the step is
  // halved until it holds instead (noted in the result; the CLI sets it when --step is not given).
  bool refine_step = false;
  double max_motor_torque = 1e6, max_motor_force = 1e6;  // motor limits (N m, N)
  // Contacts (crosscheck_contacts): Box2D applies a contact's restitution only where the normal
  // approach speed exceeds this threshold (b2FixtureDef::restitutionThreshold, m/s; Box2D's
  // default 1 m/s would make the bouncing ball's impacts from the 8th on perfectly inelastic).
  // 0: at every approach speed, as mo2d's Newton law.
  double restitution_threshold = 0;
  // Contacts: an impact of mo2d's run is compared while the interval since the contact's previous
  // event (impact, lift-off; t0 for the first) spans at least this many Box2D steps: Box2D resolves
  // a bounce only to about a step, so the accumulating bounces of a Zeno sequence are not
  // compared (nor anything after the first impact that is not).
  int min_impact_steps = 50;
  // A rotating body whose centroidal inertia is 0 (a point mass on a massless link) cannot turn
  // in Box2D; if > 0 such bodies get I = fraction * m * (farthest node distance)^2 in BOTH the
  // Box2D world and the mo2d reference (recorded in the report's notes); 0: refuse them. The
  // comparison does not depend on the fraction (both engines carry the same inertia: the pendulum
  // agrees alike at 1/12 and 1/48, docs/crosscheck.md), so it is on by default.
  double zero_inertia_fraction = 1.0 / 12;
  // Agreement: each channel's error relative to its peak. Chosen for the default step and
  // iterations from the convergence study (docs/crosscheck.md): the examples' errors are ~c h with
  // c <= 12/s (RMS) and <= 30/s (max), i.e. <= 0.6 % and 1.5 % at h = 1/2000 s; 2x margin.
  double effort_rms_tolerance = 0.01, effort_max_tolerance = 0.03;
  double reaction_rms_tolerance = 0.01, reaction_max_tolerance = 0.03;
  // Budgets of the whole cross-check (mo2d/budget.hpp; the scene's run.max_steps, max_seconds,
  // max_memory): Box2D steps (settling steps included; more is refused before the run, naming
  // the step), wall-clock seconds of both engines (an Error naming the time reached when they
  // run out), and the bytes of the results (the report's series and the CSV text, about 33 bytes
  // per value, estimated before the run). The InverseOptions' budgets are not used.
  long max_steps = kDefaultMaxSteps;
  double max_seconds = kDefaultMaxSeconds;
  double max_memory = kDefaultMaxMemory;
};

// Error of one compared quantity (an effort, or a joint's reaction force vector), relative to the
// peak magnitude of mo2d's value over the compared steps.
struct ChannelError {
  // effort label (an input of the mechanism) or reaction label (joint.Fx, joint.Fy)
  std::string label{};
  double peak = 0;          // max |mo2d value| (N m, N)
  double rms = 0, max = 0;  // relative: rms |box2d - mo2d| / peak, max |...| / peak
  double max_time = 0;      // time of the largest error (s)
};

// The result of crosscheck_inverse(): the settings used, the error of every effort and joint
// reaction of Box2D against mo2d's inverse dynamics, the verdict and the time series.
struct CrosscheckReport {
  // the mechanism's name (Model::name)
  std::string mechanism{};
  // Box2D time step h (s)
  double step = 0;
  // Box2D's solver sweeps per step (CrosscheckOptions)
  int velocity_iterations = 0, position_iterations = 0;
  // the options' sample_offset (fraction of a step) and feedback_time (s)
  double sample_offset = 0, feedback_time = 0;
  int steps = 0;           // Box2D steps from t0
  int settle_steps = 0;    // Box2D steps before t0 (not compared)
  int compared_steps = 0;  // steps in the statistics
  // one ChannelError per input (efforts) and per joint (reactions, the force vector)
  std::vector<ChannelError> efforts{}, reactions{};
  double effort_rms = 0, effort_max = 0;      // worst channel
  double reaction_rms = 0, reaction_max = 0;  // worst joint
  double tracking_error = 0;  // max |Box2D joint coordinate - exact| over driven joints (rad, m)
  std::vector<std::string> notes{};     // substitutions made (zero_inertia_fraction)
  bool agree = false;                   // all errors within the options' tolerances
  std::vector<std::string> failures{};  // which tolerance was exceeded, by which channel
  // CPU time of the Box2D run (s)
  double cpu_seconds = 0;
  // Time series (one row per compared step): t (the compared instant), mo2d and Box2D values.
  Eigen::VectorXd time{};
  std::vector<std::string> effort_labels{}, reaction_labels{};  // reaction labels: joint.Fx/.Fy
  // values per compared step (rows) and channel (columns): N m or N
  Eigen::MatrixXd mo2d_efforts{}, box2d_efforts{}, mo2d_reactions{}, box2d_reactions{};
};

// Inverse cross-check: Box2D's motors follow the exact motion of `simulated` for `motion`
// over [options.t0, options.t1] (options.samples is not used: every Box2D step is compared),
// and Box2D's motor efforts and joint reactions are compared with mo2d's inverse dynamics of
// `reference`. Normally both are the same mechanism; a test can plant an error in `reference`.
// `simulated` must be built with Reduction::none; `reference` may use any reduction.
CrosscheckReport crosscheck_inverse(const Model& reference, const Model& simulated,
                                    std::span<const Prescribed> motion,
                                    const InverseOptions& options,
                                    const CrosscheckOptions& check = {});
// The same for one mechanism, the CLI's entry point: reference = build_model(system),
// simulated = build_model(system, {.reduction = Reduction::none}).
CrosscheckReport crosscheck_inverse(const System& system, std::span<const Prescribed> motion,
                                    const InverseOptions& options,
                                    const CrosscheckOptions& check = {});

// Forward cross-check: from the same consistent state (with no input efforts: the driven joints
// are free), mo2d (CVODE BDF, rtol 1e-10) and Box2D integrate the motion up to t1; centres of mass
// and body angles are compared at `samples` instants that fall on Box2D steps. `model` must be
// built with Reduction::none; check.zero_inertia_fraction applies as in crosscheck_inverse.
struct ForwardCrosscheck {
  // the mechanism's name (Model::name)
  std::string mechanism{};
  // Box2D time step h (s)
  double step = 0;
  // Box2D steps from t0 to t1
  int steps = 0;
  double max_position_error = 0;  // max over bodies and instants of |centre of mass error| (m)
  double max_angle_error = 0;     // rad
  // errors at t1: centre of mass (m) and angle (rad), worst body
  double final_position_error = 0, final_angle_error = 0;
  double relative_position_error = 0;                       // max_position_error / Model::scale
  Eigen::VectorXd time{}, position_error{}, angle_error{};  // per instant, worst body
  // Not empty when Box2D left the assembly branch that mo2d keeps (a revolute joint's
  // sin(theta2 - theta1) changed sign in Box2D only): the joint, the time and both values. A
  // disagreement then is Box2D's (its first-order step crossed a singular position).
  std::string branch_switch{};
  std::vector<std::string> notes{};  // substitutions made (zero_inertia_fraction)
  // Evidence of Box2D's own drift: per instant, Box2D's mechanical energy (kinetic_energy and
  // potential_energy, mo2d's functions, of Box2D's state) minus mo2d's (J); and mo2d's own
  // energy-balance error over the run (energy_balance_error, J) and its largest kinetic energy.
  Eigen::VectorXd energy_difference{};
  double mo2d_energy_error = 0, kinetic_peak = 0;
};
// The forward cross-check's tolerances by default (mo2d crosscheck --forward, Python's
// crosscheck): the largest centre-of-mass error relative to the mechanism's size, and the largest
// body angle error (rad).
inline constexpr double kForwardPositionTolerance = 1e-2, kForwardAngleTolerance = 2e-2;
// Whether the two engines agree: both largest errors within their tolerances.
inline bool forward_agrees(const ForwardCrosscheck& r,
                           double position_tolerance = kForwardPositionTolerance,
                           double angle_tolerance = kForwardAngleTolerance) {
  return r.relative_position_error <= position_tolerance && r.max_angle_error <= angle_tolerance;
}
// Why a forward cross-check disagrees, when Box2D is the cause: its branch switch
// (ForwardCrosscheck::branch_switch), or, at the first instant an error exceeds its tolerance
// (position relative to the size, angle in rad), a mechanical energy that differs from mo2d's by
// more than 10x mo2d's own energy-balance error and 1e-4 of the kinetic energy peak (Box2D's
// first-order float32 step drifts; a motion that is sensitive to its energy, like one passing
// near an unstable position, amplifies the drift). "" when neither holds.
std::string box2d_cause(const ForwardCrosscheck& r, double position_tolerance,
                        double angle_tolerance);
// Forward cross-check of `model` from `initial` up to t1 (s), compared at `samples` instants (see
// ForwardCrosscheck).
// `efforts`: one law per Model::inputs entry (ForwardOptions::efforts: of time, or of the state,
// e.g. PD controllers), applied in both engines (in Box2D evaluated on its own state).
ForwardCrosscheck crosscheck_forward(const Model& model, const State& initial, double t1,
                                     const CrosscheckOptions& check = {}, int samples = 101,
                                     const EffortLaws& efforts = {});
// The same with mo2d integrating `reference` and Box2D `model` (same variables): a test plants
// an error in `reference` (a spring constant, a damper's node, a friction sign, a load's point)
// to see that the comparison catches it.
ForwardCrosscheck crosscheck_forward(const Model& reference, const Model& model,
                                     const State& initial, double t1,
                                     const CrosscheckOptions& check, int samples,
                                     const EffortLaws& efforts = {});

// One impact of a contact in both engines (crosscheck_contacts).
struct ImpactComparison {
  std::string contact{};                   // the contact's name
  int index = 0;                           // its k-th impact (k = 0: the first)
  bool found = false;                      // Box2D had a k-th closing of this contact
  double t_mo2d = 0, t_box2d = 0;          // time (s)
  double speed_mo2d = 0, speed_box2d = 0;  // approach speed -g' before (m/s)
  double after_mo2d = 0, after_box2d = 0;  // separation speed g' after (m/s)
  // the time since the previous compared impact of the contact (the first: since mo2d's previous
  // event of the contact, or t0), in each engine (s)
  double interval_mo2d = 0, interval_box2d = 0;
};
// Contact cross-check (docs/contact.md, "Box2D"): the motion at the samples, and the impacts.
struct ContactCrosscheck {
  // centres of mass and angles at the samples (energy_difference: Box2D's mechanical energy minus
  // mo2d's, informative; mo2d_energy_error is not set)
  ForwardCrosscheck motion{};
  std::vector<ImpactComparison> impacts{};  // the compared impacts, contact by contact
  std::vector<ContactEvent> events{};       // mo2d's events
  int mo2d_impacts = 0, box2d_impacts = 0;  // over the whole run (Box2D: its closings)
  bool missing = false;                     // a compared mo2d impact that Box2D does not have
  // largest |t_box2d - t_mo2d| (s: Box2D's first-order errors accumulate over a sequence of
  // bounces), largest |interval_box2d - interval_mo2d| in Box2D steps (each flight's own error),
  // and the speed errors relative to speed_scale, the largest compared approach speed of mo2d's
  double max_time_error = 0, max_interval_error = 0;
  double max_speed_error = 0, max_rebound_error = 0, speed_scale = 0;
  double deepest_penetration = 0;  // Box2D's most negative gap (mo2d's gap function), m
};
// The contact cross-check's verdict: position relative to the mechanism's size, the intervals
// between impacts in Box2D steps (max_interval_error), approach and separation speeds relative to
// ContactCrosscheck::speed_scale. From the convergence study at 1/2000 s (docs/contact.md,
// "Box2D"): the bouncing ball 6.1e-3, 8 steps, 4.2e-3; the cam follower 2.6e-3, 1.5 steps, 3.9e-2.
struct ContactTolerances {
  double position = 1e-2;      // largest position difference, relative to the mechanism's size
  double interval_steps = 16;  // largest difference of an interval between impacts, Box2D steps
  double speed = 0.1;          // largest speed difference, relative to the largest approach speed
};
// Whether the two engines agree: every compared impact found, within the tolerances.
bool contact_agrees(const ContactCrosscheck& r, const ContactTolerances& tolerances = {});
// Contact cross-check: mo2d runs contact_dynamics(reference, reference_contacts, initial, run)
// (run.forward's t0, t1 and samples set to the compared instants), Box2D integrates `model` with
// `contacts` as shapes (restitution, friction 0, CrosscheckOptions::restitution_threshold) from
// the same state up to t1. Refused (an Error naming the contact): holes, compliant laws, contacts
// between bodies a joint connects (docs/contact.md, "Box2D"). A reference that differs from
// `model` (a radius, a restitution) is a planted error the comparison must catch.
ContactCrosscheck crosscheck_contacts(const Model& reference,
                                      const std::vector<ContactDef>& reference_contacts,
                                      const Model& model, const std::vector<ContactDef>& contacts,
                                      const State& initial, double t1,
                                      const CrosscheckOptions& check, int samples,
                                      const ContactOptions& run);

// A fixed-width table of the report (one line per channel) and its CSV (atomic write):
// columns t, then for each effort and reaction label "mo2d.<label>" and "box2d.<label>".
void print_crosscheck_table(std::ostream& out, const CrosscheckReport& report);
std::string crosscheck_csv(const CrosscheckReport& report);
void write_crosscheck_csv(const CrosscheckReport& report, const std::string& path);

}  // namespace mo2d
