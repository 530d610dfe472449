// Animations (mo2d/render/animate.hpp): the run resampled at the frame times, drawn with the
// still frames' plan (same view, same effort and load scales), a plot strip with a moving cursor,
// frames drawn by a few threads while the previous batch is encoded (encoder.hpp).
#include "mo2d/render/animate.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <thread>

#include "canvas.hpp"
#include "encoder.hpp"
#include "mo2d/error.hpp"
#include "mo2d/render/plot.hpp"
#include "plan.hpp"

namespace mo2d {

namespace {

// The motion at the given times, interpolated linearly between the samples around each time.
Motion resample(const Motion& m, const std::vector<double>& times) {
  const auto n = static_cast<Eigen::Index>(times.size());
  const Eigen::Index N = m.time.size();
  Motion r;
  r.time.resize(n);
  r.q0.resize(n, m.q0.cols());
  r.efforts.resize(m.efforts.cols() ? n : 0, m.efforts.cols());
  r.q1.resize(m.q1.cols() ? n : 0, m.q1.cols());
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = times[static_cast<size_t>(i)];
    while (k + 1 < N - 1 && m.time[k + 1] <= t) ++k;
    const Eigen::Index k1 = std::min(k + 1, N - 1);
    const double span = m.time[k1] - m.time[k];
    const double w = span > 0 ? std::clamp((t - m.time[k]) / span, 0.0, 1.0) : 0.0;
    auto lerp = [&](const Eigen::MatrixXd& M, Eigen::MatrixXd& out) {
      if (M.cols() == 0) return;
      out.row(i) = w == 0 ? Eigen::RowVectorXd(M.row(k))
                          : Eigen::RowVectorXd((1 - w) * M.row(k) + w * M.row(k1));
    };
    r.time[i] = t;
    lerp(m.q0, r.q0);
    lerp(m.efforts, r.efforts);
    lerp(m.q1, r.q1);
  }
  return r;
}

double value_at(const Motion& m, const std::vector<double>& v, double t) {
  const Eigen::Index N = m.time.size();
  if (N == 1) return v[0];
  const auto* it = std::upper_bound(m.time.data(), m.time.data() + N, t);
  const Eigen::Index k1 = std::clamp<Eigen::Index>(it - m.time.data(), 1, N - 1);
  const Eigen::Index k = k1 - 1;
  const double span = m.time[k1] - m.time[k];
  const double w = span > 0 ? std::clamp((t - m.time[k]) / span, 0.0, 1.0) : 0.0;
  return (1 - w) * v[static_cast<size_t>(k)] + w * v[static_cast<size_t>(k1)];
}

// Everything the frames of an animation share.
struct Animation {
  const Motion* original = nullptr;
  std::vector<double> times{};
  Motion sampled{};
  detail::FramePlan plan{};
  int width = 0, height = 0;  // of the encoded frames (frame + strip, rounded up to even)
  bool strip = false;
  Plot plot{};
  PlotLayout layout{};
  Image strip_image{};

  Animation(const Model& model, const Motion& motion, const AnimationOptions& o, bool even)
      : original(&motion), times(animation_times(motion, o)), sampled(resample(motion, times)) {
    // the view, the rails and the scales of the still frames: one scale for the whole run
    const detail::FramePlan still = detail::make_plan(model, motion, o.frame);
    plan = detail::make_plan(model, sampled, o.frame);
    plan.view = still.view;
    plan.range = still.range;
    plan.peak = still.peak;
    plan.force_peak = still.force_peak;
    plan.torque_peak = still.torque_peak;
    plan.chain_peak = still.chain_peak;
    width = o.frame.width;
    height = o.frame.height;
    strip = o.plot;
    if (strip) make_strip(o);
    if (even) width += width % 2, height += height % 2;
  }

