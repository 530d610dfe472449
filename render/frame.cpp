// One frame of a run, back to front: traces, ground rails, ground pivots, bodies (with their
// slots), slider blocks, joints, centres of mass, effort symbols, labels, loads (above all the
// mechanism), then the time stamp, scale bar, axes and the legend of the load arrows.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "canvas.hpp"
#include "labels.hpp"
#include "mo2d/error.hpp"
#include "plan.hpp"
#include "symbols.hpp"

namespace mo2d {

namespace detail {

namespace {

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  std::string s = buf;
  if (!s.empty() && s[0] == '-') s = "\u2212" + s.substr(1);  // a typographic minus
  return s;
}

// Colour of an effort: grey at zero, the sign's colour at the run's peak.
Rgb effort_colour(const FrameStyle& s, double ratio, double u) {
  return mix(rgb_hex(0xB0B0B0), u >= 0 ? s.positive : s.negative, 0.3 + 0.7 * ratio);
}

// A round length of 1, 2 or 5 times a power of ten, at most `max`.
double round_length(double max) {
  const double p = std::pow(10.0, std::floor(std::log10(max)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= max) return m * p;
  return p;
}

std::string length_label(double L) {
  if (L >= 1) return format("%g m", L);
  if (L >= 0.01) return format("%g cm", L * 100);
  return format("%g mm", L * 1000);
}

struct Painter {
  cairo_t* cr;
  const FramePlan& p;
  const FrameStyle& s;
  Eigen::VectorXd q0;
  int k;

  double px(double pt) const { return pt * p.P; }
  Vec2 at(const Vec2& world) const { return to_pixel(p.view, world); }
  Vec2 node(const NodeRef& n) const { return at(node_position(n, q0)); }
  Rgb body_colour(int b) const {
    return b < 0 ? s.ground : s.palette[static_cast<size_t>(b) % s.palette.size()];
  }
  // unit axis i -> j of a prismatic or slot joint, in pixels
  Vec2 axis_px(const JointPart& j) const {
    const Vec2 d = node(j.j) - node(j.i);
    return d.norm() > 0 ? Vec2(d / d.norm()) : Vec2(1, 0);
  }
  double block_half_length() const { return px(2.3 * s.joint_radius); }
  double block_half_height() const { return px(1.6 * s.joint_radius); }
  double slot_width() const { return 2 * px(s.joint_radius + 0.35); }

  void font(double size_pt, bool italic = false) const {
    detail::select_font(cr, s.font, italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                        CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, px(size_pt));
  }

  void traces() const {
    for (size_t t = 0; t < p.traces.size(); ++t) {
      const auto& path = p.traces[t];
      const Rgb c = dark_shade(body_colour(p.trace_points[t].body));
      cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      for (int pass = 0; pass < 2; ++pass) {  // whole path faint, travelled part darker
        const size_t end = pass == 0 ? path.size() : static_cast<size_t>(k) + 1;
        for (size_t i = 0; i < end; ++i) {
          const Vec2 q = at(path[i]);
          i == 0 ? cairo_move_to(cr, q.x(), q.y()) : cairo_line_to(cr, q.x(), q.y());
        }
        set_colour(cr, c, pass == 0 ? 0.35 : 0.85);
        cairo_set_line_width(cr, px(pass == 0 ? 0.7 : 1.0) * s.line_width);
        cairo_stroke(cr);
      }
    }
  }

  void rails() const {
    for (size_t j = 0; j < p.parts.joints.size(); ++j) {
      const JointPart& jp = p.parts.joints[j];
      if (jp.kind != JointKind::prismatic) continue;
      const Vec2 a = node(jp.i), e = axis_px(jp);
      const double scale = p.view.scale, pad = block_half_length() + px(4);
      Vec2 from = a + (p.range[j].first * scale - pad) * e;
      Vec2 to = a + (p.range[j].second * scale + pad) * e;
      const Vec2 side(-e.y(), e.x());  // right-hand side of the axis on screen
      if (jp.body1 < 0) {
        const Vec2 off = (block_half_height() + px(0.5 * s.line_width)) * side;
        draw_hatched_line(cr, from + off, to + off, side, px(0.9 * s.joint_radius), s.ground,
                          px(s.line_width));
      } else {
        set_colour(cr, dark_shade(body_colour(jp.body1)));
        cairo_set_line_width(cr, px(1.6 * s.line_width));
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
        cairo_move_to(cr, from.x(), from.y());
        cairo_line_to(cr, to.x(), to.y());
        cairo_stroke(cr);
      }
    }
  }

  void ground_pivots() const {
    for (const JointPart& j : p.parts.joints)
      if (j.kind == JointKind::revolute && (j.body1 < 0 || j.body2 < 0))
        draw_ground_pivot(cr, node(j.node), px(s.joint_radius), s.ground, px(s.line_width));
  }

  void slots_of(int b) const {
    for (size_t j = 0; j < p.parts.joints.size(); ++j) {
      const JointPart& jp = p.parts.joints[j];
      if (jp.kind != JointKind::slot || jp.body1 != b) continue;
      const Vec2 a = node(jp.i), e = axis_px(jp);
      const Vec2 from = a + p.range[j].first * p.view.scale * e;
      const Vec2 to = a + p.range[j].second * p.view.scale * e;
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      cairo_move_to(cr, from.x(), from.y());
      cairo_line_to(cr, to.x(), to.y());
      set_colour(cr, dark_shade(body_colour(b)));
      cairo_set_line_width(cr, slot_width() + 2 * px(s.line_width));
      cairo_stroke_preserve(cr);
      set_colour(cr, s.background);
      cairo_set_line_width(cr, slot_width());
      cairo_stroke(cr);
    }
  }

  void bodies() const {
    const Model& m = *p.model;
    for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b) {
      if (p.parts.block[b]) continue;
      std::vector<Vec2> pts;
      for (const NodeRef& n : m.bodies[b].nodes) pts.push_back(node(n));
      double width = px(s.body_width);
      if (pts.size() == 1) width = px(1.25 * s.body_width);
      if (p.parts.slotted[b]) width = std::max(width, slot_width() + 2 * px(2.2 + s.line_width));
      draw_body(cr, convex_hull(pts), body_colour(b), width, px(s.line_width));
      slots_of(b);
    }
  }

  void blocks() const {
    for (const JointPart& j : p.parts.joints) {
      if (j.kind != JointKind::prismatic) continue;
      const Vec2 c = node(j.s), e = axis_px(j), n(-e.y(), e.x());
      const double hl = block_half_length(), hh = block_half_height();
      const Rgb col = body_colour(j.body2);
      cairo_new_path(cr);
      for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        const Vec2 q = c + a * hl * e + b * hh * n;
        cairo_line_to(cr, q.x(), q.y());
      }
      cairo_close_path(cr);
      set_colour(cr, light_tint(col));
      cairo_fill_preserve(cr);
      set_colour(cr, dark_shade(col));
      cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
      cairo_set_line_width(cr, px(s.line_width));
      cairo_stroke(cr);
    }
  }

