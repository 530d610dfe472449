// mo2d render SCENE [--set name=value]... [--out DIR] [--solve inverse|forward] [--frames]
// [--every K] [--format png|svg|pdf] [--video] [--loads] [--trace P,...] [--labels]: solves the
// scene (what its run.solve says, or --solve), then draws a filmstrip and the plots of that run
// (and, on request, every K-th frame and an MP4 when ffmpeg is installed) under DIR; --loads draws
// the applied forces and torques, --trace the paths of points, --labels the body names;
// --animate FILE writes an animation instead (render_animate.cpp).
#include <cstdio>

#include "command.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"
#include "mo2d/scene.hpp"
#include "render_animate.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

struct RenderCliOptions {
  SceneOptions scene{};
  std::string solve{};  // empty: the scene's run.solve
  bool frames = false, video = false;
  int every = 10;
  std::string format = "png";
  bool loads = false, labels = false;
  std::vector<std::string> traces{};
  AnimateCliOptions animate{};  // --animate PATH: only the animation (render_animate.cpp)
};

// What every frame and every filmstrip tile shows besides the mechanism.
void set_frame_options(const RenderCliOptions& o, FrameOptions& f) {
  f.show_loads = o.loads;
  f.show_labels = o.labels;
  f.traces = o.traces;
}

void print_outputs(const RenderOutputs& out) {
  if (!out.frames.empty())
    std::printf("  wrote %zu frames: %s ... %s\n", out.frames.size(), out.frames.front().c_str(),
                out.frames.back().c_str());
  if (!out.filmstrip.empty()) std::printf("  wrote %s\n", out.filmstrip.c_str());
  for (const auto& p : out.plots) std::printf("  wrote %s\n", p.c_str());
  if (!out.video.empty()) std::printf("  wrote %s\n", out.video.c_str());
  for (const auto& n : out.notes) std::printf("  note: %s\n", n.c_str());
}

int render(const RenderCliOptions& o) {
  const Scene scene = load_scene_with_overrides(o.scene);
  const Model model = build_model_of(scene);
  // the pictures land together or not at all (with --video the frames land before ffmpeg reads
  // them): every write_file_atomically below goes to this set
  OutputSet files;
  OutputSet::Scope scope(files);
  RenderJob job;
  job.dir = o.scene.out;
  job.name = scene.name;
  job.format = o.format;
  job.frames = o.frames || o.video;
  job.every = o.every;
  job.video = o.video;
  set_frame_options(o, job.frame);
  set_frame_options(o, job.filmstrip_options.tile);
  job.frame.contacts = job.filmstrip_options.tile.contacts = scene.contacts;
  const bool forward = o.solve.empty() ? scene.run.solve == Solve::forward : o.solve == "forward";
  if (forward) {
    const ForwardOptions run = forward_options(scene, model);
    check_scene_options(scene, model, run);
    // with the scene's contacts, if any
    const Trajectory r = scene_forward(scene, model, initial_state(scene, model), run).trajectory;
    std::printf("mo2d render: forward dynamics of %s, %d samples over [%g, %g] s\n",
                model.name.c_str(), static_cast<int>(r.time.size()), run.t0, run.t1);
    if (!o.animate.path.empty()) {
      write_run_animation(model, r, job.frame, o.animate);
      files.commit();
      return 0;
    }
    set_filmstrip_phase(r, o.animate, job);
    const RenderOutputs out = render_run(model, r, job);
    files.commit();
    print_outputs(out);
  } else {
    // (mo2d inverse holds a scene's closed contacts; this plain run would leave them out)
    refuse_contacts(scene, "mo2d render's inverse dynamics (mo2d inverse runs them)");
    const InverseOptions run = inverse_options(scene);
    check_scene_options(scene, model, run);
    const Trajectory r = inverse_dynamics(model, scene.motion, run);
    std::printf("mo2d render: inverse dynamics of %s, %d samples over [%g, %g] s\n",
                model.name.c_str(), static_cast<int>(r.time.size()), run.t0, run.t1);
    if (!o.animate.path.empty()) {
      write_run_animation(model, r, job.frame, o.animate);
      files.commit();
      return 0;
    }
    set_filmstrip_phase(r, o.animate, job);
    const RenderOutputs out = render_run(model, r, job);
    files.commit();
    print_outputs(out);
  }
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "render", "Solve a scene and draw it: filmstrip, plots, optionally frames and a video");
  add_scene_options(sub, o->scene, true, RunFlags::all);
  sub->add_option("--solve", o->solve, "inverse or forward (default: the scene's run.solve)")
      ->check(CLI::IsMember({"inverse", "forward"}));
  sub->add_flag("--frames", o->frames, "also write every K-th frame as DIR/NAME_0001.png ...");
  sub->add_option("--every", o->every, "frame interval K in samples (default 10)")
      ->check(finite_positive());
  sub->add_option("--format", o->format, "filmstrip and plots: png (default), svg or pdf")
      ->check(CLI::IsMember({"png", "svg", "pdf"}));
  sub->add_flag("--video", o->video, "an MP4 from the frames (needs ffmpeg on PATH)");
  sub->add_flag("--loads", o->loads,
                "draw the applied forces (arrows) and torques (arcs), sized by their value");
  sub->add_option("--trace", o->traces,
                  "trace the paths of points: named points, body.node or body.com "
                  "(comma-separated or repeated)")
      ->delimiter(',');
  sub->add_flag("--labels", o->labels, "write each body's name beside it");
  add_animate_options(sub, o->animate);
  return {sub, [o] { return render(*o); }};
}

}  // namespace mo2d::cli
