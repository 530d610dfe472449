// Shared options of the scene subcommands, output paths, progress bar.
#include "scene_options.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace mo2d::cli {

namespace {
double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

void add_scene_options(CLI::App* app, SceneOptions& o, bool with_out) {
  app->add_option("SCENE", o.scene, "scene file (YAML, see docs/scene-format.md)")->required();
  app->add_option("--set", o.set,
                  "override a parameter: --set name=value (value: an expression of the other "
                  "parameters); repeatable")
      ->allow_extra_args(false);  // one value per --set, so SCENE may follow
  if (with_out)
    app->add_option("--out", o.out, "output folder (created if needed)")->capture_default_str();
}

Scene load_scene_with_overrides(const SceneOptions& o) {
  std::vector<ParameterOverride> overrides;
  for (const auto& s : o.set) overrides.push_back(parse_override(s));
  return load_scene(o.scene, overrides);
}

std::string output_path(const SceneOptions& o, const Scene& s, const std::string& suffix) {
  std::filesystem::create_directories(o.out);
  return (std::filesystem::path(o.out) / (s.name + "_" + suffix)).string();
}

bool isatty_stderr() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(double t0, double t1)
    : t0_(t0), t1_(t1), start_(wall_seconds()), enabled_(isatty_stderr()) {}

void Progress::update(double t) {
  if (!enabled_) return;
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

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", 70, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace mo2d::cli
