// Line plots: axis ranges from the data widened to round ticks (or given), plot area sized from
// the text, grid, ticks, labels, series clipped to the plot area, legend in the emptiest corner.
#include "mo2d/render/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "canvas.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

bool plottable(double x, double y, bool log_x, bool log_y) {
  return std::isfinite(x) && std::isfinite(y) && (!log_x || x > 0) && (!log_y || y > 0);
}

// Data range of one axis, widened to round ticks (linear) or whole decades (log).
std::pair<double, double> axis_range(const Axis& a, double lo, double hi, const char* which) {
  if (a.range) {
    const auto [r0, r1] = *a.range;
    if (!std::isfinite(r0) || !std::isfinite(r1) || !(r1 > r0) || (a.log && !(r0 > 0)))
      throw Error(std::string("render: the ") + which + " axis range [" + std::to_string(r0) +
                      ", " + std::to_string(r1) + "] must be finite, increasing" +
                      (a.log ? " and positive (log axis)" : ""),
                  which);
    return {r0, r1};
  }
  if (a.log) {
    double k0 = std::floor(std::log10(lo) + 1e-9), k1 = std::ceil(std::log10(hi) - 1e-9);
    if (k1 <= k0) k0 -= 1, k1 += 1;
    return {std::pow(10.0, k0), std::pow(10.0, k1)};
  }
  if (!(hi > lo)) {
    const double d = std::max(std::abs(lo) * 0.1, 1.0);
    lo -= d, hi += d;
  }
  const std::vector<double> t = nice_ticks(lo, hi, 5);
  const double step = t.size() >= 2 ? t[1] - t[0] : hi - lo;
  return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step};
}

std::string tick_label(double v, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s.find_first_not_of("-0.") == std::string::npos) return "0";
  if (s[0] == '-') s = "\u2212" + s.substr(1);
  return s;
}

struct Fonts {
  cairo_t* cr;
  const Plot& p;
  double P;
  void set(double scale, bool bold = false, bool italic = false) const {
    detail::select_font(cr, p.font, italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                        bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, scale * p.font_size * P);
  }
};

// "10" with a raised exponent; returns its width. ax: anchor as in draw_text.
double power_of_ten(cairo_t* cr, const Fonts& f, int k, double x, double y, double ax, double ay,
                    bool draw) {
  const std::string e = k < 0 ? "\u2212" + std::to_string(-k) : std::to_string(k);
  f.set(0.9);
  const double w10 = detail::text_width(cr, "10");
  f.set(0.65);
  const double we = detail::text_width(cr, e);
  const double w = w10 + we;
  if (draw) {
    const double x0 = x - ax * w;
    f.set(0.9);
    detail::draw_text(cr, "10", x0, y, 0, ay);
    f.set(0.65);
    detail::draw_text(cr, e, x0 + w10, y - 0.45 * f.p.font_size * f.P, 0, ay);
  }
  return w;
}

std::vector<double> ticks_of(bool log, double lo, double hi) {
  return log ? decade_ticks(lo, hi) : nice_ticks(lo, hi, 6);
}

struct Measured {
  PlotLayout layout;
  std::vector<double> xt, yt;
};

