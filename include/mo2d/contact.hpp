#pragma once
// Contact and impact (issue 35; docs/contact.md): unilateral contacts between a point or a circle
// on a body and a line, a circle or a cam profile on another body or the ground, and forward
// dynamics with them.
//
// Each contact has a signed gap g(q0) (> 0 open, < 0 penetrating; src/contact/<kind>.hpp give it
// with its gradient), its rate g' = J q1 and, along the motion, g'' = J a1 + (J' q1). Two laws:
//  - compliant (Lankarani and Nikravesh 1990): while g < 0, with the penetration d = -g,
//      F = K d^n (1 + 3 (1 - e^2) / 4 * d' / v0),   v0 = the approach speed -g' at the onset,
//    a force F >= 0 along the gap's gradient (generalized force F J^T);
//  - rigid (g >= 0, lambda >= 0, lambda g = 0) with Newton's restitution: when contacts close, the
//    velocities jump, v+ = v- + G J^T P (G the constrained compliance: [M A^T; A 0]^-1's top
//    block), with impulses P >= 0 and g'+ + e g'- >= 0 complementary to them (a linear
//    complementarity problem, solved exactly by enumerating the active sets); a contact whose
//    approach speed vanishes, or whose impacts accumulate (Zeno), stays closed as an active
//    constraint g'' = 0 whose multiplier lambda is watched: it opens where lambda reaches 0.
// Every change (an onset, an exit, an impact, a lift-off, a Zeno accumulation) is an event located
// by the integrator's root finding (ForwardOptions::stop_when), so no step passes over it.
#include <memory>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/model.hpp"
#include "mo2d/table.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// The contact law (see the file's description).
struct ContactLaw {
  // compliant (Lankarani-Nikravesh: a force while g < 0) or rigid (g >= 0 kept, Newton impacts)
  enum class Kind { compliant, rigid };
  Kind kind = Kind::compliant;  // the law's kind
  // compliant: stiffness K (N/m^n) and exponent n (3/2: Hertz's, for spheres and cylinders in
  // point contact)
  double stiffness = 0, exponent = 1.5;
  // coefficient of restitution e in [0, 1]: Newton's for rigid, the target of the damping for
  // compliant
  double restitution = 1;
  // compliant: the approach speed v0 below which the damping uses this floor instead (m/s): a
  // contact that closes at (nearly) zero speed would get an unbounded damping coefficient
  double min_approach_speed = 1e-6;
  // Coulomb's friction coefficient mu >= 0 (0: frictionless), both laws: a sliding contact carries
  // the tangential force -mu N sign(v_t) (N its normal force), a sticking one (v_t = 0) any force
  // with |F_t| <= mu N; at an impact |P_t| <= mu P_n (docs/contact.md, "Friction")
  double friction = 0;
};

// A contact: a point or a circle (radius > 0) around a point of a body, against a line or a
// circle of another body or of the ground. Points are named like the rest of mo2d: a body node
// ("ball.C"), a ground node ("ground.O") or a named point (System::add_point).
struct ContactDef {
  // the contact's name (in the events and warnings)
  std::string name{};
  // the moving point and the radius of the circle around it (m; 0: a point)
  std::string point{};
  double radius = 0;
  // What it touches: a line through a and b (the free side is the left of a -> b: the normal
  // z x (b - a) / |b - a| points out of the obstacle), a circle around a of radius
  // `target_radius` touched from outside, or a hole: the circle is inside it (a pin in a hole
  // with the clearance target_radius - radius > 0), or a slot: the circle moves in a straight slot
  // of `width` > 2 radius whose centre line runs from a (its closed end, a flat wall) to b (its
  // open mouth), a and b on one body or the ground (src/contact/slot.hpp; its two walls and its end
  // are three contacts named NAME.left, NAME.right, NAME.end; outside the slot the walls' ends,
  // the lips, are point contacts and the pin enters through the mouth), or a closed cam profile
  // (src/contact/profile.hpp): the curve r(phi) (u(phi) = cos phi e1 + sin phi e2) around a, with
  // e1 = (b - a) / |b - a| (phi = 0 along a -> b) and e2 = z x e1, a and b on one body (or the
  // ground), r the table `profile` (m against rad: a periodic cubic spline of period 2 pi,
  // r > 0; a circle of radius > 0 must not be larger than the smallest radius of curvature of a
  // concave part), touched from outside; frictionless.
  enum class Target { line, circle, hole, slot, profile } target = Target::line;
  std::string a{}, b{};
  double target_radius = 0;
  double width = 0;                              // slot: its width (m)
  std::shared_ptr<const LookupTable> profile{};  // the profile's r(phi) (Target::profile)
  // its law: rigid or compliant, restitution, friction (ContactLaw)
  ContactLaw law{};
};

