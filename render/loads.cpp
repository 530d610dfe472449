// The applied loads of a frame (FrameOptions::show_loads): every force as an arrow along the force
// ending at its point (pushing on it, drawn above the bodies), every torque as a curved arrow
// around its body's centre of mass, both sized by the value relative to the run's peak of that
// load, evaluated at each sample's (t, q0, q1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "canvas.hpp"
#include "dynamics/points.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "plan.hpp"
#include "symbols.hpp"

namespace mo2d::detail {

void plan_loads(FramePlan& p) {
  const Model& m = *p.model;
  const Motion& mo = *p.motion;
  if (!p.options.show_loads || (m.forces.empty() && m.torques.empty())) return;
  const Eigen::Index N = mo.time.size();
  if (mo.q1.rows() != N || mo.q1.cols() != m.n1)
    throw Error("render: show_loads needs the quasi-velocities of every sample (Motion::q1, " +
                    std::to_string(N) + " x " + std::to_string(m.n1) + "; motion_of fills them)",
                "q1");
  p.forces.assign(N, std::vector<FramePlan::LoadAt>(m.forces.size()));
  p.torques.assign(N, std::vector<FramePlan::LoadAt>(m.torques.size()));
  p.force_peak.assign(m.forces.size(), 0.0);
  p.torque_peak.assign(m.torques.size(), 0.0);
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = mo.q0.row(k).transpose(), q1 = mo.q1.row(k).transpose();
    const double t = mo.time[k];
    for (size_t f = 0; f < m.forces.size(); ++f) {
      const PointLoad& l = m.forces[f];
      FramePlan::LoadAt& a = p.forces[k][f];
      a.at = local_position_of_point(m.bodies[l.body], q0, l.ci, l.cj, l.gamma, l.rho);
      a.force = point_force(m, l, q0, q1, t);
      if (!a.force.allFinite())
        throw Error(
            "render: force '" + l.name + "' is not finite at t = " + std::to_string(t) + " s",
            l.name, t);
      p.force_peak[f] = std::max(p.force_peak[f], a.force.norm());
    }
    for (size_t q = 0; q < m.torques.size(); ++q) {
      const TorqueLoad& l = m.torques[q];
      FramePlan::LoadAt& a = p.torques[k][q];
      a.at = com_position(m.bodies[l.body], q0);
      a.torque = torque_value(m, l, q0, q1, t);
      p.torque_peak[q] = std::max(p.torque_peak[q], std::abs(a.torque));
    }
  }
}

namespace {

// A straight arrow from `from` along `e` (unit, pixels), `len` long, line width w.
void arrow(cairo_t* cr, const Vec2& from, const Vec2& e, double len, double w, double head) {
  head = std::min(head, len);
  const Vec2 tip = from + len * e, shaft = tip - head * e;
  cairo_set_line_width(cr, w);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_move_to(cr, from.x(), from.y());
  cairo_line_to(cr, shaft.x(), shaft.y());
  cairo_stroke(cr);
  draw_arrow_head(cr, tip, e, head, 0.5 * head + 0.5 * w);
}

// An arc of radius R around c from 20 degrees (zero) to 270 degrees (the peak), centred on the
// upward direction, counter-clockwise on screen for a positive (counter-clockwise) torque.
void arc(cairo_t* cr, const Vec2& c, double R, double ratio, double u, double w, double head) {
  const double sweep = kPi / 9 + (1.5 * kPi - kPi / 9) * ratio, up = -kPi / 2;
  head = std::min(head, 0.9 * R * sweep);
  const double head_angle = head / R;
  cairo_set_line_width(cr, w);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_new_path(cr);
  double end;
  Vec2 dir;
  if (u >= 0) {  // cairo's angles grow clockwise on screen
    end = up - sweep / 2;
    cairo_arc_negative(cr, c.x(), c.y(), R, up + sweep / 2, end + head_angle);
    dir = Vec2(std::sin(end), -std::cos(end));
  } else {
    end = up + sweep / 2;
    cairo_arc(cr, c.x(), c.y(), R, up - sweep / 2, end - head_angle);
    dir = Vec2(-std::sin(end), std::cos(end));
  }
  cairo_stroke(cr);
  draw_arrow_head(cr, c + R * Vec2(std::cos(end), std::sin(end)), dir, head, 0.5 * head + 0.5 * w);
}

}  // namespace

