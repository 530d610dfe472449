// The fixed view of a run: the bounding box of every drawn point over all samples (nodes, centres
// of mass, slider ranges, traces), scaled to fit the image less the margins, the same scale on x
// and y, centred in the space left between the time stamp (top) and the scale bar (bottom).
#include <algorithm>
#include <cmath>
#include <limits>

#include "canvas.hpp"
#include "mo2d/error.hpp"
#include "plan.hpp"

namespace mo2d {

Motion motion_of(const Trajectory& r) {
  return {r.time, r.q0, r.efforts, r.q1};
}

Motion single_configuration(const Eigen::VectorXd& q0, double t) {
  Motion m;
  m.time = Eigen::VectorXd::Constant(1, t);
  m.q0 = q0.transpose();
  return m;
}

Eigen::Vector2d to_pixel(const View& v, const Eigen::Vector2d& p) {
  return {0.5 * v.width + v.scale * (p.x() - v.centre.x()),
          0.5 * v.height - v.scale * (p.y() - v.centre.y())};
}

View fit_view(const Model& model, const Motion& motion, const FrameOptions& options) {
  return detail::make_plan(model, motion, options).view;
}

namespace detail {

namespace {

// Room (pixels) between the fitted motion and each border of the image: the symbols drawn around
// the nodes (body outlines, joints, effort arcs and arrows, ground pivots below their joint), at
// least the margin plus the time stamp (top) and the scale bar and axes (bottom).
struct Pads {
  double side = 0, top = 0, bottom = 0;
};

Pads pads(const FramePlan& p) {
  const FrameStyle& s = p.options.style;
  const FrameOptions& o = p.options;
  double around = std::max({0.5 * s.body_width + s.line_width, 1.6 * s.joint_radius});
  bool forces = false, torques = false, ground_pivots = false;
  for (const JointPart& j : p.parts.joints) {
    forces |= j.force_input >= 0;
    torques |= j.torque_input >= 0;
    ground_pivots |= j.kind == JointKind::revolute && (j.body1 < 0 || j.body2 < 0);
  }
  if (!p.forces.empty()) around = std::max(around, s.effort_length + 2.5 * s.line_width);
  if (!p.torques.empty()) around = std::max(around, s.effort_radius + 2.5 * s.line_width);
  if (o.show_efforts && p.motion->efforts.cols() > 0) {
    if (torques) around = std::max(around, s.effort_radius + 2.5 * s.line_width);
    if (forces) around = std::max(around, 2.5 * s.joint_radius + s.effort_length);
  }
  Pads d;
  d.side = o.margin + around;
  d.top = std::max(d.side, o.show_time || !o.title.empty() ? o.margin + 1.6 * s.font_size : 0.0);
  if (o.show_scale_bar && load_legend_lines(p) > 0)  // the legend of the loads under the time
    d.top = std::max(d.top, o.margin + (1.6 + 1.4 * load_legend_lines(p)) * s.font_size + around);
  d.bottom = std::max(d.side, o.margin + (ground_pivots ? 4.2 * s.joint_radius : 0.0));
  if (o.show_scale_bar || o.show_axes) d.bottom = std::max(d.bottom, o.margin + 2.2 * s.font_size);
  d.side *= p.P, d.top *= p.P, d.bottom *= p.P;
  return d;
}

}  // namespace

void check_sample(const Motion& motion, int sample) {
  if (sample < 0 || sample >= motion.time.size())
    throw Error("render: sample " + std::to_string(sample) + " is not in 0.." +
                    std::to_string(motion.time.size() - 1),
                "sample");
}

FramePlan make_plan(const Model& model, const Motion& motion, const FrameOptions& options) {
  check_size(options.width, options.height, options.dpi, "frame");
  const FrameStyle& st = options.style;
  for (double v : {st.body_width, st.line_width, st.joint_radius, st.com_radius, st.effort_radius,
                   st.effort_length, st.font_size, options.margin})
    if (!std::isfinite(v) || v < 0) throw Error("render: FrameStyle sizes must be finite and >= 0");
  if (st.palette.empty()) throw Error("render: FrameStyle::palette is empty", "palette");
  const Eigen::Index N = motion.time.size();
  if (N == 0) throw Error("render: the run has no samples", "time");
  if (motion.q0.rows() != N || motion.q0.cols() != model.n0)
    throw Error("render: coordinates are " + std::to_string(motion.q0.rows()) + " x " +
                    std::to_string(motion.q0.cols()) + ", expected samples x n0 = " +
                    std::to_string(N) + " x " + std::to_string(model.n0),
                "q0");
  if (motion.efforts.cols() != 0 &&
      (motion.efforts.rows() != N || motion.efforts.cols() != model.n_inputs()))
    throw Error("render: efforts are " + std::to_string(motion.efforts.rows()) + " x " +
                    std::to_string(motion.efforts.cols()) + ", expected samples x inputs = " +
                    std::to_string(N) + " x " + std::to_string(model.n_inputs()),
                "efforts");
  for (Eigen::Index k = 0; k < N; ++k) {
    if (!std::isfinite(motion.time[k]))
      throw Error("render: time of sample " + std::to_string(k) + " is not finite", "time");
    for (int c = 0; c < model.n0; ++c)
      if (!std::isfinite(motion.q0(k, c)))
        throw Error("render: coordinate '" + model.coordinate_labels[c] +
                        "' is not finite at t = " + std::to_string(motion.time[k]) + " s (sample " +
                        std::to_string(k) + ")",
                    model.coordinate_labels[c], motion.time[k]);
  }

  FramePlan p;
  p.model = &model;
  p.motion = &motion;
  p.options = options;
  p.P = options.dpi / 72.0;
  p.parts = mechanism_parts(model);
  for (const std::string& label : options.traces)
    p.trace_points.push_back(trace_point(model, label));
  plan_loads(p);
  plan_chains(p);

  // effort peaks (non-finite efforts are not drawn)
  p.peak.assign(model.n_inputs(), 0.0);
  if (motion.efforts.cols() > 0)
    for (int u = 0; u < model.n_inputs(); ++u)
      for (Eigen::Index k = 0; k < N; ++k)
        if (std::isfinite(motion.efforts(k, u)))
          p.peak[u] = std::max(p.peak[u], std::abs(motion.efforts(k, u)));

  // slider ranges, traces, bounding box
  Eigen::AlignedBox2d box;
  p.range.assign(p.parts.joints.size(), {0.0, 0.0});
  for (size_t j = 0; j < p.parts.joints.size(); ++j) {
    const JointPart& jp = p.parts.joints[j];
    if (jp.kind == JointKind::revolute) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Eigen::Index k = 0; k < N; ++k) {
      lo = std::min(lo, motion.q0(k, jp.q));
      hi = std::max(hi, motion.q0(k, jp.q));
    }
    p.range[j] = {lo, hi};
  }
  p.traces.assign(p.trace_points.size(), {});
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = motion.q0.row(k).transpose();
    for (const Body& b : model.bodies) {
      for (const NodeRef& n : b.nodes) box.extend(node_position(n, q0));
      box.extend(com_position(b, q0));
    }
    for (size_t t = 0; t < p.trace_points.size(); ++t) {
      p.traces[t].push_back(point_position(model, p.trace_points[t], q0));
      box.extend(p.traces[t].back());
    }
    for (size_t j = 0; j < p.parts.joints.size(); ++j) {
      const JointPart& jp = p.parts.joints[j];
      if (jp.kind == JointKind::revolute) {
        box.extend(node_position(jp.node, q0));
        continue;
      }
      const Vec2 a = node_position(jp.i, q0), d = node_position(jp.j, q0) - a;
      const Vec2 e = d.norm() > 0 ? Vec2(d / d.norm()) : Vec2(1, 0);
      box.extend(a + p.range[j].first * e);
      box.extend(a + p.range[j].second * e);
      if (jp.kind == JointKind::slot) box.extend(a), box.extend(a + d);
    }
  }
  plan_contacts(p, box);
  for (size_t j = 0; j < p.parts.joints.size(); ++j) {
    const JointPart& jp = p.parts.joints[j];
    if (jp.kind == JointKind::prismatic) {
      const double r = std::abs(p.range[j].second - p.range[j].first);
      p.range[j].first -= 0.04 * r;
      p.range[j].second += 0.04 * r;
    }
  }

