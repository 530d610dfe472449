#pragma once
// Internal: the step and wall-clock budget of one run, and its progress monitor.
#include <chrono>
#include <functional>
#include <string>

#include "mo2d/budget.hpp"
#include "mo2d/run_stop.hpp"

namespace mo2d::detail {

inline double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

// Created when a run starts. check() is called at every accepted step (or right-hand-side
// evaluation) with the time reached: it throws Error when the steps or the wall-clock seconds run
// out, and calls the monitor about every `interval` seconds (progress, collapsed step size).
class RunBudget {
 public:
  struct Settings {
    std::string run;   // "forward dynamics of 'name'"
    std::string name;  // model name (the Error's element)
    double t0 = 0, t1 = 1;
    long max_steps = 0;      // <= 0: none
    double max_seconds = 0;  // <= 0 or infinite: none
    std::function<void(const RunProgress&)> monitor{};
    double interval = 1;         // s between monitor calls
    std::string hint;            // what to change besides the budget (integrator, tolerances)
    std::string unit = "steps";  // what `steps` counts (inverse dynamics: samples)
    // Why the step collapsed at (t, y), and what will help (forward: collapse_cause.cpp); called
    // once, when check() ends the run for a collapse (y: the state check() was given, or null).
    std::function<std::string(double t, const double* y)> collapse_cause{};
  };
  explicit RunBudget(Settings s);

  // Throws Error when the budget is out or the step size has collapsed (below), Interrupted when
  // the interrupt check says so (polled every kInterruptPoll s); calls the monitor when due.
  // Cheap (one clock read). y: the state at t (for Settings::collapse_cause), or null.
  void check(double t, long steps, double step_size, const double* y = nullptr);
  bool out_of_time() const;  // the wall-clock budget is spent (no throw: for C callbacks)
  [[noreturn]] void throw_exhausted(double t, long steps, double step_size) const;
  bool stalled() const { return stalled_; }
  // The first time the step size collapsed (RunProgress::stall_ratio), as a warning; "" if never.
  const std::string& stall_warning() const { return stall_warning_; }
  double elapsed() const;

 private:
  Settings s_;
  double start_ = 0, next_report_ = 0, next_poll_ = 0;
  bool stalled_ = false;
  std::string stall_warning_;
  // Collapse of the step size relative to the run's own steps (check_collapse, budget.cpp):
  // ref_step_ the recent accepted steps' decaying maximum; the checks in a row whose step was
  // collapsed (tiny: against ref_step_; hopeless: against the step budget) and the step count
  // when each run of them began.
  long last_steps_ = 0;
  double ref_step_ = 0;
  long tiny_checks_ = 0, tiny_from_ = 0, hopeless_checks_ = 0, hopeless_from_ = 0;
  double hopeless_step_ = 0;  // the step size at the first of the hopeless checks
  void check_collapse(double t, long steps, double step_size, const double* y);
};

}  // namespace mo2d::detail
