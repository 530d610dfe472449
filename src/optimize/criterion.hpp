#pragma once
// The objective and the constraints of an optimization (mo2d/optimize.hpp): expressions of the
// scene's expression language over parameters and a run's summary values (run_values.hpp). A
// constraint is "g" (g <= 0), "g <= h" or "g >= h"; its value is written g - h <= 0.
#include <string>
#include <vector>

#include "mo2d/expression.hpp"
#include "optimize/run_values.hpp"

namespace mo2d::optimize_detail {

struct Criterion {
  std::string text{};  // as given
  std::string what{};  // "objective" or "constraint N" (1-based), for messages
  Expression lhs{}, rhs{};
  bool has_rhs = false;
  int rhs_offset = 0;  // 0-based column of rhs in text
  double sign = 1;     // +1: lhs - rhs <= 0 (or lhs alone); -1: ">=", rhs - lhs <= 0
};

// Parses `text`; a comparison (<=, >=) splits it, only where `comparison_allowed`. Throws
// OptimizeInputError ("objective 'TEXT', column C: ...").
Criterion parse_criterion(const std::string& text, const std::string& what,
                          bool comparison_allowed);

// An OptimizeInputError "WHAT 'TEXT', column C: MESSAGE" for the 1-based column C of text.
[[noreturn]] void fail_criterion(const Criterion& c, int column, const std::string& message);

// The value of c (objective) or of g - h (constraint, <= 0 when it holds) with its names bound
// to variables indexed into `values`.
double criterion_value(const Criterion& c, const std::vector<Jet>& values);

// The scale of a constraint: max(1, |h|), so that its tolerance is relative to its bound.
double criterion_scale(const Criterion& c, const std::vector<Jet>& values);

}  // namespace mo2d::optimize_detail
