#pragma once
// The designer's measures of a run on the command line (mo2d/design.hpp, docs/design.md): what
// `mo2d inverse|forward SCENE [--measures]` computes, the table it prints and its JSON section.
#include <string>

#include "mo2d/design.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::cli {

// Whether a run reports measures: a design: block or --measures.
inline bool wants_design(const Scene& scene, bool measures) {
  return measures || !scene.design.empty();
}

// The efforts' RMS, peak-to-peak and flywheel; the four-bars' Grashof class, limit positions and
// transmission angles; the largest shaking force and moment and bearing loads (sampled).
void print_design_table(const Trajectory& r, const DesignSummary& d);

// The same as a JSON object (text), for the run's summary file.
std::string design_json(const Trajectory& r, const DesignSummary& d);

}  // namespace mo2d::cli
