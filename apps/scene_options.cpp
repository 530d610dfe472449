// Shared options of the scene subcommands, output paths, progress bar.
#include "scene_options.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace mo2d::cli {

namespace {
double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

namespace {

struct RunFlag {
  const char* key;
  const char* help;
};

// The run settings a subcommand may take from the command line, with their help (the scene's
// key, docs/scene-format.md#run).
constexpr RunFlag kBudgetFlags[] = {
    {"max_steps", "step budget of a forward run (default: the scene's run.max_steps, else 1e7)"},
    {"max_seconds",
     "wall-time budget of the run in s (default: the scene's run.max_seconds, else "
     "600)"},
    {"max_memory",
     "refuse a mechanism whose dense matrices and results need more bytes "
     "(default: the scene's run.max_memory, else 4e9)"},
};
constexpr RunFlag kTimeFlags[] = {
    {"t0", "start time in s (run.t0)"},
    {"duration", "s; the run ends at t0 + duration (run.duration)"},
    {"samples", "equally spaced output times, both ends included (run.samples)"},
};
constexpr RunFlag kInverseFlags[] = {
    {"tolerance", "inverse: position tolerance |psi|, relative to the model size (run.tolerance)"},
};
constexpr RunFlag kForwardFlags[] = {
    {"integrator", "cvode_bdf, cvode_adams, rk4, dopri5, erk6, erk8 or baumgarte (run.integrator)"},
    {"formulation", "augmented_lagrangian, lagrange or null_space (run.formulation)"},
    {"linear_algebra", "automatic, dense or sparse matrices of a forward run (run.linear_algebra)"},
    {"rtol", "relative tolerance of cvode_bdf, cvode_adams, dopri5, erk6 and erk8 (run.rtol)"},
    {"atol", "absolute tolerance of cvode_bdf, cvode_adams, dopri5, erk6 and erk8 (run.atol)"},
    {"step", "s, fixed step of rk4 and baumgarte (run.step)"},
    {"accuracy",
     "error of the positions asked for, relative to the mechanism's size: mo2d picks the "
     "integrator and its tolerances (run.accuracy; not with --integrator, --rtol, --atol, "
     "--step)"},
    {"error_estimate",
     "automatic, on or off: estimate the run's global error by a second run at tighter settings "
     "(automatic: when an accuracy is asked for; run.error_estimate)"},
};

template <std::size_t N>
void add_run_flags(CLI::App* app, SceneOptions& o, const RunFlag (&flags)[N]) {
  for (const RunFlag& f : flags) {
    const std::string key = f.key;
    app->add_option_function<std::string>(
           run_override_flag(key),
           [&o, key](const std::string& v) {
             o.run.push_back({key, v});
           },
           std::string(f.help) +
               "; replaces the scene's value (a number may be an expression of "
               "the parameters)")
        ->type_name(key == "integrator" || key == "formulation" || key == "linear_algebra" ||
                            key == "error_estimate"
                        ? "NAME"
                        : "VALUE");
  }
}

}  // namespace

CLI::Validator name_equals_value() {
  return CLI::Validator(
      [](const std::string& s) {
        try {
          parse_override(s);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      },
      "name=value");
}

namespace {
CLI::Validator finite_number(bool zero_allowed) {
  return CLI::Validator(
      [zero_allowed](const std::string& s) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        const char* expected = zero_allowed ? "a finite number >= 0" : "a finite number > 0";
        if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v) ||
            (zero_allowed ? v < 0 : v <= 0))
          return std::string("must be ") + expected + ", got '" + s + "'";
        return std::string();
      },
      zero_allowed ? "NONNEGATIVE" : "POSITIVE");
}
}  // namespace

CLI::Validator finite_positive() {
  return finite_number(false);
}
CLI::Validator finite_non_negative() {
  return finite_number(true);
}