Measured measure(cairo_t* cr, const Plot& plot) {
  detail::check_size(plot.width, plot.height, plot.dpi, "plot");
  if (!std::isfinite(plot.font_size) || plot.font_size <= 0 || !std::isfinite(plot.line_width) ||
      plot.line_width < 0)
    throw Error("render: plot font size and line width must be finite and positive", "plot");
  if (plot.series.empty()) throw Error("render: the plot has no series", "series");
  const bool lx = plot.x.log, ly = plot.y.log;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : plot.series) {
    if (s.x.size() != s.y.size())
      throw Error("render: series '" + s.label + "' has " + std::to_string(s.x.size()) +
                      " x values and " + std::to_string(s.y.size()) + " y values",
                  s.label);
    for (size_t i = 0; i < s.x.size(); ++i)
      if (plottable(s.x[i], s.y[i], lx, ly)) {
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
      }
  }
  if (!(x0 <= x1) && plot.x.range && plot.y.range) x0 = x1 = y0 = y1 = 1;  // empty axes
  if (!(x0 <= x1))
    throw Error(std::string("render: the plot has no point to draw (all empty, non-finite") +
                    (lx || ly ? " or not positive on a log axis)" : ")"),
                "series");
  Measured m;
  PlotLayout& L = m.layout;
  L.log_x = lx;
  L.log_y = ly;
  std::tie(L.x0, L.x1) = axis_range(plot.x, x0, x1, "x");
  std::tie(L.y0, L.y1) = axis_range(plot.y, y0, y1, "y");
  m.xt = ticks_of(lx, L.x0, L.x1);
  m.yt = ticks_of(ly, L.y0, L.y1);

  const double P = plot.dpi / 72.0, fs = plot.font_size * P, pad = 6 * P, tick = 3.5 * P;
  Fonts f{cr, plot, P};
  double ylab = 0;
  for (double v : m.yt) {
    if (ly) {
      ylab = std::max(ylab, power_of_ten(cr, f, static_cast<int>(std::lround(std::log10(v))), 0, 0,
                                         0, 0, false));
    } else {
      f.set(0.9);
      const double step = m.yt.size() >= 2 ? m.yt[1] - m.yt[0] : 1;
      ylab = std::max(ylab, detail::text_width(cr, tick_label(v, step)));
    }
  }
  double last_x = 0;
  if (!m.xt.empty()) {
    f.set(0.9);
    last_x = lx ? 2 * fs
                : detail::text_width(
                      cr, tick_label(m.xt.back(), m.xt.size() >= 2 ? m.xt[1] - m.xt[0] : 1));
  }
  L.left = pad + (plot.y.label.empty() ? 0 : 1.4 * fs) + ylab + tick + 3 * P;
  L.right = plot.width - pad - std::max(0.5 * last_x, 2 * P);
  L.top = pad + (plot.title.empty() ? 0.4 * fs : 1.8 * fs);
  L.bottom = plot.height - pad - (plot.x.label.empty() ? 0 : 1.5 * fs) - 1.2 * fs - tick - 2 * P;
  if (L.right - L.left < 10 || L.bottom - L.top < 10)
    throw Error("render: plot of " + std::to_string(plot.width) + " x " +
                    std::to_string(plot.height) + " pixels is too small for its labels",
                "size");
  return m;
}