// The gap of a contact at a state: g (m), g' = J q1 (m/s), J' q1 (m/s^2: g'' = J a1 + J' q1),
// and J (n1, the gradient of g in the node coordinates; 0 for rotation rates).
struct GapValue {
  double g = 0;          // the gap (m; < 0: penetration)
  double rate = 0;       // g' = J q1 (m/s)
  double curvature = 0;  // J' q1 (m/s^2)
  Eigen::VectorXd J{};   // d g / d q0 (n0; 0 for the rotation rates)
};
// The gap of contact c of model m at (q0, q1). Throws Error naming the contact for an unknown
// point, a line of zero length, or a circle contact at coincident centres.
GapValue contact_gap(const Model& m, const ContactDef& c, const Eigen::VectorXd& q0,
                     const Eigen::VectorXd& q1);

// The tangent of a contact at a state (friction): the sliding rate v_t = J_t q1 (m/s), the
// relative velocity along the tangent t of the two bodies' material points at the contact point
// (t: a line's direction a -> b, n = z x t; for a circle t = (n_y, -n_x): src/contact/tangent.hpp),
// the bias dv_t/dt - J_t a1 (m/s^2) and J_t (n1, the rotation rates' entries included).
struct TangentValue {
  double rate = 0;       // v_t (m/s)
  double curvature = 0;  // dv_t/dt - J_t a1 (m/s^2)
  Eigen::VectorXd J{};   // d v_t / d q1 (n1)
};
// The tangent of contact c of model m at (q0, q1); the errors of contact_gap, and for a line whose
// points are on two different bodies (its tangent belongs to no body).
TangentValue contact_tangent(const Model& m, const ContactDef& c, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& q1);

// One event of a contact run.
struct ContactEvent {
  // a compliant contact closes (onset) or opens (exit); a rigid one is hit (impact), lifts off
  // (lift_off: its multiplier reached 0) or ends its accumulating impacts (zeno); a closed contact
  // with friction starts sticking (stick: its sliding rate reached 0 and the force that holds it
  // fits in the friction cone) or sliding (slip: its sticking force reached the cone's edge, or
  // it slides back at once after stopping); a pin enters a slot through its mouth (enter) or
  // leaves it (leave; `contact` names the slot)
  enum class Kind { onset, exit, impact, lift_off, zeno, stick, slip, enter, leave };
  Kind kind = Kind::onset;  // what happened
  double t = 0;             // s
  std::string contact;      // its name
  double speed = 0;         // approach speed -g' before (m/s): onset, impact, zeno
  double impulse = 0;       // impact: the impulse P (N s)
  double energy_lost = 0;   // impact: the energy its contact impulses dissipate, all contacts (J)
  double predicted_t = 0;   // zeno: the accumulation time t_inf the impacts converge to (s)
  // impact (and a lift-off in an impact): the separation speed g' after (m/s)
  double speed_after = 0;
};

// The kind's name: "onset", "exit", "impact", "lift_off", "zeno", "stick", "slip", "enter",
// "leave".
const char* contact_event_name(ContactEvent::Kind kind);

// The settings of a contact run: the forward options (integrator, tolerances, output times, ...;
// stop_when and extra_forces are the contact stage's own and must be empty), and the contact
// stage's limits.
struct ContactOptions {
  ForwardOptions forward{};  // the forward runs between events
  // events in a run before it is refused (a chattering contact)
  int max_events = 20000;
  // Zeno: a rigid contact whose last three impact intervals shrink by a steady ratio r < 1
  // (within 10 %) and whose remaining accumulation time dt r / (1 - r) is below zeno_time (s;
  // <= 0: 1e-5 of the run's duration t1 - t0), or whose approach speed is below zeno_speed (m/s),
  // is closed for good (a persistent contact) after a last, perfectly inelastic impact; the
  // remaining accumulation (at most zeno_time, bounces of height ~ g zeno_time^2 / 8) is skipped
  double zeno_time = 0, zeno_speed = 1e-6;
  // the persistent contacts' constraint g'' = -2 w g' - w^2 g holds g at 0 against the drift
  // (w = baumgarte_rate, 1/s; 0: g'' = 0)
  double baumgarte_rate = 0;
  // The accuracy asked for (a scene's run.accuracy, which chose forward's method and tolerances;
  // forward.accuracy itself must be 0): the run's error is estimated when it is > 0 and
  // forward.error_estimate is automatic, or whenever forward.error_estimate is on, by a second run
  // at tighter settings (the estimator of ForwardOptions::error_estimate) whose events are
  // compared with the run's; a warning where the estimate exceeds it, or where the events differ.
  double accuracy = 0;
};

// A contact run: the trajectory (kind forward; the impacts' energy loss in energy.dissipated) and
// its events in order.
struct ContactRun {
  Trajectory trajectory;             // the whole run, its legs joined
  std::vector<ContactEvent> events;  // in time order
};

// Forward dynamics of m from `initial` with the contacts (see the file's description). Throws
// Error naming the contact and the time for a contact that starts closed beyond its tolerance, a
// non-finite gap, an impact problem without a solution, chattering (more than max_events). The
// error estimate (ContactOptions::accuracy): in trajectory.stats (error_estimate, estimated_error).
ContactRun contact_dynamics(const Model& m, const std::vector<ContactDef>& contacts,
                            const State& initial, const ContactOptions& options = {});

}  // namespace mo2d