void add_scene_options(CLI::App* app, SceneOptions& o, bool with_out, RunFlags flags) {
  app->add_option("SCENE", o.scene, "scene file (YAML, see docs/scene-format.md)")->required();
  app->add_option("--set", o.set,
                  "override a parameter: --set name=value (value: an expression of the other "
                  "parameters); repeatable")
      ->allow_extra_args(false)  // one value per --set, so SCENE may follow
      ->check(name_equals_value());
  if (with_out)
    app->add_option("--out", o.out,
                    "output folder (created if needed); a run's files land together or not at "
                    "all (docs/scene-format.md)")
        ->capture_default_str();
  if (flags != RunFlags::budgets) add_run_flags(app, o, kTimeFlags);
  if (flags == RunFlags::inverse || flags == RunFlags::all) add_run_flags(app, o, kInverseFlags);
  if (flags == RunFlags::forward || flags == RunFlags::all) add_run_flags(app, o, kForwardFlags);
  add_run_flags(app, o, kBudgetFlags);
}

Scene load_scene_with_overrides(const SceneOptions& o) {
  std::vector<ParameterOverride> overrides;
  for (const auto& s : o.set) overrides.push_back(parse_override(s));
  try {
    return load_scene(o.scene, overrides, o.run);
  } catch (const SceneError& e) {  // at "--set" or "--duration": the command line's
    if (e.where().file.starts_with("--") && e.where().line == 0) throw UsageError(e.what());
    throw;
  }
}

Model build_model_of(const Scene& s) {
  BuildOptions b;
  b.max_memory = s.run.max_memory;
  Model m = build_scene_model(s, b);
  for (const auto& w : m.sketch.warnings) std::fprintf(stderr, "mo2d: warning: %s\n", w.c_str());
  return m;
}

ContactInverseModel inverse_model_of(const Scene& s) {
  BuildOptions b;
  b.max_memory = s.run.max_memory;
  ContactInverseModel held = scene_inverse_model(s, b);
  for (const auto& w : held.model.sketch.warnings)
    std::fprintf(stderr, "mo2d: warning: %s\n", w.c_str());
  return held;
}

std::string output_path(const SceneOptions& o, const Scene& s, const std::string& suffix) {
  return (std::filesystem::path(o.out) / (s.name + "_" + suffix)).string();
}

bool isatty_stderr() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(const std::string& what, double t0, double t1, const char* unit)
    : what_(what),
      unit_(unit),
      t0_(t0),
      t1_(t1),
      start_(wall_seconds()),
      enabled_(isatty_stderr()) {
  last_line_ = start_;
}

void Progress::update(double t) {
  if (enabled_) draw(t);
}

void Progress::draw(double t) {
  const double now = wall_seconds();
  if (now - start_ < 0.5 || now - last_draw_ < 0.1) return;
  last_draw_ = now;
  const double f = std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0);
  const int width = 40, filled = static_cast<int>(f * width);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(width, ' ');
  std::fprintf(stderr, "\r[%s] %3.0f%%  t = %.3g s", bar.c_str(), 100 * f, t);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::report(const RunProgress& p) {
  if (p.stalled && !stall_said_) {
    stall_said_ = true;
    finish();
    std::fprintf(stderr,
                 "mo2d: warning: %s: the step size collapsed to %.3g s at t = %.6g s after %ld "
                 "steps; the run may not finish (budget: --max-seconds, --max-steps)\n",
                 what_.c_str(), p.step_size, p.t, p.steps);
  }
  if (enabled_) return draw(p.t);
  const double now = wall_seconds();
  if (now - last_line_ < kLineInterval) return;
  last_line_ = now;
  const double f = std::clamp((p.t - p.t0) / (p.t1 - p.t0), 0.0, 1.0);
  std::fprintf(stderr, "mo2d: %s at t = %.6g s of [%g, %g] s (%.1f%%), %ld %s", what_.c_str(), p.t,
               p.t0, p.t1, 100 * f, p.steps, unit_.c_str());
  if (p.step_size > 0) std::fprintf(stderr, ", last step %.3g s", p.step_size);
  std::fprintf(stderr, ", %.0f s elapsed\n", p.seconds);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", 70, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace mo2d::cli