void draw_plot(cairo_t* cr, const Plot& plot, const Measured& m) {
  const PlotLayout& L = m.layout;
  const double P = plot.dpi / 72.0, fs = plot.font_size * P, tick = 3.5 * P;
  const Rgb ink = rgb_hex(0x222222), grid = rgb_hex(0xE3E3E3), minor = rgb_hex(0xF1F1F1);
  Fonts f{cr, plot, P};
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);

  auto X = [&](double x) { return to_pixel(L, x, L.y0).x(); };
  auto Y = [&](double y) { return to_pixel(L, L.x0, y).y(); };
  auto line = [&](double ax, double ay, double bx, double by) {
    cairo_move_to(cr, ax, ay);
    cairo_line_to(cr, bx, by);
  };
  // grid: minor decades (2..9) on log axes, then the major ticks
  if (plot.grid) {
    cairo_set_line_width(cr, 0.6 * P);
    auto minors = [&](bool log, double lo, double hi, auto&& draw) {
      if (!log || std::log10(hi / lo) > 6) return;
      for (double d = std::pow(10.0, std::floor(std::log10(lo))); d < hi; d *= 10)
        for (int k = 2; k <= 9; ++k)
          if (k * d > lo && k * d < hi) draw(k * d);
    };
    detail::set_colour(cr, minor);
    minors(L.log_x, L.x0, L.x1, [&](double v) { line(X(v), L.top, X(v), L.bottom); });
    minors(L.log_y, L.y0, L.y1, [&](double v) { line(L.left, Y(v), L.right, Y(v)); });
    cairo_stroke(cr);
    detail::set_colour(cr, grid);
    for (double v : m.xt) line(X(v), L.top, X(v), L.bottom);
    for (double v : m.yt) line(L.left, Y(v), L.right, Y(v));
    cairo_stroke(cr);
  }
  // axes box, ticks, tick labels
  detail::set_colour(cr, ink);
  cairo_set_line_width(cr, 0.8 * P);
  cairo_rectangle(cr, L.left, L.top, L.right - L.left, L.bottom - L.top);
  for (double v : m.xt) line(X(v), L.bottom, X(v), L.bottom + tick);
  for (double v : m.yt) line(L.left - tick, Y(v), L.left, Y(v));
  cairo_stroke(cr);
  const double xstep = m.xt.size() >= 2 ? m.xt[1] - m.xt[0] : 1;
  const double ystep = m.yt.size() >= 2 ? m.yt[1] - m.yt[0] : 1;
  for (double v : m.xt) {
    if (L.log_x) {
      power_of_ten(cr, f, static_cast<int>(std::lround(std::log10(v))), X(v),
                   L.bottom + tick + 2 * P + 0.5 * fs, 0.5, 0, true);
    } else {
      f.set(0.9);
      detail::draw_text(cr, tick_label(v, xstep), X(v), L.bottom + tick + 2 * P, 0.5, 0);
    }
  }
  for (double v : m.yt) {
    if (L.log_y) {
      power_of_ten(cr, f, static_cast<int>(std::lround(std::log10(v))), L.left - tick - 3 * P, Y(v),
                   1, 0.5, true);
    } else {
      f.set(0.9);
      detail::draw_text(cr, tick_label(v, ystep), L.left - tick - 3 * P, Y(v), 1, 0.5);
    }
  }
  // axis labels and title
  f.set(1.0);
  if (!plot.x.label.empty())
    detail::draw_text(cr, plot.x.label, 0.5 * (L.left + L.right), plot.height - 6 * P, 0.5, 1);
  if (!plot.y.label.empty()) {
    cairo_save(cr);
    cairo_translate(cr, 6 * P, 0.5 * (L.top + L.bottom));
    cairo_rotate(cr, -std::acos(0.0));
    detail::draw_text(cr, plot.y.label, 0, 0, 0.5, 0);
    cairo_restore(cr);
  }
  if (!plot.title.empty()) {
    f.set(1.1, true);
    detail::draw_text(cr, plot.title, 0.5 * (L.left + L.right), 6 * P, 0.5, 0);
  }
  // series, clipped to the plot area
  std::vector<Rgb> colours;
  for (size_t i = 0; i < plot.series.size(); ++i)
    colours.push_back(plot.series[i].colour.value_or(okabe_ito()[i % okabe_ito().size()]));
  cairo_save(cr);
  cairo_rectangle(cr, L.left, L.top, L.right - L.left, L.bottom - L.top);
  cairo_clip(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    bool open = false;
    for (size_t j = 0; j < s.x.size(); ++j) {
      if (!plottable(s.x[j], s.y[j], L.log_x, L.log_y)) {
        open = false;
        continue;
      }
      const Eigen::Vector2d q = to_pixel(L, s.x[j], s.y[j]);
      open ? cairo_line_to(cr, q.x(), q.y()) : cairo_move_to(cr, q.x(), q.y());
      open = true;
    }
    const double dash[] = {4.5 * P, 2.5 * P};
    cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0);
    detail::set_colour(cr, colours[i]);
    cairo_set_line_width(cr, plot.line_width * P);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    if (s.markers)
      for (size_t j = 0; j < s.x.size(); ++j)
        if (plottable(s.x[j], s.y[j], L.log_x, L.log_y)) {
          const Eigen::Vector2d q = to_pixel(L, s.x[j], s.y[j]);
          cairo_new_sub_path(cr);
          cairo_arc(cr, q.x(), q.y(), 2.2 * P, 0, 4 * std::acos(0.0));
          cairo_fill(cr);
        }
  }
  cairo_restore(cr);
  // legend in the corner of the plot area that covers the fewest points
  bool any_label = false;
  for (const Series& s : plot.series) any_label |= !s.label.empty();
  if (!plot.legend || !any_label) return;
  f.set(0.9);
  double tw = 0;
  int rows = 0;
  for (const Series& s : plot.series)
    if (!s.label.empty()) tw = std::max(tw, detail::text_width(cr, s.label)), ++rows;
  const double row_h = 1.45 * 0.9 * fs, sample = 16 * P, inner = 5 * P;
  const double bw = inner * 3 + sample + tw, bh = rows * row_h + inner;
  const double gap = 6 * P;
  const double cx[2] = {L.right - gap - bw, L.left + gap},
               cy[2] = {L.top + gap, L.bottom - gap - bh};
  double best_x = cx[0], best_y = cy[0];
  size_t best = std::numeric_limits<size_t>::max();
  for (double by : cy)
    for (double bx : cx) {
      size_t inside = 0;
      for (const Series& s : plot.series)
        for (size_t j = 0; j < s.x.size(); ++j)
          if (plottable(s.x[j], s.y[j], L.log_x, L.log_y)) {
            const Eigen::Vector2d q = to_pixel(L, s.x[j], s.y[j]);
            inside += q.x() >= bx && q.x() <= bx + bw && q.y() >= by && q.y() <= by + bh;
          }
      if (inside < best) best = inside, best_x = bx, best_y = by;
    }
  cairo_rectangle(cr, best_x, best_y, bw, bh);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.88);
  cairo_fill_preserve(cr);
  detail::set_colour(cr, rgb_hex(0xBBBBBB));
  cairo_set_line_width(cr, 0.6 * P);
  cairo_stroke(cr);
  int r = 0;
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    if (s.label.empty()) continue;
    const double y = best_y + inner * 0.5 + (r++ + 0.5) * row_h;
    const double dash[] = {4.5 * P, 2.5 * P};
    cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0);
    detail::set_colour(cr, colours[i]);
    cairo_set_line_width(cr, plot.line_width * P);
    line(best_x + inner, y, best_x + inner + sample, y);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    detail::set_colour(cr, ink);
    detail::draw_text(cr, s.label, best_x + 2 * inner + sample, y, 0, 0.5);
  }
}

}  // namespace

