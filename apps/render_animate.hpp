#pragma once
// `mo2d render SCENE --animate out.webm|.mp4|.gif|.apng` (render_animate.cpp): the options and
// the animation of a solved run (mo2d/render/animate.hpp).
#include <CLI/CLI.hpp>
#include <string>

#include "mo2d/model.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/render/run.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::cli {

struct AnimateCliOptions {
  std::string path{};  // empty: no animation
  double fps = 30, slow = 1;
  std::string plot{};  // a column of the run's CSV drawn in a strip below the frames
  int max_frames = 3000;
  int width = 800, height = 600;
  int threads = 0;  // 0: the cores
  // the filmstrip's tiles at evenly spaced values of this coordinate over its last cycle
  std::string phase{}, cycle{};
};

void add_animate_options(CLI::App* sub, AnimateCliOptions& o);
// Writes the animation of `run` (what each frame shows: `frame`, less its size) and prints it.
// --filmstrip-phase COORD --filmstrip-cycle C: the tiles of job's filmstrip by phase.
void set_filmstrip_phase(const Trajectory& run, const AnimateCliOptions& o, RenderJob& job);
void write_run_animation(const Model& model, const Trajectory& run, const FrameOptions& frame,
                         const AnimateCliOptions& o);

}  // namespace mo2d::cli
