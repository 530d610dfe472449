#pragma once
// Inverse dynamics with contacts (issue 35, item 3; docs/contact.md, "Inverse dynamics"): the cam
// designer's question, at what speed the follower lifts off and what spring preload prevents it.
//
// A rigid contact closed at the start (|g| <= 1e-10 of the mechanism's size at the model's
// initial configuration) is held closed during the prescribed motion: a bilateral position
// constraint -g(q) = 0 (src/contact/contact_inverse.cpp), so M a1 = f + B u + N J^T + (the other
// constraints' forces), and its multiplier is the normal force N (N, > 0 pushing the bodies
// apart), the reaction column "NAME.normal_force". Where N < 0 the motion needs the contact to
// pull: a free contact would open there (a cam follower lifts off). The report names the first
// time N goes negative (a root between samples, located to rounding), the least N and its time
// (located between samples), and the extra force pressing the contact closed that would prevent
// it, -min N (a spring's preload).
//
// Every other contact stays out of the run: an open contact (g > tol at the start) must stay
// open; a compliant one must not penetrate (its force, a function of the state and of its
// approach speed at the onset, would be a load of the run: not supported yet). Where the
// prescribed motion closes either, the run is refused, naming the contact and the time.
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/system.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// One contact of an inverse run: held closed or left out, and what the run found.
struct InverseContact {
  std::string name;      // the contact's name
  bool held = false;     // a rigid contact closed at the start, held closed (see above)
  double gap = 0;        // its gap at the model's initial configuration (m)
  std::string column;    // held: its normal force's reaction column, "NAME.normal_force" (N)
  bool pulls = false;    // held: the force is negative somewhere (the contact would open)
  double min_force = 0;  // held: the least normal force (N; located between samples)
  double t_min = 0;      // held: its time (s)
  // held: the first time the force is negative (s; NaN when it never is)
  double t_negative = std::numeric_limits<double>::quiet_NaN();
  double preload = 0;    // held: -min_force when it is negative (N), else 0
  double min_gap = 0;    // not held: the least gap over the samples (m)
  double t_min_gap = 0;  // not held: its time (s)
};

// The model of an inverse run with contacts: `system` (the one m was built from, with options)
// with a position constraint per held contact, named like the contact, its multiplier's reaction
// relabelled "NAME.normal_force" and signed as the normal force.
struct ContactInverseModel {
  Model model;                           // the model with the held contacts
  std::vector<InverseContact> contacts;  // every contact, in the order given
};
// Throws Error naming the contact for a contact the model refuses (an unknown point, ...), or one
// that starts penetrated beyond the tolerance.
ContactInverseModel hold_closed_contacts(const System& system, const BuildOptions& options,
                                         const Model& m, const std::vector<ContactDef>& contacts);

// After the inverse run r of m (a ContactInverseModel's model for `contacts`; the same motion and
// options): each contact's report in `report` (hold_closed_contacts' list), and a warning in
// r.stats.warnings for each held contact whose force goes negative. Throws Error naming the contact
// and the first sample time where a contact left out is closed by the prescribed motion (g < -1e-10
// of the size: the motion penetrates it).
void report_contact_forces(const Model& m, std::span<const ContactDef> contacts,
                           std::vector<InverseContact>& report, std::span<const Prescribed> motion,
                           const InverseOptions& options, Trajectory& r);

}  // namespace mo2d
