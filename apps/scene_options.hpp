#pragma once
// Options shared by the subcommands that read a scene (SCENE, --set, --out) and the helpers
// they share: loading with overrides, the output folder, a progress bar.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mo2d/output.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::cli {

struct SceneOptions {
  std::string scene{};
  std::vector<std::string> set{};  // name=value
  std::string out = "out";
  // run settings given on the command line (--duration 2 -> {"duration", "2"}), applied on top of
  // the scene's run: block (RunOverride, mo2d/scene.hpp), in the order given
  std::vector<RunOverride> run{};
  bool units_row = false;  // inverse, forward: --units-row
  bool measures = false;   // inverse, forward: --measures (frame and bearing loads, docs/design.md)
};

// Which run settings a subcommand lets the command line override (--KEY for each run key).
enum class RunFlags {
  budgets,  // --max-steps, --max-seconds, --max-memory
  inverse,  // + --t0, --duration, --samples, --tolerance
  forward,  // + --t0, --duration, --samples, --integrator, --formulation, --rtol, --atol, --step
  all,      // both
};

// SCENE positional (required), --set and the run settings of `flags`; with_out: --out DIR too.
// A --set without '=' is a usage error (exit status 2).
void add_scene_options(CLI::App* app, SceneOptions& o, bool with_out,
                       RunFlags flags = RunFlags::budgets);
// The scene with the --set and run overrides. A bad value on the command line (an unknown
// parameter, --duration -1) is a UsageError, reported like the scene's own errors
// ("--duration: run.duration: must be > 0 s") but with exit status 2.
Scene load_scene_with_overrides(const SceneOptions& o);

// CLI11 check of a --set / --reference-set value: name=value (parse_override), else a usage error.
CLI::Validator name_equals_value();
// CLI11 checks of a number option that must be finite and > 0 (or >= 0): CLI11's PositiveNumber
// and NonNegativeNumber let "nan" through (no comparison with NaN fails), and "inf".
CLI::Validator finite_positive();
CLI::Validator finite_non_negative();

// A command-line usage error: main prints it and exits with status 2.
struct UsageError : Error {
  using Error::Error;
};
// build_scene_model with the scene's memory limit (run.max_memory, --max-memory).
Model build_model_of(const Scene& s);
// The model of an inverse run: build_model_of, or with the scene's contacts closed at the start
// held closed (scene_inverse_model; docs/contact.md, "Inverse dynamics").
ContactInverseModel inverse_model_of(const Scene& s);
// OUT/<scene name>_<suffix> (the folder is created when the run's outputs are added to an
// OutputSet, mo2d/output.hpp).
std::string output_path(const SceneOptions& o, const Scene& s, const std::string& suffix);

bool isatty_stderr();

// Progress of a run on stderr. When stderr is a terminal: a bar, drawn once the run has lasted
// more than half a second, erased by finish(). Otherwise: a line every kLineInterval seconds
// ("mo2d: forward dynamics at t = ... of [t0, t1] s (..%), N steps, last step h s, S s"), and a
// warning line when the step size collapses. Short runs print nothing.
class Progress {
 public:
  static constexpr double kLineInterval = 10;
  Progress(const std::string& what, double t0, double t1, const char* unit = "steps");
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void update(double t);              // at output times
  void report(const RunProgress& p);  // from the run's monitor (also between output times)
  void finish();

 private:
  std::string what_, unit_;
  double t0_ = 0, t1_ = 1;
  double start_ = 0, last_draw_ = 0, last_line_ = 0;
  bool enabled_ = false, drawn_ = false, stall_said_ = false;
  void draw(double t);
};

}  // namespace mo2d::cli