  void joints() const {
    for (const JointPart& j : p.parts.joints) {
      if (j.kind == JointKind::prismatic) continue;
      const Vec2 c = node(j.kind == JointKind::revolute ? j.node : j.s);
      draw_pin(cr, c, px(s.joint_radius), s.joint_fill, s.ink, px(s.line_width));
    }
  }

  bool on_a_joint(const Vec2& c) const {
    for (const JointPart& j : p.parts.joints) {
      const Vec2 q = node(j.kind == JointKind::revolute ? j.node : j.s);
      if ((q - c).norm() < px(1.5 * s.joint_radius)) return true;
    }
    return false;
  }

  void centres_of_mass() const {
    for (const Body& b : p.model->bodies) {
      if (b.mass <= 0) continue;
      const Vec2 c = at(com_position(b, q0));
      if (on_a_joint(c)) continue;  // a centre of mass on a joint would hide the joint
      draw_com(cr, c, px(s.com_radius), s.ink, px(0.8 * s.line_width));
    }
  }

  void efforts() const {
    const Eigen::MatrixXd& U = p.motion->efforts;
    if (!p.options.show_efforts || U.cols() == 0) return;
    for (const JointPart& j : p.parts.joints) {
      if (j.torque_input >= 0) torque(j, U(k, j.torque_input), p.peak[j.torque_input]);
      if (j.force_input >= 0) force(j, U(k, j.force_input), p.peak[j.force_input]);
    }
    if (!p.options.show_effort_values) return;
    // values in the top-right corner: "tau = 0.81 N.m" (with the joint's name if several)
    int n = 0;
    for (const JointPart& j : p.parts.joints) n += (j.torque_input >= 0) + (j.force_input >= 0);
    double y = px(p.options.margin);
    for (const JointPart& j : p.parts.joints)
      for (int input : {j.torque_input, j.force_input}) {
        if (input < 0 || !std::isfinite(U(k, input))) continue;
        const double u = U(k, input), ratio = p.peak[input] > 0 ? std::abs(u) / p.peak[input] : 0;
        const bool torque = input == j.torque_input;
        const std::string head =
            (n > 1 ? j.name + ": " : std::string()) + (torque ? "\u03C4" : "F");
        const std::string value = " = " + format("%.3g", u) + (torque ? " N\u00B7m" : " N");
        font(s.font_size);
        const double x = p.view.width - px(p.options.margin) - text_width(cr, value);
        set_colour(cr, dark_shade(effort_colour(s, std::min(ratio, 1.0), u)));
        draw_text(cr, value, x, y, 0, 0);
        font(s.font_size, !torque || n > 1 ? false : true);
        draw_text(cr, head, x, y, 1, 0);
        y += px(1.4 * s.font_size);
      }
  }

