// The viewer page and pictures in notebooks (mo2d/view.hpp, mo2d/render/drawing.hpp): a Result
// displays as the viewer page (Result._repr_html_: the page in an iframe's srcdoc, so that its
// script runs apart from the notebook's), writes it (Result.write_viewer); a System and a Model
// display as the drawing of their initial configuration (_repr_svg_). The GIL is kept (a drawing
// may evaluate the model's Python laws).
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mo2d/render/animate.hpp"
#include "mo2d/render/drawing.hpp"
#include "mo2d/view.hpp"

namespace mo2d::py_bind {

namespace {

ViewerOptions viewer_options(const Result& r, int max_frames,
                             const std::vector<std::string>& columns, int width, int height) {
  ViewerOptions o;
  o.frame.contacts = r.scene_contacts;  // a scene's contacts, drawn as in its frames
  o.max_frames = max_frames;
  o.columns = columns;
  o.frame.width = width;
  o.frame.height = height;
  return o;
}

// The page in an iframe's srcdoc: the attribute's text escaped (& and ").
std::string iframe(const std::string& page, int width, int height) {
  std::string srcdoc;
  srcdoc.reserve(page.size() + page.size() / 16);
  for (const char c : page) {
    if (c == '&')
      srcdoc += "&amp;";
    else if (c == '"')
      srcdoc += "&quot;";
    else
      srcdoc += c;
  }
  return "<iframe style=\"border:0\" width=\"" + std::to_string(width + 360) + "\" height=\"" +
         std::to_string(height + 420) + "\" sandbox=\"allow-scripts\" srcdoc=\"" + srcdoc +
         "\"></iframe>";
}

// Result.animate's timing and size, and what its frames show (mo2d render --animate's flags).
struct AnimationTiming {
  double fps, slow;
  int max_frames, width, height, threads;
};
struct AnimationContent {
  bool loads, labels;
  std::vector<std::string> traces;
  std::string plot;  // empty: no plot strip
};

py::dict animate(const Result& r, const std::string& path, const AnimationTiming& t,
                 const AnimationContent& c) {
  AnimationOptions a;
  a.frame.width = t.width;
  a.frame.height = t.height;
  a.frame.show_loads = c.loads;
  a.frame.show_labels = c.labels;
  a.frame.traces = c.traces;
  a.frame.contacts = r.scene_contacts;
  a.fps = t.fps;
  a.slow = t.slow;
  a.max_frames = t.max_frames;
  a.threads = t.threads;
  if (!c.plot.empty()) {
    a.plot = true;
    a.strip = animation_plot(*r.model, r.trajectory, c.plot);
  }
  const AnimationInfo info = write_animation(*r.model, motion_of(r.trajectory), a, path);
  py::dict d;
  d["frames"] = info.frames;
  d["width"] = info.width;
  d["height"] = info.height;
  d["fps"] = info.fps;
  d["codec"] = info.codec;
  return d;
}

std::string model_svg(const Model& m) {
  FrameOptions o;
  o.width = 480;
  o.height = 360;
  return frame_svg(m, single_configuration(m.q0), 0, o);
}

}  // namespace

void bind_view(py::module_& m) {
  py::class_<Result> result(m.attr("Result"));
  result
      .def(
          "viewer_html",
          [](const Result& r, int max_frames, const std::vector<std::string>& columns, int width,
             int height) {
            return viewer_page(*r.model, r.trajectory,
                               viewer_options(r, max_frames, columns, width, height))
                .html;
          },
          py::arg("max_frames") = 400, py::arg("columns") = std::vector<std::string>{},
          py::arg("width") = 800, py::arg("height") = 600,
          "The run's viewer page (as `mo2d view` writes it): one self-contained HTML text that "
          "plays the run, with play/pause, a time scrubber, zoom and pan, the values of a body "
          "or joint clicked, and plots of `columns` (CSV labels; default the efforts). At most "
          "max_frames samples go in (every k-th and the last). Raises mo2d.Error for an "
          "unknown column.")
      .def(
          "write_viewer",
          [](const Result& r, const std::string& path, int max_frames,
             const std::vector<std::string>& columns, int width, int height) {
            write_viewer_page(*r.model, r.trajectory,
                              viewer_options(r, max_frames, columns, width, height), path);
          },
          py::arg("path"), py::arg("max_frames") = 400,
          py::arg("columns") = std::vector<std::string>{}, py::arg("width") = 800,
          py::arg("height") = 600,
          "Write the run's viewer page (viewer_html) to `path`, atomically: one HTML file that "
          "opens in any browser, nothing fetched from the network.")
      .def(
          "animate",
          [](const Result& r, const std::string& path, double fps, double slow, int max_frames,
             int width, int height, int threads, bool loads, const std::vector<std::string>& traces,
             bool labels, const std::string& plot) {
            return animate(r, path, {fps, slow, max_frames, width, height, threads},
                           {loads, labels, traces, plot});
          },
          py::arg("path"), py::arg("fps") = 30.0, py::arg("slow") = 1.0,
          py::arg("max_frames") = 3000, py::arg("width") = 800, py::arg("height") = 600,
          py::arg("threads") = 0, py::arg("loads") = false,
          py::arg("traces") = std::vector<std::string>{}, py::arg("labels") = false,
          py::arg("plot") = std::string(),
          "Write the run as an animation, as `mo2d render --animate` does: .webm (VP9), .mp4 "
          "(H.264), .gif or .apng by the extension of `path`, frame i at t0 + i / (fps * slow), "
          "written atomically. loads: draw the applied forces (arrows) and torques (arcs), "
          "scaled by their peak over the run (--loads); traces: points whose paths are drawn, "
          "as in write_frame (--trace); labels: the bodies' names (--labels); plot: a column of "
          "the run (a CSV label, e.g. 'crank_pivot.torque') drawn in a strip below the frames "
          "with a cursor at the frame's time, a third of the frame's height (--plot). Returns a "
          "dict with 'frames', 'width', 'height', 'fps' and 'codec'. Raises mo2d.Error without "
          "FFmpeg's libraries (naming the packages), for an unknown extension, trace or column, "
          "or more than max_frames frames.")
      .def(
          "_repr_html_",
          [](const Result& r) {
            const ViewerOptions o = viewer_options(r, 400, {}, 800, 600);
            return iframe(viewer_page(*r.model, r.trajectory, o).html, o.frame.width,
                          o.frame.height);
          },
          "The viewer page in an iframe: how a notebook (Jupyter) shows a Result.");
  py::class_<System, std::shared_ptr<System>> system(m.attr("System"));
  system.def(
      "_repr_svg_", [](const System& s) { return model_svg(build_model(s)); },
      "The drawing of the system's initial configuration as SVG (build_model, then the frame "
      "of its assembled q0): how a notebook shows a System. Raises mo2d.Error as build_model "
      "does.");
  py::class_<Model, std::shared_ptr<Model>> model(m.attr("Model"));
  model.def(
      "_repr_svg_", [](const Model& x) { return model_svg(x); },
      "The drawing of the model's initial configuration (q0) as SVG: how a notebook shows a "
      "Model.");
}

}  // namespace mo2d::py_bind
