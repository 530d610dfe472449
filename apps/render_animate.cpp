// `mo2d render --animate`: the options, the plot strip (animation_plot) and the animation written
// (atomically) with its frame count and codec printed.
#include "render_animate.hpp"

#include <chrono>
#include <cstdio>

#include "mo2d/error.hpp"
#include "mo2d/render/animate.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

// "720deg", "4pi", "12.566": a cycle in the coordinate's unit (deg and pi: radians).
double parse_cycle(const std::string& text) {
  const auto ends = [&](const std::string& tail) {
    return text.size() > tail.size() &&
           text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
  };
  const double scale = ends("deg")  ? 3.14159265358979323846 / 180
                       : ends("pi") ? 3.14159265358979323846
                                    : 1;
  const std::string number = text.substr(0, text.size() - (ends("deg") ? 3 : ends("pi") ? 2 : 0));
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != number.size() || !(v > 0))
    throw Error("render: --filmstrip-cycle '" + text +
                    "' is not a positive number (optionally with deg or pi: 720deg, 4pi)",
                "--filmstrip-cycle");
  return v * scale;
}

}  // namespace

void set_filmstrip_phase(const Trajectory& run, const AnimateCliOptions& o, RenderJob& job) {
  if (o.phase.empty()) return;
  if (o.cycle.empty())
    throw Error("render: --filmstrip-phase needs --filmstrip-cycle (e.g. 360deg)",
                "--filmstrip-cycle");
  const Eigen::VectorXd v = run.q0.col(run.column(o.phase));
  job.filmstrip_options.phase.assign(v.data(), v.data() + v.size());
  job.filmstrip_options.cycle = parse_cycle(o.cycle);
}

void add_animate_options(CLI::App* sub, AnimateCliOptions& o) {
  sub->add_option("--animate", o.path,
                  "write an animation to this file instead of the filmstrip and plots: .webm "
                  "(VP9), .mp4 (H.264), .gif or .apng (needs FFmpeg's libraries)");
  sub->add_option("--fps", o.fps, "animation: frames per second (default 30)")
      ->check(finite_positive());
  sub->add_option("--slow", o.slow,
                  "animation: play this many times slower than real time (default 1)")
      ->check(finite_positive());
  sub->add_option("--plot", o.plot,
                  "animation: a column of the run (e.g. crank.torque) drawn below the frames "
                  "with a cursor at the frame's time");
  sub->add_option("--max-frames", o.max_frames, "animation: the most frames (default 3000)")
      ->check(finite_positive());
  sub->add_option("--filmstrip-phase", o.phase,
                  "filmstrip tiles at evenly spaced values of this coordinate (e.g. crank.angle) "
                  "over the run's last cycle, not at evenly spaced times");
  sub->add_option("--filmstrip-cycle", o.cycle,
                  "the cycle of --filmstrip-phase: 360deg, 720deg (a four-stroke engine), 2pi, "
                  "or a length in m");
  sub->add_option("--threads", o.threads, "animation: threads drawing frames (default: the cores)")
      ->check(finite_non_negative());
  sub->add_option("--width", o.width, "animation: frame width in pixels (default 800)")
      ->check(CLI::Range(16, 8192));
  sub->add_option("--height", o.height, "animation: frame height in pixels (default 600)")
      ->check(CLI::Range(16, 8192));
}

void write_run_animation(const Model& model, const Trajectory& run, const FrameOptions& frame,
                         const AnimateCliOptions& o) {
  AnimationOptions a;
  a.frame = frame;
  a.frame.width = o.width;
  a.frame.height = o.height;
  a.fps = o.fps;
  a.slow = o.slow;
  a.max_frames = o.max_frames;
  if (!o.plot.empty()) {
    a.plot = true;
    a.strip = animation_plot(model, run, o.plot);
  }
  a.threads = o.threads;
  const auto start = std::chrono::steady_clock::now();
  const AnimationInfo info = write_animation(model, motion_of(run), a, o.path);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  std::printf("  wrote %s: %d frames of %d x %d at %g frames/s (%s) in %.2f s\n", o.path.c_str(),
              info.frames, info.width, info.height, info.fps, info.codec.c_str(), took.count());
}

}  // namespace mo2d::cli