  const double W = options.width, H = options.height;
  View& v = p.view;
  v.width = W;
  v.height = H;
  if (options.window) {
    const Eigen::AlignedBox2d& w = *options.window;
    if (w.isEmpty() || !(w.sizes().minCoeff() > 0) || !w.sizes().allFinite())
      throw Error("render: FrameOptions::window must have a positive, finite size", "window");
    v.scale = std::min(W / w.sizes().x(), H / w.sizes().y());
    v.centre = w.center();
  } else {
    const Pads pad = pads(p);
    const double tb = pad.top, bb = pad.bottom;
    const double aw = W - 2 * pad.side, ah = H - tb - bb;
    if (aw < 8 || ah < 8)
      throw Error("render: frame of " + std::to_string(options.width) + " x " +
                      std::to_string(options.height) +
                      " pixels is too small for its margins and symbols at " +
                      std::to_string(options.dpi) + " dpi",
                  "size");
    Vec2 size = box.sizes();
    const double floor = 1e-3 * std::max(model.scale, 1e-9);
    size = size.cwiseMax(floor);
    v.scale = std::min(aw / size.x(), ah / size.y());
    v.centre = box.center();
    v.centre.y() += (tb - bb) / (2 * v.scale);
  }
  if (N > 1) {
    const double dt = std::abs(motion.time[N - 1] - motion.time[0]) / static_cast<double>(N - 1);
    p.time_decimals =
        dt > 0 ? std::clamp(static_cast<int>(std::ceil(-std::log10(dt) - 1e-9)), 0, 6) : 2;
  }
  return p;
}

}  // namespace detail
}  // namespace mo2d
