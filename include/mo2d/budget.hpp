#pragma once
// Limits of a run, checked so that every run ends and no run produces a silent wrong answer:
//  - the time grid: equally spaced samples (and fixed steps) that double precision resolves;
//  - memory: the dense matrices of a computation, estimated from the model's sizes before they
//    are allocated, against a limit (bytes);
//  - budgets: accepted steps and wall-clock seconds (ForwardOptions, InverseOptions), with a
//    progress report every few seconds (RunProgress).
// Every refusal is an Error that names the setting, its value and what to change.
#include <string>

namespace mo2d {

struct Model;

// Default limit of the dense-matrix memory of one computation (bytes).
inline constexpr double kDefaultMaxMemory = 4e9;
// Default budgets of a run: accepted steps (forward) and wall-clock seconds (forward, inverse).
inline constexpr int kDefaultMaxSteps = 10'000'000;
inline constexpr double kDefaultMaxSeconds = 600;
// A sample spacing or fixed step shorter than this times max(|t0|, |t1|) is refused: the times
// would be resolved to worse than 1e-4 of the spacing (double precision: 2.2e-16 relative).
inline constexpr double kTimeResolution = 2.2e-12;

// State of a run, passed to a progress monitor (ForwardOptions::monitor, InverseOptions::monitor).
struct RunProgress {
  double t = 0, t0 = 0, t1 = 1;  // time reached, run interval
  long steps = 0;                // accepted steps so far (forward), samples solved (inverse)
  double step_size = 0;          // last step size (s); 0 when unknown
  double seconds = 0;            // wall-clock time since the run started
  bool stalled = false;          // the step size collapsed (see RunProgress::stall_ratio)
  // The step size is reported as collapsed when below stall_ratio * (t1 - t0).
  static constexpr double stall_ratio = 1e-9;
};

// Equally spaced samples over [t0, t1] (both ends; `samples` >= 1, t1 > t0 when samples > 1):
// throws Error (element "t0", "t1" or "samples") when t0 or t1 is not finite or the spacing is
// below the time resolution at max(|t0|, |t1|). `run`: "forward dynamics" or "inverse dynamics".
void check_time_grid(const char* run, double t0, double t1, long long samples);

// Throws Error (element `setting`) when `bytes` > `limit`: "<what> needs about X GB of dense
// matrices (<sizes>), more than the limit of Y GB (<setting>)". limit <= 0: no limit.
void check_memory(const std::string& what, double bytes, double limit, const std::string& sizes,
                  const std::string& setting);

// Estimated bytes of the dense matrices of: building a model with these sizes (assembly and rank
// checks); the conditioning of the velocity constraints (SVD, mo2d info).
double build_memory_bytes(int n0, int m0, int n1, int m1);
double conditioning_memory_bytes(const Model& m);
// Refuses magnitudes double precision cannot carry through a run (Error naming the element):
// a body's weight and energy scale m max(1, |g|) max(1, L)^2 (L: the model's size), its inertia,
// a spring's stiffness k max(1, L)^2 and damping, above kMaxMagnitude (mass 1e308 kg: m g L
// overflows to inf and the efforts to NaN); gravity |g| max(1, L) above sqrt(kMaxMagnitude)
// (its accelerations are squared).
inline constexpr double kMaxMagnitude = 1e250;
void check_magnitudes(const Model& m);

// "n0 = .., n1 = .., m0 = .., m1 = .." for messages.
std::string model_sizes(const Model& m);

}  // namespace mo2d
