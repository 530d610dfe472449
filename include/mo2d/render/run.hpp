#pragma once
// One call per kind of run for the command-line tool: frames, a filmstrip, plots and (optionally)
// a video of an inverse- or forward-dynamics result, written under one folder.
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/render/plot.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// What render_run() draws and where (the `mo2d render` command's settings).
struct RenderJob {
  std::string dir = "out";     // created if missing
  std::string name = "run";    // file name prefix
  std::string format = "png";  // filmstrip and plots: png, svg or pdf (frames are always PNG)
  bool frames = false;         // DIR/NAME_0001.png ... every `every` samples
  // frame stride, in samples
  int every = 10;
  bool filmstrip = true;  // DIR/NAME_filmstrip.FORMAT
  // tiles and size of the filmstrip
  FilmstripOptions filmstrip_options{};
  bool plots = true;   // inverse: efforts, residuals; forward: energies, residuals
  bool video = false;  // DIR/NAME.mp4 from the frames, only if ffmpeg is on PATH
  // frames per second of the video
  double fps = 25;
  FrameOptions frame{};  // frames (and the video)
  // size of the plots (pixels) and their resolution (dpi)
  int plot_width = 800, plot_height = 450;
  double plot_dpi = 96;
};

// The paths render_run() wrote.
struct RenderOutputs {
  // DIR/NAME_0001.png, ... in order
  std::vector<std::string> frames{};
  // the filmstrip's path (empty: none)
  std::string filmstrip{};
  // the plots' paths
  std::vector<std::string> plots{};
  std::string video{};               // empty if not asked for or ffmpeg is missing
  std::vector<std::string> notes{};  // e.g. "ffmpeg not found: no video"
};

// Frames (with the effort symbols of an inverse run), filmstrip (traces, if any, show the
// trajectory) and plots. An inverse run: DIR/NAME_efforts.FORMAT (every input against time, torques
// and forces in their units; when the mechanism has inputs) and DIR/NAME_residuals.FORMAT
// (position, velocity and acceleration residuals, log scale). A forward run:
// DIR/NAME_energies.FORMAT (kinetic, potential, input work, dissipated, balance) and
// DIR/NAME_residuals.FORMAT (position and velocity residuals). Returns the paths written.
RenderOutputs render_run(const Model& model, const Trajectory& result, const RenderJob& job);

// The plots on their own (used by render_run). energies_plot: a forward run (Error otherwise).
Plot efforts_plot(const Trajectory& result);
Plot residuals_plot(const Trajectory& result);
Plot energies_plot(const Trajectory& result);

// An MP4 (H.264) from DIR/NAME_%04d.png with ffmpeg. Returns false (and writes nothing) if
// ffmpeg is not on PATH; throws Error if ffmpeg fails.
bool encode_video(const std::string& dir, const std::string& name, double fps,
                  const std::string& path);

}  // namespace mo2d
