#pragma once
// Unilateral springs reduced to constraints (ReducedSpring, SpringDef::reduce): the constraint is
// bilateral, so a rope (acts: tension) whose multiplier comes out negative is held where the
// spring would have gone slack (and a bump stop, acts: compression, pulled). No silent wrong
// answer: the run gets a warning naming the spring, the first output time, the number of samples
// and the worst tension (docs/reduction.md). Checked at the recorded samples only.
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::detail {

// Appends one warning per reduced unilateral spring whose tension r.reactions has the wrong sign
// (beyond 1e-9 of its largest magnitude over the run) at some sample.
void reduced_spring_slack(const Model& m, const Trajectory& r, std::vector<std::string>& warnings);

}  // namespace mo2d::detail