  // Arc centred above the joint, sweeping from 20 degrees (zero effort) to 270 degrees (the
  // run's peak), counter-clockwise on screen for a positive (counter-clockwise) torque.
  void torque(const JointPart& j, double u, double peak) const {
    if (!std::isfinite(u) || peak <= 0) return;
    const double ratio = std::min(std::abs(u) / peak, 1.0);
    const Vec2 c = node(j.kind == JointKind::revolute ? j.node : j.s);
    const Rgb col = effort_colour(s, ratio, u);
    const double min_sweep = kPi / 9;
    const double R = px(s.effort_radius), sweep = min_sweep + (1.5 * kPi - min_sweep) * ratio;
    const double up = -kPi / 2;
    const double w = px(s.line_width) * (1.2 + 1.3 * ratio);
    set_colour(cr, col);
    cairo_set_line_width(cr, w);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    const double head = std::min(px(4.5) + 1.5 * w, 0.9 * R * std::max(sweep, 1e-9));
    const double head_angle = head / R;
    {
      double end;
      Vec2 dir;
      cairo_new_path(cr);
      if (u >= 0) {  // cairo's angles grow clockwise on screen: counter-clockwise is negative
        end = up - sweep / 2;
        cairo_arc_negative(cr, c.x(), c.y(), R, up + sweep / 2,
                           std::min(end + head_angle, up + sweep / 2));
        dir = Vec2(std::sin(end), -std::cos(end));
      } else {
        end = up + sweep / 2;
        cairo_arc(cr, c.x(), c.y(), R, up - sweep / 2, std::max(end - head_angle, up - sweep / 2));
        dir = Vec2(-std::sin(end), std::cos(end));
      }
      cairo_stroke(cr);
      const Vec2 tip = c + R * Vec2(std::cos(end), std::sin(end));
      draw_arrow_head(cr, tip, dir, head, 0.5 * head + 0.5 * w);
    }
  }

