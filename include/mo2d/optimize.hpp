#pragma once
// Optimization of a scene's parameters (issue 36, docs/design.md "Optimization"): minimize an
// expression of a run's summary values over parameters within bounds, subject to inequality
// constraints, with NLopt's derivative-free methods (BOBYQA without constraints, COBYLA with
// them), from several deterministic starts. One evaluation = one run of the scene with the
// parameters replaced (load, build, inverse or forward dynamics as its run.solve says).
//
// Names an objective or constraint may use (the expression language of scene files,
// mo2d/expression.hpp):
//   a parameter of the scene      its value at the design ("a", "m_cw")
//   peak.COL                      max |COL| over the samples (as `mo2d sweep`'s peak.<effort>)
//   max.COL, min.COL              the largest and smallest sample of COL
//   mean.COL, rms.COL             time average and RMS of COL (trapezoid rule, as the design
//                                 summary's efforts)
//   peak_to_peak.COL              max.COL - min.COL
//   energy_fluctuation.INPUT,     an input's dE_max (J) and flywheel inertia (kg m^2) of the
//   flywheel.INPUT                design summary (mo2d/design.hpp; flywheel: needs the scene's
//                                 design: speed_fluctuation)
// COL is any column of the run's CSV (mo2d/csv.hpp), including the design columns
// (frame.shaking.F, J.load, ...: with OptimizeOptions::measures or a design: block).
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/error.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {

// A parameter the optimizer varies, within [lo, hi] (lo < hi, both finite).
struct DesignVariable {
  std::string name{};     // a parameter of the scene's parameters: block
  double lo = 0, hi = 0;  // its bounds
};

// One evaluation, as reported to OptimizeOptions::progress.
struct OptimizeProgress {
  int evaluation = 0;       // 1-based, over all starts
  int start = 0;            // 0-based start index
  std::vector<double> x{};  // the design (in the order of OptimizeOptions::vary)
  double value = 0;         // objective at x
  double violation = 0;     // max(0, max_i g_i(x)): how far x is from feasible
  bool feasible = true;     // violation <= OptimizeOptions::constraint_tol: every constraint holds
  bool improved = false;    // x is the best design so far
  double best = 0;          // the best objective so far (of feasible designs when any)
  double seconds = 0;       // wall time since the optimization started
};

// What to optimize and how (the flags of `mo2d optimize`, docs/scene-format.md).
struct OptimizeOptions {
  std::string scene{};                    // the scene file
  std::string minimize{};                 // objective: an expression (see above)
  std::vector<DesignVariable> vary{};     // at least one
  std::vector<std::string> subject_to{};  // "g" (g <= 0), "g <= h" or "g >= h"
  std::vector<ParameterOverride> set{};   // fixed overrides of other parameters
  std::vector<RunOverride> run{};         // run settings (as mo2d inverse / forward)
  bool measures = false;                  // add the frame and bearing columns
  int starts = 1;                         // start 0: the scene's values; others seeded random
  std::uint64_t seed = 1;                 // of the random starts (std::mt19937_64)
  int max_evals = 200;                    // per start
  double xtol = 1e-6;                     // stop when a step is below xtol x (hi - lo)
  double constraint_tol = 1e-9;           // a constraint holds when g <= tol x max(1, |h|)
  // Whole optimization's wall-time budget (s); 0: the scene's run.max_seconds (with `run`).
  // Every run gets what is left; when it runs out the best design so far is returned with a
  // warning (stop == "max_seconds").
  double max_seconds = 0;
  std::function<void(const OptimizeProgress&)> progress{};  // after every evaluation
};

// The end of one start.
struct OptimizeStart {
  std::vector<double> x0{}, x{};  // where it started and the best design it found
  double value = 0;               // objective at x
  double violation = 0;           // max(0, max_i g_i(x))
  int evaluations = 0;            // runs of the scene in this start
  std::string status{};           // "xtol" (converged), "max_evals", "max_seconds", "roundoff", ...
};

// The best design over every start.
struct OptimizeResult {
  std::vector<std::string> names{};          // the varied parameters
  std::vector<double> x{};                   // their best values
  double value = 0;                          // the objective there
  std::vector<double> constraints{};         // g_i(x) in the form g <= 0, one per subject_to
  bool feasible = true;                      // every constraint holds at x
  std::string method{};                      // "BOBYQA" or "COBYLA" (NLopt)
  std::string stop{};                        // "converged", "max_evals" or "max_seconds"
  int evaluations = 0;                       // runs of the scene
  double wall_seconds = 0, cpu_seconds = 0;  // the whole optimization's wall and CPU time
  std::vector<OptimizeStart> starts{};       // one per start, in start order
  std::vector<std::string> warnings{};       // budget run out, a start out of evaluations, no
                                             // feasible design, a variable at its bound
  // every parameter of the scene at the best design (dependency order, evaluated)
  std::vector<std::pair<std::string, double>> parameters{};
  // the scene file's text with the varied (and --set) parameters replaced by their values at x
  std::string scene_text{};
};

// A refusal of the optimization's input before any run (an unknown parameter, LO >= HI, an
// expression that does not parse, a name the run has no value for): what() says which, with the
// column in the expression and a suggestion.
class OptimizeInputError : public Error {
 public:
  using Error::Error;
};

// Runs the optimization (see the file's description). Throws OptimizeInputError for bad input,
// SceneError for the scene, Error for a run that fails at a design (the message names the
// parameters' values) or a non-finite objective or constraint.
OptimizeResult optimize_scene(const OptimizeOptions& options);

// "name=LO:HI" -> DesignVariable; throws OptimizeInputError (no '=', not two finite numbers,
// LO >= HI).
DesignVariable parse_design_variable(const std::string& text);

}  // namespace mo2d
