#pragma once
// How a run stops early, besides a failure: its budget runs out (BudgetExhausted, mo2d/budget.hpp)
// or it is interrupted (Interrupted, e.g. Ctrl-C in Python).
#include <exception>

#include "mo2d/error.hpp"

namespace mo2d {

// The Error of a run whose step or wall-time budget ran out (or that would need more than its
// budget, estimated before it starts): its own type, so that the stages that recover from an
// Error (a line search, a shorter step) let it through.
class BudgetExhausted : public Error {
 public:
  using Error::Error;
};

// Interrupts. Every run polls the interrupt check about every kInterruptPoll seconds of wall time
// (at its budget checks: each accepted step, right-hand side evaluation, sample, Box2D step,
// linearization stage); when it returns true, the run ends by throwing Interrupted. The Python
// module installs a check that runs Python's signal handlers (Ctrl-C: KeyboardInterrupt within
// 0.1 s); the command line installs none (SIGINT ends the process, mo2d/output.hpp).
inline constexpr double kInterruptPoll = 0.05;
using InterruptCheck = bool (*)();
void set_interrupt_check(InterruptCheck check);  // nullptr: none (the default)
InterruptCheck interrupt_check();                // the check installed (nullptr: none)
// Thrown by a run that its interrupt check stopped. Not an Error, so that nothing in mo2d that
// recovers from an Error (a retry, a fallback method) swallows it.
struct Interrupted : std::exception {
  // "mo2d: the run was interrupted"
  const char* what() const noexcept override { return "mo2d: the run was interrupted"; }
};
// Calls the interrupt check (if any) and throws Interrupted when it says so.
void poll_interrupt();

}  // namespace mo2d
