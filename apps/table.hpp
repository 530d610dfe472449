#pragma once
// The short tables the subcommands print after a run.
#include <string>
#include <vector>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::cli {

// Sizes, max residuals and CPU time of an inverse run.
void print_inverse_table(const Model& model, const Trajectory& r, const InverseOptions& run);
// Sizes, integrator statistics, residuals and energy balance of a forward run.
void print_forward_table(const Model& model, const Trajectory& r, const ForwardOptions& run);

// The max and min of each input's effort with their times, located between the samples
// (locate_extremes, mo2d/extremes.hpp; "(sampled)" where not located).
void print_peaks_table(const Trajectory& r, const std::vector<Extreme>& extremes);

// The tracking error of each controller (input, coordinate, max |x - r| with its time, final).
void print_tracking_table(const std::vector<TrackingError>& tracking);

// A contact run's events (mo2d/contact.hpp): a count per kind, the energy the impacts lost, then
// one line per event (time, kind, contact, approach speed before, separation speed after,
// impulse, energy lost, Zeno's predicted time), the first kListedContactEvents of them.
inline constexpr size_t kListedContactEvents = 40;
void print_contact_events(const std::vector<ContactEvent>& events);
// An inverse run's contacts: held closed (the least normal force, where it goes negative, the
// preload that prevents it; each negative one also as a warning on stderr) or left out.
void print_inverse_contacts(const std::vector<InverseContact>& contacts);

// The shortest text that reads back to the same double (std::to_chars), as in mo2d's CSV files.
std::string shortest(double v);

// max |E(t) - E(t0) - W_inputs(t) + D(t)| with E = kinetic + potential (J).
double energy_error(const Trajectory& r);

}  // namespace mo2d::cli
