#pragma once
// Plots of time histories and of speed-against-error tables: several series in one plot, linear
// or logarithmic axes, ticks at round numbers (1-2-5 steps; decades on log axes), axis labels
// with units, legend, grid. PNG, SVG or PDF.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/render/image.hpp"

namespace mo2d {

// One line of a plot: its points and how it is drawn.
struct Series {
  // legend entry
  std::string label{};
  std::vector<double> x{}, y{};  // same size; non-finite points (and <= 0 on a log axis) are gaps
  std::optional<Rgb> colour{};   // default: okabe_ito()[index of the series]
  // a dashed line
  bool dashed = false;
  bool markers = false;  // a dot at every point (tables: speed against error)
};

// One axis of a plot: label, scale and range.
struct Axis {
  std::string label{};  // with its unit: "time (s)", "torque (N m)"
  // logarithmic scale (decades)
  bool log = false;
  std::optional<std::pair<double, double>> range{};  // default: the data, widened to round ticks
};

// A line plot (docs/rendering.md, "Plots"): title, axes, series, size and style.
struct Plot {
  // title above the plot area
  std::string title{};
  // horizontal and vertical axes
  Axis x{}, y{};
  // the lines, drawn in order
  std::vector<Series> series{};
  int width = 800, height = 500;  // pixels
  // pixels per inch (sizes in points are converted with it)
  double dpi = 96;
  double font_size = 9;     // points
  double line_width = 1.4;  // points
  // a legend of the labelled series (in the corner that hides the fewest points)
  bool legend = true;
  // light grid lines at the ticks
  bool grid = true;
  // font family of the text
  std::string font = "DejaVu Sans";
};

// Where the data go: the plot area in pixels and the axis ranges (log axes: in data units).
struct PlotLayout {
  double left = 0, top = 0, right = 0, bottom = 0;  // plot area (pixels)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;            // axis ranges
  // whether each axis is logarithmic
  bool log_x = false, log_y = false;
};
// Throws Error for a plot without plottable points (unless both axis ranges are given: then the
// axes are drawn empty), mismatched x/y sizes, a bad size or range.
PlotLayout plot_layout(const Plot& plot);
// The pixel (x right, y down) of data point (x, y).
Eigen::Vector2d to_pixel(const PlotLayout& layout, double x, double y);

// Round tick values in [lo, hi] with a step of 1, 2 or 5 times a power of ten, about `target` of
// them. Decades (powers of ten) for a log axis.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);
std::vector<double> decade_ticks(double lo, double hi);

// The plot as an image in memory.
Image render_plot(const Plot& plot);
// .png, .svg or .pdf by extension (atomic write).
void write_plot(const Plot& plot, const std::string& path);

}  // namespace mo2d