  void make_strip(const AnimationOptions& o) {
    const AnimationPlot& s = o.strip;
    if (s.values.size() != static_cast<size_t>(original->time.size()))
      throw Error("render: the plot strip '" + s.label + "' has " +
                      std::to_string(s.values.size()) + " values for " +
                      std::to_string(original->time.size()) + " samples",
                  s.label);
    if (s.height < 0) throw Error("render: the plot strip's height must be >= 0", "height");
    const std::vector<double> t(original->time.data(),
                                original->time.data() + original->time.size());
    plot.width = o.frame.width;
    plot.height = s.height > 0 ? s.height : std::max(60, o.frame.height / 3);
    plot.dpi = o.frame.dpi;
    plot.legend = false;
    plot.x.label = "time (s)";
    if (t.back() > t.front()) plot.x.range = std::pair{t.front(), t.back()};
    plot.y.label = s.label;
    plot.series.push_back({s.label, t, s.values, std::nullopt, false, false});
    strip_image = render_plot(plot);
    layout = plot_layout(plot);
    height += plot.height;
  }

  // Frame i into `pixels` (width x height, 0x00RRGGBB words as Cairo's RGB24).
  void draw(int i, std::vector<std::uint32_t>& pixels) const {
    pixels.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
    cairo_surface_t* surface =
        cairo_image_surface_create_for_data(reinterpret_cast<unsigned char*>(pixels.data()),
                                            CAIRO_FORMAT_RGB24, width, height, 4 * width);
    cairo_t* cr = cairo_create(surface);
    detail::set_colour(cr, plan.options.style.background);
    cairo_paint(cr);
    detail::draw_frame(cr, plan, i, {true, true, true});
    if (strip) draw_strip(cr, i);
    cairo_destroy(cr);
    cairo_surface_flush(surface);
    const cairo_status_t status = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS)
      throw Error(std::string("render: Cairo failed drawing an animation frame: ") +
                  cairo_status_to_string(status));
  }

  void draw_strip(cairo_t* cr, int i) const {
    const double y0 = plan.view.height;
    cairo_surface_t* s = cairo_image_surface_create_for_data(
        reinterpret_cast<unsigned char*>(const_cast<std::uint32_t*>(strip_image.argb.data())),
        CAIRO_FORMAT_RGB24, strip_image.width, strip_image.height, 4 * strip_image.width);
    cairo_set_source_surface(cr, s, 0, y0);
    cairo_paint(cr);
    cairo_surface_destroy(s);
    const double t = times[static_cast<size_t>(i)];
    const Eigen::Vector2d c = to_pixel(layout, t, value_at(*original, plot.series[0].y, t));
    const double P = plot.dpi / 72.0;
    detail::set_colour(cr, rgb_hex(0xC0392B));
    cairo_set_line_width(cr, 1.0 * P);
    cairo_move_to(cr, c.x(), y0 + layout.top);
    cairo_line_to(cr, c.x(), y0 + layout.bottom);
    cairo_stroke(cr);
    if (std::isfinite(c.y()) && c.y() >= layout.top && c.y() <= layout.bottom) {
      cairo_arc(cr, c.x(), y0 + c.y(), 2.5 * P, 0, 2 * detail::kPi);
      cairo_fill(cr);
    }
  }
};

int thread_count(const AnimationOptions& o) {
  if (o.threads < 0) throw Error("render: AnimationOptions::threads must be >= 0", "threads");
  const int hw = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return o.threads > 0 ? o.threads : hw;
}

}  // namespace

std::string animation_support() {
  return detail::encoder_support();
}

