#pragma once
// The one exception type of mo2d: every message names the element (body, joint, coordinate,
// constraint) and, for a run, the time at which the problem was found.
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace mo2d {

// The exception thrown by mo2d: a message, the offending element's label and the time of a run.
class Error : public std::runtime_error {
 public:
  // `what`: the message; `element`: the label of the element at fault; `time`: the time (s) of the
  // run at which it was found (NaN: outside a run).
  explicit Error(const std::string& what, std::string element = {},
                 double time = std::numeric_limits<double>::quiet_NaN())
      : std::runtime_error(what), element_(std::move(element)), time_(time) {}
  const std::string& element() const { return element_; }  // label of the offending element
  double time() const { return time_; }                    // NaN when not raised during a run
 private:
  std::string element_;
  double time_;
};

}  // namespace mo2d
