// The numbers of a frame's drawing (mo2d/render/drawing.hpp): the same plan and the same
// geometry as the Painter of frame.cpp (body hulls, pins, blocks, rails, slots, centres of mass)
// and render/contacts.cpp (the contacts).
#include "mo2d/render/drawing.hpp"

#include <algorithm>

#include "plan.hpp"
#include "symbols.hpp"

namespace mo2d {

namespace {

const char* kind_name(detail::JointKind k) {
  switch (k) {
    case detail::JointKind::revolute:
      return "revolute";
    case detail::JointKind::prismatic:
      return "prismatic";
    case detail::JointKind::slot:
      return "slot";
  }
  return "revolute";
}

const char* target_name(ContactDef::Target t) {
  switch (t) {
    case ContactDef::Target::line:
      return "line";
    case ContactDef::Target::circle:
      return "circle";
    case ContactDef::Target::hole:
      return "hole";
    case ContactDef::Target::slot:
      return "slot";
    case ContactDef::Target::profile:  // the page draws its point only (docs/viewer.md)
      return "profile";
  }
  return "line";
}

// The contacts' static part (the per-sample points: drawn_sample).
std::vector<DrawnContact> drawn_contacts(const detail::FramePlan& p) {
  std::vector<DrawnContact> out;
  const double scale = p.view.scale;
  for (size_t c = 0; c < p.options.contacts.size(); ++c) {
    const ContactDef& def = p.options.contacts[c];
    out.push_back(
        {.name = def.name,
         .target = target_name(def.target),
         .point_body = p.contact_bodies[c].first,
         .target_body = p.contact_bodies[c].second,
         .radius = std::max(def.radius * scale, p.P * 0.6 * p.options.style.joint_radius),
         .target_radius = def.target_radius * scale,
         .half_width = def.target == ContactDef::Target::slot ? def.width / 2 * scale : 0.0});
  }
  return out;
}

DrawnSample drawn_sample(const detail::FramePlan& p, const Drawing& d, int k) {
  const Model& m = *p.model;
  const Eigen::VectorXd q0 = p.motion->q0.row(k).transpose();
  auto node = [&](const NodeRef& n) { return Vec2(to_pixel(p.view, node_position(n, q0))); };
  DrawnSample s;
  s.time = p.motion->time[k];
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    std::vector<Vec2> pts;
    if (!p.parts.block[b])
      for (const NodeRef& n : m.bodies[b].nodes) pts.push_back(node(n));
    s.hulls.push_back(detail::convex_hull(pts));
    s.coms.emplace_back(to_pixel(p.view, com_position(m.bodies[b], q0)));
  }
  for (size_t j = 0; j < p.parts.joints.size(); ++j) {
    const detail::JointPart& jp = p.parts.joints[j];
    if (jp.kind == detail::JointKind::revolute) {
      s.joints.push_back(node(jp.node));
      s.axes.emplace_back(1, 0);
      s.rails.emplace_back(s.joints.back(), s.joints.back());
      continue;
    }
    const Vec2 a = node(jp.i), dv = node(jp.j) - a;
    const Vec2 e = dv.norm() > 0 ? Vec2(dv / dv.norm()) : Vec2(1, 0);
    s.joints.push_back(node(jp.s));
    s.axes.push_back(e);
    const double pad =
        jp.kind == detail::JointKind::prismatic ? d.block_half_length + p.P * 4 : 0.0;
    s.rails.emplace_back(a + (p.range[j].first * p.view.scale - pad) * e,
                         a + (p.range[j].second * p.view.scale + pad) * e);
  }
  if (!p.contacts.empty())
    for (const detail::FramePlan::ContactAt& c : p.contacts[static_cast<size_t>(k)])
      s.contacts.push_back(
          {Vec2(to_pixel(p.view, c.p)), Vec2(to_pixel(p.view, c.a)), Vec2(to_pixel(p.view, c.b))});
  return s;
}

}  // namespace

Drawing drawing_of(const Model& model, const Motion& motion, const FrameOptions& options,
                   const std::vector<int>& samples) {
  const detail::FramePlan p = detail::make_plan(model, motion, options);
  const FrameStyle& st = options.style;
  Drawing d;
  d.view = p.view;
  d.style = st;
  d.line_width = p.P * st.line_width;
  d.joint_radius = p.P * st.joint_radius;
  d.com_radius = p.P * st.com_radius;
  d.block_half_length = p.P * 2.3 * st.joint_radius;
  d.block_half_height = p.P * 1.6 * st.joint_radius;
  d.slot_width = 2 * p.P * (st.joint_radius + 0.35);
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    d.body_names.push_back(model.bodies[b].name);
    d.body_colours.push_back(st.palette[b % st.palette.size()]);
    double width = p.P * st.body_width;
    if (model.bodies[b].nodes.size() == 1) width = p.P * 1.25 * st.body_width;
    if (p.parts.slotted[b]) width = std::max(width, d.slot_width + 2 * p.P * (2.2 + st.line_width));
    d.body_widths.push_back(width);
    d.body_has_com.push_back(model.bodies[b].mass > 0);
  }
  for (const detail::JointPart& jp : p.parts.joints)
    d.joints.push_back(
        {.name = jp.name,
         .kind = kind_name(jp.kind),
         .body1 = jp.body1,
         .body2 = jp.body2,
         .ground_pivot = jp.kind == detail::JointKind::revolute && (jp.body1 < 0 || jp.body2 < 0),
         .pin = jp.kind != detail::JointKind::prismatic});
  d.contacts = drawn_contacts(p);
  for (int k : samples) {
    detail::check_sample(motion, k);
    d.samples.push_back(drawn_sample(p, d, k));
  }
  return d;
}

}  // namespace mo2d
