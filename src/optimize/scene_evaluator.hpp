#pragma once
// One evaluation of an optimization (mo2d/optimize.hpp): the scene run at a design (its text
// parsed with the design's parameters as overrides, the model built, inverse or forward dynamics
// as its run.solve says, the output and design columns added), then the objective and the
// constraints from the run's summary values.
#include <span>
#include <string>
#include <vector>

#include "mo2d/optimize.hpp"
#include "optimize/criterion.hpp"

namespace mo2d::optimize_detail {

class SceneEvaluator {
 public:
  // Reads the scene file, loads it once with the fixed overrides (a SceneError for the scene),
  // checks the varied names and bounds and parses the criteria (OptimizeInputError).
  explicit SceneEvaluator(const OptimizeOptions& o);

  struct Values {
    double objective = 0;
    std::vector<double> constraints{};  // g - h (<= 0 when the constraint holds)
    std::vector<double> scaled{};       // (g - h) / max(1, |h|): what COBYLA is given
    double violation = 0;               // max(0, max of scaled): feasible when <= constraint_tol
  };
  // The run at design x (in the order of vary) within `seconds` of wall time. The first call
  // binds the criteria's names to the run's values (an OptimizeInputError for a name the run has
  // no value for). Throws Error naming the design when the run fails or a value is not finite.
  Values evaluate(std::span<const double> x, double seconds);

  // The scene loaded with the fixed overrides (the start values of the varied parameters).
  const Scene& scene() const { return scene_; }
  // The overrides of design x: the fixed ones, then the varied ones (shortest exact text).
  std::vector<ParameterOverride> overrides(std::span<const double> x) const;
  // The scene at x: its parameters, and its text with the varied and fixed parameters replaced.
  Scene scene_at(std::span<const double> x) const;
  std::string text_at(std::span<const double> x) const;
  // "a = 0.1, b = 0.35" for messages.
  std::string describe(std::span<const double> x) const;

 private:
  struct Source {        // what a bound name reads
    int parameter = -1;  // index in Scene::parameters, or
    RunValue value{};    // a summary value of the run
  };
  OptimizeOptions o_;
  std::string text_{};
  Scene scene_{};
  std::vector<Criterion> criteria_{};  // objective first
  bool bound_ = false;
  bool needs_summary_ = false;
  std::vector<Source> sources_{};
  std::vector<Jet> values_{};
  void bind(const Scene& s, const Trajectory& r);
};

}  // namespace mo2d::optimize_detail