std::vector<double> animation_times(const Motion& motion, const AnimationOptions& o) {
  if (!std::isfinite(o.fps) || o.fps <= 0)
    throw Error("render: the frame rate must be finite and > 0 (got " + std::to_string(o.fps) + ")",
                "fps");
  if (!std::isfinite(o.slow) || o.slow <= 0)
    throw Error("render: the slow-motion factor must be finite and > 0 (got " +
                    std::to_string(o.slow) + ")",
                "slow");
  if (o.max_frames < 1) throw Error("render: max_frames must be >= 1", "max_frames");
  const Eigen::Index N = motion.time.size();
  if (N == 0) throw Error("render: the run has no samples", "time");
  const double t0 = motion.time[0], t1 = motion.time[N - 1];
  if (!std::isfinite(t0) || !std::isfinite(t1) || t1 < t0)
    throw Error("render: the run's times must be finite and increasing", "time");
  const double rate = o.fps * o.slow;  // frames per second of run time
  const double count = std::floor((t1 - t0) * rate + 1e-9) + 1;
  if (!(count <= o.max_frames))
    throw Error("render: the animation would have " + std::to_string(std::llround(count)) +
                    " frames, more than the limit of " + std::to_string(o.max_frames) +
                    " (AnimationOptions::max_frames, --max-frames); lower --fps or --slow, or "
                    "shorten the run",
                "max_frames");
  std::vector<double> t(static_cast<size_t>(count));
  for (size_t i = 0; i < t.size(); ++i) t[i] = t0 + static_cast<double>(i) / rate;
  return t;
}

Image render_animation_frame(const Model& model, const Motion& motion,
                             const AnimationOptions& options, int frame) {
  const Animation a(model, motion, options, false);
  if (frame < 0 || frame >= static_cast<int>(a.times.size()))
    throw Error("render: frame " + std::to_string(frame) + " is not in 0.." +
                    std::to_string(a.times.size() - 1),
                "frame");
  Image im;
  im.width = a.width;
  im.height = a.height;
  a.draw(frame, im.argb);
  for (auto& p : im.argb) p |= 0xFF000000u;
  return im;
}

AnimationInfo write_animation(const Model& model, const Motion& motion,
                              const AnimationOptions& options, const std::string& path) {
  const detail::EncoderChoice choice = detail::encoder_choice(path);  // Error without FFmpeg
  const int threads = thread_count(options);
  const Animation a(model, motion, options, choice.even_size);
  const int n = static_cast<int>(a.times.size());

  // GIF: the palette of the first, middle and last frames
  std::vector<std::vector<std::uint32_t>> samples;
  std::vector<const std::uint32_t*> palette_frames;
  if (choice.palette) {
    for (int i : {0, n / 2, n - 1}) a.draw(i, samples.emplace_back());
    for (const auto& s : samples) palette_frames.push_back(s.data());
  }
  detail::Encoder encoder(path, a.width, a.height, options.fps, palette_frames);
  samples.clear();

  // batches of frames drawn by `threads` threads while the previous batch is encoded
  const int batch = 4 * threads;
  auto draw_batch = [&a, n, batch, threads](int b, std::vector<std::vector<std::uint32_t>>& out) {
    const int first = b * batch, count = std::min(batch, n - first);
    out.resize(static_cast<size_t>(count));
    std::vector<std::future<void>> jobs;
    jobs.reserve(static_cast<size_t>(threads));
    for (int w = 0; w < threads; ++w)
      jobs.push_back(std::async(std::launch::async, [&, w] {
        for (int i = w; i < count; i += threads) a.draw(first + i, out[static_cast<size_t>(i)]);
      }));
    for (auto& j : jobs) j.get();
  };
  std::vector<std::vector<std::uint32_t>> ready, next;
  draw_batch(0, ready);
  for (int b = 0; b * batch < n; ++b) {
    std::future<void> drawing;
    if ((b + 1) * batch < n)
      drawing = std::async(std::launch::async, [&, b] { draw_batch(b + 1, next); });
    try {
      for (const auto& f : ready) encoder.add(f.data());
    } catch (...) {
      if (drawing.valid()) drawing.wait();
      throw;
    }
    if (drawing.valid()) drawing.get();
    std::swap(ready, next);
  }
  detail::write_bytes(path, encoder.finish());
  return {n, a.width, a.height, options.fps, encoder.codec()};
}

}  // namespace mo2d
