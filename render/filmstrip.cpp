// Contact sheet: tiles of one size and one view side by side, each a frame of the run; the scale
// bar and the axes only on the first tile.
#include <algorithm>
#include <cmath>

#include "canvas.hpp"
#include "mo2d/error.hpp"
#include "plan.hpp"

namespace mo2d {

namespace {

struct Sheet {
  int columns = 1, rows = 1, width = 0, height = 0;
  double gap = 0;  // pixels
  std::vector<int> samples{};
};

// The samples nearest evenly spaced values of the phase over the run's last cycle.
std::vector<int> phase_samples(const Motion& motion, const FilmstripOptions& o) {
  const auto N = static_cast<int>(motion.time.size());
  if (static_cast<int>(o.phase.size()) != N)
    throw Error("render: a filmstrip by phase needs one phase value per sample (" +
                    std::to_string(o.phase.size()) + " for " + std::to_string(N) + ")",
                "phase");
  if (!std::isfinite(o.cycle) || o.cycle <= 0)
    throw Error("render: the filmstrip's phase cycle must be finite and > 0", "cycle");
  const double end = o.phase.back(), dir = end >= o.phase.front() ? 1.0 : -1.0;
  const double start = end - dir * o.cycle;
  if (dir * (o.phase.front() - start) > 0)
    throw Error("render: the run covers " + std::to_string(std::abs(end - o.phase.front())) +
                    " of the phase, less than one cycle (" + std::to_string(o.cycle) +
                    "): no filmstrip by phase",
                "cycle");
  int k = N - 1;  // the last sample at or before the cycle's start
  while (k > 0 && dir * (o.phase[static_cast<size_t>(k)] - start) > 0) --k;
  std::vector<int> out;
  for (int j = 0; j < o.frames; ++j) {
    const double target = start + dir * o.cycle * j / o.frames;
    while (k + 1 < N && dir * (o.phase[static_cast<size_t>(k) + 1] - target) <= 0) ++k;
    const int best = k + 1 < N && std::abs(o.phase[static_cast<size_t>(k) + 1] - target) <
                                      std::abs(o.phase[static_cast<size_t>(k)] - target)
                         ? k + 1
                         : k;
    out.push_back(best);
  }
  return out;
}

Sheet layout(const Motion& motion, const FilmstripOptions& o) {
  if (o.frames < 1 && o.samples.empty())
    throw Error("render: a filmstrip needs at least one frame", "frames");
  if (o.columns < 0) throw Error("render: filmstrip columns must be >= 0", "columns");
  if (!std::isfinite(o.gap) || o.gap < 0) throw Error("render: filmstrip gap must be >= 0", "gap");
  const int N = static_cast<int>(motion.time.size());
  if (N == 0) throw Error("render: the run has no samples", "time");
  Sheet s;
  s.columns = o.columns == 0 ? o.frames : std::min(o.columns, o.frames);
  s.rows = (o.frames + s.columns - 1) / s.columns;
  if (!o.samples.empty()) {
    for (int k : o.samples) detail::check_sample(motion, k);
    s.samples = o.samples;
    s.columns = o.columns == 0 ? static_cast<int>(o.samples.size())
                               : std::min<int>(o.columns, static_cast<int>(o.samples.size()));
    s.rows = (static_cast<int>(o.samples.size()) + s.columns - 1) / s.columns;
  }
  if (o.samples.empty() && !o.phase.empty()) s.samples = phase_samples(motion, o);
  for (int f = 0; f < o.frames && o.samples.empty() && o.phase.empty(); ++f)
    s.samples.push_back(o.frames == 1 ? 0
                                      : static_cast<int>(std::lround(static_cast<double>(f) *
                                                                     (N - 1) / (o.frames - 1))));
  s.gap = o.gap * o.tile.dpi / 72.0;
  const double w = s.columns * o.tile.width + (s.columns - 1) * s.gap;
  const double h = s.rows * o.tile.height + (s.rows - 1) * s.gap;
  s.width = static_cast<int>(std::ceil(w));
  s.height = static_cast<int>(std::ceil(h));
  return s;
}

void draw_sheet(cairo_t* cr, const detail::FramePlan& plan, const Sheet& s,
                const FilmstripOptions& o) {
  detail::set_colour(cr, plan.options.style.background);
  cairo_paint(cr);
  for (size_t f = 0; f < s.samples.size(); ++f) {
    const int col = static_cast<int>(f) % s.columns, row = static_cast<int>(f) / s.columns;
    const double x = col * (o.tile.width + s.gap), y = row * (o.tile.height + s.gap);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    detail::draw_frame(cr, plan, s.samples[f], {true, f == 0, f == 0});
    if (o.tile_border) {
      const double lw = plan.P * 0.6;
      cairo_rectangle(cr, 0.5 * lw, 0.5 * lw, o.tile.width - lw, o.tile.height - lw);
      detail::set_colour(cr, rgb_hex(0xBBBBBB));
      cairo_set_line_width(cr, lw);
      cairo_stroke(cr);
    }
    cairo_restore(cr);
  }
  detail::check_status(cr, "drawing a filmstrip");
}

}  // namespace

Image render_filmstrip(const Model& model, const Motion& motion, const FilmstripOptions& options) {
  const detail::FramePlan plan = detail::make_plan(model, motion, options.tile);
  const Sheet s = layout(motion, options);
  detail::Canvas canvas(detail::Format::png, s.width, s.height, options.tile.dpi);
  draw_sheet(canvas.cr(), plan, s, options);
  return canvas.image();
}

void write_filmstrip(const Model& model, const Motion& motion, const FilmstripOptions& options,
                     const std::string& path) {
  const detail::Format f = detail::format_of(path);
  const detail::FramePlan plan = detail::make_plan(model, motion, options.tile);
  const Sheet s = layout(motion, options);
  detail::Canvas canvas(f, s.width, s.height, options.tile.dpi);
  draw_sheet(canvas.cr(), plan, s, options);
  detail::write_bytes(path, canvas.finish());
}

}  // namespace mo2d