Eigen::Vector2d to_pixel(const PlotLayout& L, double x, double y) {
  auto t = [](bool log, double v, double a, double b) {
    return log ? (std::log10(v) - std::log10(a)) / (std::log10(b) - std::log10(a))
               : (v - a) / (b - a);
  };
  return {L.left + t(L.log_x, x, L.x0, L.x1) * (L.right - L.left),
          L.bottom - t(L.log_y, y, L.y0, L.y1) * (L.bottom - L.top)};
}

PlotLayout plot_layout(const Plot& plot) {
  detail::check_size(plot.width, plot.height, plot.dpi, "plot");
  detail::Canvas scratch(detail::Format::png, 1, 1, plot.dpi);
  return measure(scratch.cr(), plot).layout;
}

Image render_plot(const Plot& plot) {
  detail::check_size(plot.width, plot.height, plot.dpi, "plot");
  detail::Canvas canvas(detail::Format::png, plot.width, plot.height, plot.dpi);
  const Measured m = measure(canvas.cr(), plot);
  draw_plot(canvas.cr(), plot, m);
  detail::check_status(canvas.cr(), "drawing a plot");
  return canvas.image();
}

void write_plot(const Plot& plot, const std::string& path) {
  const detail::Format fmt = detail::format_of(path);
  detail::check_size(plot.width, plot.height, plot.dpi, "plot");
  detail::Canvas canvas(fmt, plot.width, plot.height, plot.dpi);
  const Measured m = measure(canvas.cr(), plot);
  draw_plot(canvas.cr(), plot, m);
  detail::write_bytes(path, canvas.finish());
}

}  // namespace mo2d
