// Rendering from Python (mo2d/render.hpp): frames and filmstrips of a result, its standard plots,
// and plots of any series. The format follows the file's extension: .png, .svg or .pdf; every
// file is written atomically. The GIL is kept (a frame may evaluate the model's Python laws).
#include <pybind11/stl.h>

#include <utility>

#include "bindings.hpp"
#include "mo2d/error.hpp"
#include "mo2d/render.hpp"

namespace mo2d::py_bind {

namespace {

FrameOptions frame_options(const Result& r, int width, int height, bool labels, bool loads,
                           const std::vector<std::string>& traces) {
  FrameOptions f;
  f.contacts = r.scene_contacts;
  f.width = width;
  f.height = height;
  f.show_labels = labels;
  f.show_loads = loads;
  f.traces = traces;
  return f;
}

Plot standard_plot(const Result& r, const std::string& which) {
  if (which == "efforts") return efforts_plot(r.trajectory);
  if (which == "residuals") return residuals_plot(r.trajectory);
  if (which == "energies") return energies_plot(r.trajectory);
  throw Error("plot: 'efforts', 'residuals' or 'energies', not '" + which + "'", which);
}

using SeriesList = std::vector<std::tuple<std::string, std::vector<double>, std::vector<double>>>;

void write_series_plot(const std::string& path, const SeriesList& series, const std::string& title,
                       const std::string& xlabel, const std::string& ylabel, bool log_y, int width,
                       int height) {
  Plot p;
  p.title = title;
  p.x.label = xlabel;
  p.y.label = ylabel;
  p.y.log = log_y;
  p.width = width;
  p.height = height;
  for (const auto& [label, x, y] : series) p.series.push_back({.label = label, .x = x, .y = y});
  write_plot(p, path);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "write_frame",
      [](const Result& r, const std::string& path, int sample, int width, int height, bool labels,
         bool loads, const std::vector<std::string>& traces) {
        write_frame(*r.model, motion_of(r.trajectory), sample,
                    frame_options(r, width, height, labels, loads, traces), path);
      },
      py::arg("result"), py::arg("path"), py::arg("sample") = 0, py::arg("width") = 800,
      py::arg("height") = 600, py::arg("labels") = false, py::arg("loads") = false,
      py::arg("traces") = std::vector<std::string>{},
      "Draw one sample of a result to `path`, the format from its extension (.png, .svg or "
      ".pdf).\n\n"
      "sample: the sample's index; width, height: the image size (pixels); labels: name the "
      "bodies; loads: draw the applied forces and torques; traces: labels of points "
      "('link.P') whose paths over the run are drawn. Raises mo2d.Error for an unknown label or a "
      "file that "
      "cannot be written.\n\n"
      "Example::\n\n"
      "    mo2d.write_frame(r, 'frame.svg', sample=10, labels=True, traces=['link.P'])");
  m.def(
      "write_filmstrip",
      [](const Result& r, const std::string& path, int frames, int columns, bool labels,
         const std::vector<std::string>& traces) {
        FilmstripOptions o;
        o.frames = frames;
        o.columns = columns;
        o.tile.show_labels = labels;
        o.tile.traces = traces;
        o.tile.contacts = r.scene_contacts;
        write_filmstrip(*r.model, motion_of(r.trajectory), o, path);
      },
      py::arg("result"), py::arg("path"), py::arg("frames") = 6, py::arg("columns") = 3,
      py::arg("labels") = false, py::arg("traces") = std::vector<std::string>{},
      "Draw `frames` samples equally spaced over the run side by side, in rows of `columns`, "
      "to `path` (.png, .svg or .pdf); labels, traces: as in write_frame.\n\n"
      "Example::\n\n"
      "    mo2d.write_filmstrip(r, 'strip.png', frames=6, columns=3, traces=['coupler.B'])");
  m.def(
      "write_plot",
      [](const Result& r, const std::string& path, const std::string& which) {
        write_plot(standard_plot(r, which), path);
      },
      py::arg("result"), py::arg("path"), py::arg("which") = "efforts",
      "Draw the plot `mo2d render` draws to `path` (.png, .svg or .pdf): which = 'efforts', "
      "'residuals' or 'energies' (forward runs only). Raises mo2d.Error for another name.");
  m.def("write_series_plot", &write_series_plot, py::arg("path"), py::arg("series"),
        py::arg("title") = "", py::arg("xlabel") = "", py::arg("ylabel") = "",
        py::arg("log_y") = false, py::arg("width") = 800, py::arg("height") = 500,
        "Plot any data with the project's renderer to `path` (.png, .svg or .pdf): series = "
        "[(label, x, y)], x and y sequences of equal length; title, xlabel, ylabel: text; "
        "log_y: a logarithmic y axis; width, height: pixels.\n\n"
        "Example::\n\n"
        "    mo2d.write_series_plot('torque.svg', [('torque', r.t, r['pivot.torque'])],\n"
        "                           xlabel='time (s)', ylabel='torque (N m)')");
}

}  // namespace mo2d::py_bind
