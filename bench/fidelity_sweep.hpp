#pragma once
// Speed against error between fidelities (issue 13, docs/reduction.md): the pieces of the sweep
// bench/fidelity_sweep.cpp runs. A fidelity is a row of a table: a name, edits of the scene's
// YAML (set or erase a key by its path) and the integrator that suits it; a run is a scene with
// one fidelity, one chain stiffness and one tolerance, timed over repetitions (CPU of the solve
// only, ForwardOptions' RunStats::cpu_seconds: no loading, no model building, no output columns),
// its slow signals low-pass filtered and compared with the same signals of the reference run.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace mo2d::sweep {

// An edit of the scene's YAML: `path` a dotted key path ("loads.chains.chain.fidelity"),
// `value` a YAML text (a scalar or a flow map) to set there, or empty to erase the key.
struct Edit {
  std::string path{};
  std::string value{};
};

// A slow signal: the sum of factor x column (columns of coordinates, rates, reactions, efforts
// and output columns), or (angle_about set) the angle of the point (x column, y column) about a
// fixed point, unwrapped.
struct Term {
  std::string column{};
  double factor = 1;
};
struct Signal {
  std::string name{};  // "wheel speed"
  std::vector<Term> terms{};
  bool angle = false;
  double x0 = 0, y0 = 0;  // angle: the fixed point; terms[0] the x column, terms[1] the y column
};

struct Fidelity {
  std::string name{};         // "unilateral (BDF)"
  std::vector<Edit> edits{};  // on the scene's YAML
  std::string integrator{};   // cvode_bdf, dopri5, ...
  // a signal of the same name replacing the scene's (e.g. the chain tension of a gear model)
  std::vector<Signal> signals{};
  bool optional = false;  // refused by the scene loader: "not available in this build", skipped
};

struct SceneCase {
  std::string name{};  // "half_bike"
  std::string file{};
  std::vector<std::string> parameters{};  // "name=value" for every run (scenario, ...)
  double duration = 1;
  int samples = 101;
  double sigma = 0.1;             // s, standard deviation of the Gaussian low-pass filter
  std::vector<Signal> signals{};  // the slow signals
  std::vector<Fidelity> fidelities{};
};

struct RunSpec {
  double k = 1e5;  // chain stiffness, N/m (parameter k_chain)
  double rtol = 1e-6, atol = 1e-8;
  std::string integrator{};
  int repetitions = 3;
  int max_steps = 200000;   // budget of one run
  double max_seconds = 30;  // wall-clock budget of one run
};

enum class Status { ok, budget_exceeded, not_available, failed };
const char* to_string(Status s);

struct RunResult {
  Status status = Status::ok;
  std::string message{};               // the reason when not ok
  double cpu_median = 0, cpu_min = 0;  // s, of the solve
  long steps = 0;
  std::vector<Eigen::VectorXd> slow{};  // filtered slow signals, one per SceneCase::signals
};

// The scene's text with the fidelity's edits (yaml-cpp; throws mo2d::Error naming a path that is
// not there).
std::string edited_scene(const std::string& file, const std::vector<Edit>& edits);

// Run the scene with the fidelity at `spec`: status not_available when the scene loader or the
// model builder refuses an optional fidelity, budget_exceeded when a run's budget runs out.
RunResult run_case(const SceneCase& scene, const Fidelity& fidelity, const RunSpec& spec);

// Zero-phase Gaussian low-pass filter on equally spaced samples (spacing dt): the kernel
// exp(-s^2 / (2 sigma^2)) truncated at 4 sigma and renormalized where it leaves the interval.
Eigen::VectorXd gaussian_filter(const Eigen::VectorXd& x, double dt, double sigma);

// Half-width of the filter's kernel in samples: the first and last `margin` samples are filtered
// by a truncated kernel, whose step at the interval's end lets fast motion through (a response
// falling as 1/f, not as a Gaussian): the errors leave them out.
Eigen::Index filter_margin(double dt, double sigma);

// Error of a filtered signal against the reference's, samples margin .. n-1-margin:
// max |x - ref| / (max ref - min ref) over them.
double relative_error(const Eigen::VectorXd& x, const Eigen::VectorXd& ref, Eigen::Index margin);

}  // namespace mo2d::sweep
