#pragma once
// The JSON summary of a run (peaks of the efforts, reactions and outputs with their times, located
// between the samples (mo2d/extremes.hpp), max residuals, energy error,
// CPU time), written next to the CSV: also mo2d's version, the run settings used with the ones
// the command line overrode, and every CSV column with its unit (trajectory_csv_units).
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

// extremes: locate_extremes of the run (the efforts', reactions' and output columns' peaks);
// design: the JSON text of its design measures (design_json), "" for none
std::string inverse_summary(const SceneOptions& o, const Scene& s, const Model& m,
                            const Trajectory& r, const InverseOptions& run,
                            const std::vector<Extreme>& extremes, const std::string& design = "",
                            const std::vector<InverseContact>& contacts = {});
// events: a contact run's (scene_forward), written as "contacts": {"events": [...]} for a scene
// with contacts
std::string forward_summary(const SceneOptions& o, const Scene& s, const Model& m,
                            const Trajectory& r, const ForwardOptions& run,
                            const std::vector<Extreme>& extremes, const std::string& design = "",
                            const std::vector<ContactEvent>& events = {});

}  // namespace mo2d::cli
