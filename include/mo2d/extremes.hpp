#pragma once
// The extremes of a run's columns located between its samples (issue 30, item 5): a peak of the
// crank torque lies between two samples, and the largest sample misses it by ~ g'' h^2 / 8.
//
// For each column (efforts, reactions, then the output columns asked for) and each of its maximum
// and minimum: the samples that may hold the extreme (local extremes of the samples within the
// largest second difference of the best one: the most a smooth column can rise between samples),
// then the two sample intervals around each are evaluated again on a fine grid of kExtremeGrid
// points by the run's own solver, and the extreme is the root of the derivative of the polynomial
// through the kExtremeFit fine points around the best one (exact derivative of the interpolant,
// root by safeguarded Newton), its value that polynomial's there. Inverse runs evaluate the grid
// with inverse_dynamics_sample (the solution at each instant, to rounding); forward runs
// integrate the two intervals again from the recorded state (the run's integrator and options,
// the grid its dense output), so a forward extreme carries the run's integration error and no
// sampling error. An extreme at the first or last sample where the column leaves the run's span
// rising is that sample. Where the fine evaluation fails or the polynomial has no extreme in its
// middle interval, or where it and the polynomial through its inner points disagree there by more
// than 1e-9 of the column (a kink: friction's sign change, a chain going slack; a spike near a
// singular configuration), the largest fine sample is reported, located = false.
//
// Cost: one grid (kExtremeGrid samples, or a re-integration of two sample intervals) per distinct
// pair of intervals, shared by the columns whose extremes fall there.
#include <span>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/output_columns.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// points of the fine grid over two sample intervals; points of the local polynomial
inline constexpr int kExtremeGrid = 25, kExtremeFit = 9;

// The maximum and minimum of one column with their times (s), in the column's unit.
struct Extreme {
  std::string label;  // the column's label (an input, a reaction component, an output)
  // the largest and smallest value and their times (s)
  double max = 0, t_max = 0, min = 0, t_min = 0;
  // the extremes of the samples themselves, for comparison
  double sampled_max = 0, sampled_min = 0;
  // the maximum / minimum were located between the samples (false: the largest fine sample, the
  // column is not smooth there, or its fine evaluation failed)
  bool located_max = false, located_min = false;
};

// The extremes of every effort, reaction and output column of an inverse run r of m (r as
// inverse_dynamics returned it for these motions and options, with add_output_columns(m, r,
// outputs) applied if outputs asks for columns).
std::vector<Extreme> locate_extremes(const Model& m, std::span<const Prescribed> motion,
                                     const InverseOptions& options, const Trajectory& r,
                                     const OutputRequest& outputs = {});
// The same for a forward run r of m with these options.
std::vector<Extreme> locate_extremes(const Model& m, const ForwardOptions& options,
                                     const Trajectory& r, const OutputRequest& outputs = {});

// The extremes of r's columns at its samples only, none evaluated between them (located_max and
// located_min false unless the column has no curvature): for a run whose motion is not smooth
// between its samples, which a re-integration would not reproduce (a contact run's impacts).
std::vector<Extreme> sampled_extremes(const Model& m, const Trajectory& r,
                                      const OutputRequest& outputs = {});

}  // namespace mo2d
