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

FrameOptions frame_options(int width, int height, bool labels, bool loads,
                           const std::vector<std::string>& traces) {
  FrameOptions f;
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
                    frame_options(width, height, labels, loads, traces), path);
      },
      py::arg("result"), py::arg("path"), py::arg("sample") = 0, py::arg("width") = 800,
      py::arg("height") = 600, py::arg("labels") = false, py::arg("loads") = false,
      py::arg("traces") = std::vector<std::string>{},
      "one sample of a result drawn to PATH (.png, .svg or .pdf)");
  m.def(
      "write_filmstrip",
      [](const Result& r, const std::string& path, int frames, int columns, bool labels,
         const std::vector<std::string>& traces) {
        FilmstripOptions o;
        o.frames = frames;
        o.columns = columns;
        o.tile.show_labels = labels;
        o.tile.traces = traces;
        write_filmstrip(*r.model, motion_of(r.trajectory), o, path);
      },
      py::arg("result"), py::arg("path"), py::arg("frames") = 6, py::arg("columns") = 3,
      py::arg("labels") = false, py::arg("traces") = std::vector<std::string>{},
      "frames equally spaced over the run, side by side, to PATH (.png, .svg or .pdf)");
  m.def(
      "write_plot",
      [](const Result& r, const std::string& path, const std::string& which) {
        write_plot(standard_plot(r, which), path);
      },
      py::arg("result"), py::arg("path"), py::arg("which") = "efforts",
      "the plot `mo2d render` draws: 'efforts', 'residuals' or 'energies' (forward runs)");
  m.def("write_series_plot", &write_series_plot, py::arg("path"), py::arg("series"),
        py::arg("title") = "", py::arg("xlabel") = "", py::arg("ylabel") = "",
        py::arg("log_y") = false, py::arg("width") = 800, py::arg("height") = 500,
        "series: [(label, x, y)]: the project's renderer on any data");
}

}  // namespace mo2d::py_bind
