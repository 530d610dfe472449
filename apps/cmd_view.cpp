// mo2d view SCENE -o RUN.html [--columns a,b] [--max-frames N] [--width W --height H]
// [--solve inverse|forward] [--set name=value]... [run settings]: solves the scene as `mo2d
// render` does (its run.solve, or --solve) and writes ONE self-contained HTML page that plays the
// run (mo2d/view.hpp, docs/viewer.md). Written atomically; the page holds at most N frames.
#include <cstdio>

#include "command.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/view.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

struct ViewCliOptions {
  SceneOptions scene{};
  std::string out{};    // default: OUT/<scene name>_view.html
  std::string solve{};  // empty: the scene's run.solve
  std::vector<std::string> columns{};
  int max_frames = 400;
  int width = 800, height = 600;
};

Trajectory solve(const ViewCliOptions& o, const Scene& scene, const Model& model) {
  const bool forward = o.solve.empty() ? scene.run.solve == Solve::forward : o.solve == "forward";
  if (forward) {
    const ForwardOptions run = forward_options(scene, model);
    check_scene_options(scene, model, run);
    // with the scene's contacts, if any
    Trajectory r = scene_forward(scene, model, initial_state(scene, model), run).trajectory;
    add_output_columns(model, r, scene.outputs);
    std::printf("mo2d view: forward dynamics of %s, %d samples over [%g, %g] s\n",
                model.name.c_str(), static_cast<int>(r.time.size()), run.t0, run.t1);
    return r;
  }
  // (mo2d inverse holds a scene's closed contacts; this plain run would leave them out)
  refuse_contacts(scene, "mo2d view's inverse dynamics (mo2d inverse runs them)");
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, model, run);
  Trajectory r = inverse_dynamics(model, scene.motion, run);
  add_output_columns(model, r, scene.outputs);
  std::printf("mo2d view: inverse dynamics of %s, %d samples over [%g, %g] s\n", model.name.c_str(),
              static_cast<int>(r.time.size()), run.t0, run.t1);
  return r;
}

int view(const ViewCliOptions& o) {
  const Scene scene = load_scene_with_overrides(o.scene);
  const Model model = build_model_of(scene);
  const Trajectory r = solve(o, scene, model);
  ViewerOptions v;
  v.frame.width = o.width;
  v.frame.height = o.height;
  v.frame.contacts = scene.contacts;  // drawn as in mo2d render's frames
  v.max_frames = o.max_frames;
  v.columns = o.columns;
  const std::string path = o.out.empty() ? output_path(o.scene, scene, "view.html") : o.out;
  ViewerPage page;
  try {
    page = viewer_page(model, r, v);
  } catch (const Error& e) {
    if (std::string(e.what()).starts_with("unknown column")) throw UsageError(e.what());
    throw;
  }
  OutputSet files;  // the folder is created if needed; the page lands whole or not at all
  files.add(path, page.html);
  files.commit();
  std::printf("  wrote %s (%zu bytes, %d of %d samples)\n", path.c_str(), page.html.size(),
              page.frames, page.samples);
  for (const auto& n : page.notes) std::printf("  note: %s\n", n.c_str());
  return 0;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "view", "Solve a scene and write one self-contained HTML page that plays the run");
  add_scene_options(sub, o->scene, true, RunFlags::all);
  sub->add_option("-o,--output", o->out, "the page (default: OUT/NAME_view.html)");
  sub->add_option("--solve", o->solve, "inverse or forward (default: the scene's run.solve)")
      ->check(CLI::IsMember({"inverse", "forward"}));
  sub->add_option("--columns", o->columns,
                  "columns plotted under the drawing, by their CSV labels (comma-separated or "
                  "repeated; default: the efforts)")
      ->delimiter(',');
  sub->add_option("--max-frames", o->max_frames,
                  "at most N samples in the page: every k-th and the last (default 400)")
      ->check(CLI::Range(2, 1000000));
  sub->add_option("--width", o->width, "drawing width in pixels (default 800)")
      ->check(CLI::Range(64, 8192));
  sub->add_option("--height", o->height, "drawing height in pixels (default 600)")
      ->check(CLI::Range(64, 8192));
  return {sub, [o] { return view(*o); }};
}

}  // namespace mo2d::cli
