// mo2d demo [MECHANISM] [--out DIR]: inverse dynamics of a built-in example mechanism (default:
// whitworth), a short table, DIR/MECHANISM_inverse.csv, a filmstrip of the motion and plots of the
// efforts and residuals. scripts/quickstart.sh runs it.
#include <cstdio>
#include <filesystem>
#include <map>

#include "command.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/output.hpp"
#include "mo2d/render.hpp"
#include "scene_options.hpp"
#include "table.hpp"

namespace mo2d::cli {

namespace {

struct DemoOptions {
  std::string mechanism = "whitworth";
  std::string out = "out";
};

int demo(const DemoOptions& o) {
  const std::map<std::string, mechanisms::Example (*)()> table = {
      {"whitworth", &mechanisms::whitworth},
      {"rrr3", &mechanisms::rrr3},
      {"slider_crank", [] { return mechanisms::slider_crank(); }},
      {"fourbar", &mechanisms::fourbar},
      {"pendulum", [] { return mechanisms::pendulum(); }}};
  auto it = table.find(o.mechanism);
  if (it == table.end())
    throw UsageError("unknown mechanism '" + o.mechanism +
                     "' (expected whitworth, rrr3, slider_crank, fourbar or pendulum)");
  const mechanisms::Example ex = it->second();
  const Model model = build_model(ex.system);
  const Trajectory r = inverse_dynamics(model, ex.motion, ex.run);

  std::printf("mo2d inverse dynamics: %s\n", model.name.c_str());
  print_inverse_table(model, r, ex.run);
  OutputSet files;  // the CSV and the pictures land together or not at all
  {
    OutputSet::Scope scope(files);
    write_trajectory_csv(r,
                         (std::filesystem::path(o.out) / (o.mechanism + "_inverse.csv")).string());
    RenderJob job;
    job.dir = o.out;
    job.name = o.mechanism;
    render_run(model, r, job);
  }
  files.commit();
  for (const auto& p : files.paths()) std::printf("  wrote %s\n", p.c_str());
  return 0;
}

}  // namespace

Command add_demo_command(CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand(
      "demo",
      "Inverse dynamics of a built-in mechanism; writes DIR/MECHANISM_inverse.csv, a filmstrip "
      "and plots");
  sub->add_option("MECHANISM", o->mechanism,
                  "whitworth (default), rrr3, slider_crank, fourbar, pendulum");
  sub->add_option("--out", o->out, "output folder")->capture_default_str();
  return {sub, [o] { return demo(*o); }};
}

}  // namespace mo2d::cli
