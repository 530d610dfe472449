#pragma once
// The interactive viewer page of a run (target mo2d::view; docs/viewer.md): ONE self-contained
// HTML file, data and script inline, nothing fetched from the network, that plays the run
// (play/pause, a time scrubber, speed, zoom and pan), shows the values of a body or joint clicked,
// and plots chosen columns with a cursor that moves with the frame. The mechanism is drawn from
// the numbers of the Cairo frame (mo2d/render/drawing.hpp): at zoom 1 the page's joints land on
// the pixels of render_frame's joints for the same sample and FrameOptions.
//
// Budget: at most ViewerOptions::max_frames samples go into the page (every k-th sample and the
// last one); the page and ViewerPage::notes say how many of how many.
//
// The page's script API (window.mo2dViewer), for tests and for embedding: seek(t) (the nearest
// frame, paused; returns its time), seekFrame(i), frame(), time(), frames, times, play(), pause(),
// playing(), jointPositions() (name, kind and the pixel centre x, y on the canvas of every joint of
// the current frame, after zoom and pan), canvasRect(), setZoom(z), resetView(), select(name)
// (the info panel's text), errors (script errors caught on the page), firstFrameMs.
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// What the page shows.
struct ViewerOptions {
  // size of the drawing (pixels) and what it shows, as for render_frame (traces and loads are not
  // drawn on the page)
  FrameOptions frame{};
  // at most this many samples in the page (>= 2): every k-th sample, and the last
  int max_frames = 400;
  // columns plotted under the drawing, by their CSV labels (trajectory_csv_labels); empty: the
  // efforts of the run, or its first coordinate if it has no inputs
  std::vector<std::string> columns{};
  std::string title{};  // empty: the model's name and the kind of run
};

// The page and what went into it.
struct ViewerPage {
  std::string html{};  // the page
  int samples = 0;     // of the run
  int frames = 0;      // in the page
  int stride = 1;      // every stride-th sample (and the last)
  // e.g. "251 of 501 samples in the page (every 2nd and the last; at most 400)", a column not
  // finite at some time
  std::vector<std::string> notes{};
};

// Throws Error for an unknown column (naming the closest label), an empty run, max_frames < 2,
// and what render_frame throws for.
ViewerPage viewer_page(const Model& model, const Trajectory& run, const ViewerOptions& options);
// viewer_page(...) written to `path` atomically (mo2d/output.hpp: joins an OutputSet::Scope).
ViewerPage write_viewer_page(const Model& model, const Trajectory& run,
                             const ViewerOptions& options, const std::string& path);

// Every column of trajectory_csv(run), in its order: label and values (samples).
std::vector<std::pair<std::string, Eigen::VectorXd>> trajectory_columns(const Trajectory& run);

}  // namespace mo2d
