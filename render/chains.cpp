// Chain and belt drives in a frame (Model::chains): each sprocket's pitch circle, and each span
// as a straight line between its tangent points (the open-belt geometry of dynamics/chain.hpp:
// cos alpha = (r_a - r_b) / D, the radius to the upper span's tangent points at beta + alpha,
// the lower's at beta - alpha), coloured by its tension from grey (zero) to style.positive at the
// run's peak tension of that chain, thicker with the tension; a slack span (T = 0) dashed.
#include <algorithm>
#include <cmath>

#include "canvas.hpp"
#include "dynamics/points.hpp"
#include "mo2d/dynamics.hpp"
#include "plan.hpp"

namespace mo2d::detail {

namespace {

FramePlan::ChainAt chain_at(const Model& m, const ChainLoad& c, const Eigen::VectorXd& q0,
                            const Eigen::VectorXd& q1, double t) {
  FramePlan::ChainAt a;
  a.ca = point_state(m, c.a, q0, q1).p;
  a.cb = point_state(m, c.b, q0, q1).p;
  const Vec2 d = a.cb - a.ca;
  const double D = d.norm(), beta = std::atan2(d.y(), d.x());
  const double alpha = std::acos(std::clamp((c.radius_a - c.radius_b) / D, -1.0, 1.0));
  for (int side = 0; side < 2; ++side) {  // 0: upper, 1: lower
    const double phi = side == 0 ? beta + alpha : beta - alpha;
    const Vec2 u(std::cos(phi), std::sin(phi));
    a.span[side] = {a.ca + c.radius_a * u, a.cb + c.radius_b * u};
  }
  const ChainValue v = chain_value(m, c, q0, q1, t);
  a.tension[0] = v.upper_tension;
  a.tension[1] = v.lower_tension;
  return a;
}

}  // namespace

void plan_chains(FramePlan& p) {
  const Model& m = *p.model;
  const Motion& mo = *p.motion;
  if (m.chains.empty()) return;
  const Eigen::Index N = mo.time.size();
  const bool rates = mo.q1.rows() == N && mo.q1.cols() == m.n1;
  p.chains.assign(N, std::vector<FramePlan::ChainAt>(m.chains.size()));
  p.chain_peak.assign(m.chains.size(), 0.0);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.n1);
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = mo.q0.row(k).transpose();
    const Eigen::VectorXd q1 = rates ? Eigen::VectorXd(mo.q1.row(k).transpose()) : zero;
    for (size_t c = 0; c < m.chains.size(); ++c) {
      FramePlan::ChainAt& a = p.chains[k][c] = chain_at(m, m.chains[c], q0, q1, mo.time[k]);
      p.chain_peak[c] = std::max({p.chain_peak[c], a.tension[0], a.tension[1]});
    }
  }
}

void draw_chains(cairo_t* cr, const FramePlan& p, int k) {
  if (p.chains.empty()) return;
  const FrameStyle& s = p.options.style;
  const double P = p.P;
  for (size_t c = 0; c < p.chains[k].size(); ++c) {
    const FramePlan::ChainAt& a = p.chains[k][c];
    const ChainLoad& ch = p.model->chains[c];
    set_colour(cr, s.ink, 0.6);
    cairo_set_line_width(cr, P * 0.8 * s.line_width);
    cairo_set_dash(cr, nullptr, 0, 0);
    const double scale = p.view.scale;
    for (const auto& [centre, r] : {std::pair{a.ca, ch.radius_a}, std::pair{a.cb, ch.radius_b}}) {
      const Vec2 px = to_pixel(p.view, centre);
      cairo_new_path(cr);
      cairo_arc(cr, px.x(), px.y(), r * scale, 0, 2 * kPi);
      cairo_stroke(cr);
    }
    for (int side = 0; side < 2; ++side) {
      const double T = a.tension[side];
      const double ratio = p.chain_peak[c] > 0 ? std::min(T / p.chain_peak[c], 1.0) : 0.0;
      const Vec2 from = to_pixel(p.view, a.span[side].first);
      const Vec2 to = to_pixel(p.view, a.span[side].second);
      const double dash[] = {P * 3, P * 2.5};
      cairo_set_dash(cr, dash, T > 0 ? 0 : 2, 0);
      set_colour(cr, mix(rgb_hex(0x9A9A9A), s.positive, T > 0 ? 0.25 + 0.75 * ratio : 0.0));
      cairo_set_line_width(cr, P * s.line_width * (1.2 + 1.8 * ratio));
      cairo_move_to(cr, from.x(), from.y());
      cairo_line_to(cr, to.x(), to.y());
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
  }
}

}  // namespace mo2d::detail