// A force's arrow ends at its point (the force pushes on it), short of the pin drawn there; an
// arrow shorter than its head is drawn as the head alone, so that a small force still shows.
void draw_loads(cairo_t* cr, const FramePlan& p, int k) {
  if (p.forces.empty() && p.torques.empty()) return;
  const FrameStyle& s = p.options.style;
  const double P = p.P;
  set_colour(cr, s.load);
  for (size_t f = 0; f < p.forces[k].size(); ++f) {
    const FramePlan::LoadAt& a = p.forces[k][f];
    const double F = a.force.norm();
    if (p.force_peak[f] <= 0 || F <= 0) continue;
    const double ratio = std::min(F / p.force_peak[f], 1.0);
    const Vec2 e(a.force.x() / F, -a.force.y() / F);  // y down on screen
    const double w = P * s.line_width * (1.2 + 1.3 * ratio);
    const double head = P * 4.5 + 1.5 * w;
    const double len = std::max(P * s.effort_length * ratio, head);
    const Vec2 tip = to_pixel(p.view, a.at) - P * (s.joint_radius + 1.0) * e;
    arrow(cr, tip - len * e, e, len, w, head);
  }
  for (size_t q = 0; q < p.torques[k].size(); ++q) {
    const FramePlan::LoadAt& a = p.torques[k][q];
    if (p.torque_peak[q] <= 0 || a.torque == 0) continue;
    const double ratio = std::min(std::abs(a.torque) / p.torque_peak[q], 1.0);
    const double w = P * s.line_width * (1.2 + 1.3 * ratio);
    arc(cr, to_pixel(p.view, a.at), P * s.effort_radius, ratio, a.torque, w, P * 4.5 + 1.5 * w);
  }
}

int load_legend_lines(const FramePlan& p) {
  int n = 0;
  for (double peak : p.force_peak) n += peak > 0;
  for (double peak : p.torque_peak) n += peak > 0;
  return n;
}

namespace {

std::string with_unit(double v, const char* unit) {
  const double a = std::abs(v);
  const char* prefix = a >= 1e6 ? "M" : a >= 1e3 ? "k" : a >= 1 || a == 0 ? "" : "m";
  const double scale = a >= 1e6 ? 1e-6 : a >= 1e3 ? 1e-3 : a >= 1 || a == 0 ? 1 : 1e3;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g %s%s", v * scale, prefix, unit);
  return buf;
}

}  // namespace

// Under the time stamp, one line per load: the arrow (or arc) at the run's peak and its value.
void draw_load_legend(cairo_t* cr, const FramePlan& p) {
  if (load_legend_lines(p) == 0) return;
  const FrameStyle& s = p.options.style;
  const double P = p.P, m = P * p.options.margin, line = P * 1.4 * s.font_size;
  double y = m + P * 1.6 * s.font_size + 0.5 * line;
  detail::select_font(cr, s.font, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, P * 0.9 * s.font_size);
  const double w = P * s.line_width * 2.5, head = P * 4.5 + 1.5 * w, len = P * s.effort_length;
  for (size_t f = 0; f < p.force_peak.size(); ++f) {
    if (p.force_peak[f] <= 0) continue;
    set_colour(cr, s.load);
    arrow(cr, {m, y}, {1, 0}, len, w, head);
    draw_text(cr, " " + with_unit(p.force_peak[f], "N") + "  " + p.model->forces[f].name,
              m + len + P * 2, y, 0, 0.5);
    y += line;
  }
  for (size_t q = 0; q < p.torque_peak.size(); ++q) {
    if (p.torque_peak[q] <= 0) continue;
    set_colour(cr, s.load);
    draw_text(cr,
              "\u21BA 270\u00B0 = " + with_unit(p.torque_peak[q], "N\u00B7m") + "  " +
                  p.model->torques[q].name,
              m, y, 0, 0.5);
    y += line;
  }
}

}  // namespace mo2d::detail