  // Arrow along the axis (its sign) from the end face of the slider block.
  void force(const JointPart& j, double u, double peak) const {
    if (!std::isfinite(u) || peak <= 0) return;
    const double ratio = std::min(std::abs(u) / peak, 1.0);
    const Vec2 e = axis_px(j) * (u >= 0 ? 1.0 : -1.0);
    const Vec2 c = node(j.s);
    const Rgb col = effort_colour(s, ratio, u);
    const double w = px(s.line_width) * (1.2 + 1.3 * ratio);
    const double len = px(s.effort_length) * ratio, head = std::min(px(4.5) + 1.5 * w, len);
    const Vec2 from = c + (block_half_length() + px(1.5)) * e, tip = from + len * e;
    set_colour(cr, col);
    if (len > px(0.5)) {
      cairo_set_line_width(cr, w);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      cairo_move_to(cr, from.x(), from.y());
      const Vec2 shaft = tip - head * e;
      cairo_line_to(cr, shaft.x(), shaft.y());
      cairo_stroke(cr);
      draw_arrow_head(cr, tip, e, head, 0.5 * head + 0.5 * w);
    }
  }

  // Body names beside their bodies, none over another (labels.hpp).
  void labels() const {
    if (!p.options.show_labels) return;
    font(0.9 * s.font_size, true);
    cairo_font_extents_t fe;
    cairo_font_extents(cr, &fe);
    const auto nb = p.model->bodies.size();
    std::vector<Vec2> anchors(nb, Vec2(0, 0)), sizes(nb, Vec2(0, 0));
    for (size_t b = 0; b < nb; ++b) {
      for (const NodeRef& n : p.model->bodies[b].nodes) anchors[b] += node(n);
      anchors[b] /= static_cast<double>(p.model->bodies[b].nodes.size());
      sizes[b] = Vec2(text_width(cr, p.model->bodies[b].name), 0.72 * fe.ascent + fe.descent);
    }
    const double m = px(p.options.margin);
    const std::vector<LabelBox> boxes = place_labels(
        anchors, sizes, px(s.body_width), {m, m, p.view.width - 2 * m, p.view.height - 2 * m});
    for (size_t b = 0; b < nb; ++b) {
      set_colour(cr, dark_shade(body_colour(static_cast<int>(b))));
      draw_text(cr, p.model->bodies[b].name, boxes[b].x, boxes[b].y, 0, 0);
    }
  }

  void decorations(const Decorations& d) const {
    const double W = p.view.width, H = p.view.height, m = px(p.options.margin);
    set_colour(cr, s.ink);
    double x = m;
    if (d.time && !p.options.title.empty()) {
      font(s.font_size);
      draw_text(cr, p.options.title, x, m, 0, 0);
      x += text_width(cr, p.options.title + (p.options.show_time ? "   " : ""));
    }
    if (d.time && p.options.show_time) {
      font(s.font_size, true);
      draw_text(cr, "t", x, m, 0, 0);
      const double tw = text_width(cr, "t");
      font(s.font_size);
      char buf[64];
      std::snprintf(buf, sizeof buf, " = %.*f s", p.time_decimals, p.motion->time[k]);
      draw_text(cr, buf, x + tw, m, 0, 0);
    }
    const double base = H - m - px(2);
    if (d.scale_bar && p.options.show_scale_bar) {
      const double L = round_length(0.22 * W / p.view.scale), len = L * p.view.scale;
      const double x1 = W - m, x0 = x1 - len, tick = px(3);
      cairo_set_line_width(cr, px(s.line_width));
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);
      cairo_move_to(cr, x0, base - tick);
      cairo_line_to(cr, x0, base);
      cairo_line_to(cr, x1, base);
      cairo_line_to(cr, x1, base - tick);
      cairo_stroke(cr);
      font(0.9 * s.font_size);
      draw_text(cr, length_label(L), 0.5 * (x0 + x1), base - tick - px(2), 0.5, 1);
    }
    if (d.axes && p.options.show_axes) {
      const double len = px(16), x0 = m + px(2);
      const double head = px(4);
      cairo_set_line_width(cr, px(s.line_width));
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      cairo_move_to(cr, x0 + len - head, base);
      cairo_line_to(cr, x0, base);
      cairo_line_to(cr, x0, base - len + head);
      cairo_stroke(cr);
      draw_arrow_head(cr, {x0 + len, base}, {1, 0}, head, 0.45 * head);
      draw_arrow_head(cr, {x0, base - len}, {0, -1}, head, 0.45 * head);
      font(0.9 * s.font_size, true);
      draw_text(cr, "x", x0 + len + px(2), base, 0, 0.5);
      draw_text(cr, "y", x0, base - len - px(2), 0.5, 1);
    }
  }
};

}  // namespace

