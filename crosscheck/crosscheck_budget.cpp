// The budgets of a cross-check (crosscheck_budget.hpp).
#include "crosscheck_budget.hpp"

#include <climits>
#include <cmath>

#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::crosscheck_detail {

using detail::fmt;

void check_box2d_steps(const std::string& what, const std::string& name, double steps, double h,
                       const CrosscheckOptions& check) {
  const double limit =
      check.max_steps > 0 ? std::fmin(static_cast<double>(check.max_steps), INT_MAX) : INT_MAX;
  if (steps <= limit) return;
  throw Error(what + ": a step of " + fmt(h) + " s needs " + fmt(steps) +
                  " Box2D steps, more than the step budget of " + fmt(limit) +
                  " (max_steps: scene run.max_steps, mo2d --max-steps" +
                  (limit == INT_MAX ? ", at most 2^31 - 1" : "") + "): use a longer --step",
              name);
}

void check_result_memory(const std::string& what, const std::string& name, double rows,
                         double values, const CrosscheckOptions& check) {
  const double bytes = 33.0 * rows * values;
  if (check.max_memory <= 0 || bytes <= check.max_memory) return;
  throw Error(what + ": its results (" + fmt(rows) + " compared steps x " + fmt(values) +
                  " values, the series and their CSV) need about " + fmt(bytes / 1e9) +
                  " GB, more than the limit of " + fmt(check.max_memory / 1e9) +
                  " GB (max_memory: scene run.max_memory, mo2d --max-memory): use a longer --step "
                  "or a shorter duration",
              name);
}

detail::RunBudget::Settings box2d_budget(const std::string& what, const std::string& name,
                                         double t0, double t1, const CrosscheckOptions& check) {
  return {.run = what,
          .name = name,
          .t0 = t0,
          .t1 = t1,
          .max_steps = 0,  // counted before the run (check_box2d_steps)
          .max_seconds = check.max_seconds,
          .monitor = {},
          .interval = 1e9,
          .hint = "use a longer --step",
          .unit = "Box2D steps"};
}

}  // namespace mo2d::crosscheck_detail
