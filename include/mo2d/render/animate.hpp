#pragma once
// Animations of a run: the frames of render_frame() at evenly spaced times, encoded by FFmpeg's
// libavcodec / libavformat into a WebM (VP9), MP4 (H.264 with libx264, else MPEG-4 part 2), GIF or
// APNG file (docs/rendering.md, "Animations").
//
// Timing: frame i shows the run at t0 + i / (fps * slow) (slow = 1: real time; 4: four times
// slower); the run's samples are interpolated linearly in time between the two samples around
// (time, q0, q1, efforts: a frame at a sample's time is that sample exactly). The view, the
// effort and load scales (one per effort and per load: its peak over the whole run) are those of
// the run's still frames, so frame i is pixel for pixel render_frame() of the same time.
// An optional plot strip below the mechanism shows one column against time with a cursor at the
// frame's time.
//
// mo2d_render links FFmpeg only when CMake found it (libavcodec-dev, libavformat-dev,
// libswscale-dev, libavutil-dev): otherwise animation_support() says why and write_animation()
// throws an Error naming the missing packages.
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/render/image.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// A column drawn in a strip below the frames, with a cursor at the frame's time.
struct AnimationPlot {
  std::string label{};           // axis label with its unit: "crank.torque (N·m)"
  std::vector<double> values{};  // one per sample of the Motion
  int height = 0;                // pixels; 0: a third of the frame's height
};

// The strip of the column `label` of a run (a CSV label: a coordinate, rate, effort, reaction or
// added output, e.g. "crank.torque"), its unit in the axis label ("crank.torque (N·m)"). Error
// for an unknown label, naming it and the run's columns.
AnimationPlot animation_plot(const Model& model, const Trajectory& run, const std::string& label);

// What an animation shows, its frame rate, speed and budget.
struct AnimationOptions {
  // size, what each frame shows (traces, loads, labels, ...); sizes are rounded up to even for
  // WebM and MP4 (4:2:0 video)
  FrameOptions frame{};
  double fps = 30;  // frames per second of the file
  double slow = 1;  // playback is this many times slower than the run (1: real time)
  // the most frames written (an Error names the limit and the frames asked for)
  int max_frames = 3000;
  bool plot = false;  // draw `strip` below the frames
  // the column drawn below the frames when `plot` is set
  AnimationPlot strip{};
  int threads = 0;  // threads drawing frames; 0: std::thread::hardware_concurrency()
};

// What write_animation() wrote.
struct AnimationInfo {
  // frames written
  int frames = 0;
  int width = 0, height = 0;  // pixels of the encoded frames
  // frames per second of the file
  double fps = 0;
  std::string codec{};  // FFmpeg's name of the encoder: libvpx-vp9, libx264, mpeg4, gif, apng
};

// "" when animations can be written, else why not (the missing packages).
std::string animation_support();

// The times of the frames: t0 + i / (fps * slow) up to the run's last time. Error for fps or slow
// not finite and positive, an empty run, or more than max_frames frames (naming the limit).
std::vector<double> animation_times(const Motion& motion, const AnimationOptions& options);

// Frame i as it is encoded (before the colour conversion of the codec), for tests and stills.
Image render_animation_frame(const Model& model, const Motion& motion,
                             const AnimationOptions& options, int frame);

// The animation written to `path`: .webm, .mp4, .gif or .apng by extension. The file is encoded
// in memory and written atomically (write_file_atomically: an OutputSet when one is active): an
// error or an interruption leaves no file. Error: no FFmpeg, unknown extension, too many frames,
// a plot strip whose values are not one per sample, an encoder failure.
AnimationInfo write_animation(const Model& model, const Motion& motion,
                              const AnimationOptions& options, const std::string& path);

}  // namespace mo2d