void draw_frame(cairo_t* cr, const FramePlan& plan, int k, const Decorations& decorations) {
  Painter paint{cr, plan, plan.options.style, plan.motion->q0.row(k).transpose(), k};
  cairo_save(cr);
  cairo_rectangle(cr, 0, 0, plan.view.width, plan.view.height);
  cairo_clip(cr);
  set_colour(cr, plan.options.style.background);
  cairo_paint(cr);
  paint.traces();
  paint.rails();
  paint.ground_pivots();
  paint.bodies();
  draw_chains(cr, plan, k);
  draw_contacts(cr, plan, k);
  paint.blocks();
  paint.joints();
  if (plan.options.show_com) paint.centres_of_mass();
  paint.efforts();
  paint.labels();
  draw_loads(cr, plan, k);  // above everything of the mechanism
  paint.decorations(decorations);
  if (decorations.scale_bar && plan.options.show_scale_bar) draw_load_legend(cr, plan);
  cairo_restore(cr);
  check_status(cr, "drawing a frame");
}

}  // namespace detail

Image render_frame(const Model& model, const Motion& motion, int sample,
                   const FrameOptions& options) {
  detail::check_sample(motion, sample);
  const detail::FramePlan plan = detail::make_plan(model, motion, options);
  detail::Canvas canvas(detail::Format::png, options.width, options.height, options.dpi);
  detail::draw_frame(canvas.cr(), plan, sample, {});
  return canvas.image();
}

void write_frame(const Model& model, const Motion& motion, int sample, const FrameOptions& options,
                 const std::string& path) {
  const detail::Format f = detail::format_of(path);
  detail::check_sample(motion, sample);
  const detail::FramePlan plan = detail::make_plan(model, motion, options);
  detail::Canvas canvas(f, options.width, options.height, options.dpi);
  detail::draw_frame(canvas.cr(), plan, sample, {});
  detail::write_bytes(path, canvas.finish());
}

std::vector<std::string> write_frames(const Model& model, const Motion& motion,
                                      const FrameOptions& options, const std::string& dir,
                                      const std::string& name, int every) {
  if (every < 1) throw Error("render: frames every " + std::to_string(every) + " samples", "every");
  if (name.empty() || name.find('/') != std::string::npos)
    throw Error("render: frame name '" + name + "' must be a plain file name", "name");
  const detail::FramePlan plan = detail::make_plan(model, motion, options);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("render: cannot create the folder '" + dir + "': " + ec.message(), dir);
  std::vector<std::string> paths;
  int n = 0;
  for (int k = 0; k < motion.time.size(); k += every) {
    detail::Canvas canvas(detail::Format::png, options.width, options.height, options.dpi);
    detail::draw_frame(canvas.cr(), plan, k, {});
    char file[32];
    std::snprintf(file, sizeof file, "_%04d.png", ++n);
    paths.push_back((std::filesystem::path(dir) / (name + file)).string());
    detail::write_bytes(paths.back(), canvas.finish());
  }
  return paths;
}

}  // namespace mo2d
