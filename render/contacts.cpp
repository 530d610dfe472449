// Contacts in a frame (FrameOptions::contacts; mo2d/contact.hpp, docs/contact.md): each contact's
// circle of radius r around its moving point (a small ring for a point contact, r = 0), and what it
// touches, at its true size in the world:
//  - a line through a and b: the segment a-b, hatched on the obstacle's side (the right of
//    a -> b: the free side is the left); the gap is measured to the whole line, the segment shows
//    where the user put it;
//  - a circle of radius R around a (touched from outside): its outline, hatched inside;
//  - a hole of radius R around a (the circle is inside it): its outline, hatched outside;
//  - a slot of width w from its closed end a to its mouth b: its two walls (a -> b, w/2 to
//    either side of the centre line) and its flat end across a, each hatched outside the slot.
//  - a cam profile r(phi) around a (axis a -> b): the closed polyline of its spline at 360 angles,
//    on its body.
// The shapes are outlined in a dark shade of their body's colour (the ground's grey on the ground),
// over the bodies, so a closed contact shows as two outlines that touch.
#include <algorithm>
#include <cmath>

#include "canvas.hpp"
#include "contact/contact_set.hpp"
#include "contact/profile.hpp"
#include "dynamics/points.hpp"
#include "plan.hpp"
#include "symbols.hpp"

namespace mo2d::detail {

void plan_contacts(FramePlan& p, Eigen::AlignedBox2d& box) {
  const Model& m = *p.model;
  const Motion& mo = *p.motion;
  if (p.options.contacts.empty()) return;
  const Eigen::Index N = mo.time.size();
  std::vector<CompiledContact> compiled;
  for (const ContactDef& c : p.options.contacts) compiled.push_back(compile_contact(m, c));
  p.contacts.assign(N, std::vector<FramePlan::ContactAt>(compiled.size()));
  const Eigen::VectorXd q1 = Eigen::VectorXd::Zero(m.n1);
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = mo.q0.row(k).transpose();
    for (size_t c = 0; c < compiled.size(); ++c) {
      const CompiledContact& cc = compiled[c];
      FramePlan::ContactAt& a = p.contacts[k][c];
      a.p = point_state(m, cc.p, q0, q1).p;
      a.a = point_state(m, cc.a, q0, q1).p;
      const bool two = cc.def.target == ContactDef::Target::line ||
                       cc.def.target == ContactDef::Target::slot ||
                       cc.def.target == ContactDef::Target::profile;
      a.b = two ? point_state(m, cc.b, q0, q1).p : a.a;
      // the target's reach around a: a slot's half width, a profile's largest radius (a margin
      // for the spline)
      double reach = cc.def.target_radius;
      if (cc.def.target == ContactDef::Target::slot) reach += cc.def.width / 2;
      if (cc.def.target == ContactDef::Target::profile)
        for (double y : cc.def.profile->y()) reach = std::max(reach, 1.05 * y);
      const Vec2 r(cc.def.radius, cc.def.radius), R(reach, reach);
      box.extend(a.p - r), box.extend(a.p + r);
      box.extend(a.a - R), box.extend(a.a + R);
      const Vec2 W = cc.def.target == ContactDef::Target::slot ? R : Vec2(0, 0);  // its mouth
      box.extend(a.b - W), box.extend(a.b + W);
    }
  }
  p.contact_bodies.clear();
  for (const CompiledContact& cc : compiled) p.contact_bodies.push_back({cc.p.body, cc.a.body});
}

namespace {

Rgb shape_colour(const FrameStyle& s, int body) {
  return body < 0 ? s.ground : dark_shade(s.palette[static_cast<size_t>(body) % s.palette.size()]);
}

// The profile r around a (axis a -> b, world), as a closed polyline in pixels.
void profile_outline(cairo_t* cr, const FramePlan& p, const LookupTable& r, const Vec2& a,
                     const Vec2& b) {
  cairo_new_path(cr);
  for (int i = 0; i < 360; ++i) {
    const Vec2 q = to_pixel(p.view, profile_point(r, a, b, 2 * kPi * i / 360));
    if (i == 0)
      cairo_move_to(cr, q.x(), q.y());
    else
      cairo_line_to(cr, q.x(), q.y());
  }
  cairo_close_path(cr);
  cairo_stroke(cr);
}

void circle(cairo_t* cr, const Vec2& c, double r) {
  cairo_new_path(cr);
  cairo_arc(cr, c.x(), c.y(), r, 0, 2 * kPi);
  cairo_stroke(cr);
}

// Short strokes along the circle of radius r around c, pointing `inward` (+1) or outward (-1).
void hatched_circle(cairo_t* cr, const Vec2& c, double r, double depth, int inward) {
  const int n = std::clamp(static_cast<int>(2 * kPi * r / (2.5 * depth)), 8, 96);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    const Vec2 u(std::cos(t), std::sin(t));
    const Vec2 from = c + r * u, to = from - inward * depth * (u + 0.6 * Vec2(-u.y(), u.x()));
    cairo_move_to(cr, from.x(), from.y());
    cairo_line_to(cr, to.x(), to.y());
  }
  cairo_stroke(cr);
}

// A slot from its closed end pa to its mouth pb (pixels), `half` = w/2 in pixels: the walls and
// the end, hatched on the material's side (outside the channel).
void draw_slot(cairo_t* cr, const Vec2& pa, const Vec2& pb, double half, double depth,
               const Rgb& colour, double width) {
  const Vec2 d = pb - pa;
  if (!(d.norm() > 0)) return;
  const Vec2 t = d / d.norm(), n(-t.y(), t.x());  // n: one side of the centre line, in pixels
  for (const double k : {1.0, -1.0})
    draw_hatched_line(cr, pa + k * half * n, pb + k * half * n, k * n, depth, colour, width);
  draw_hatched_line(cr, pa - half * n, pa + half * n, -t, depth, colour, width);
}

}  // namespace

void draw_contacts(cairo_t* cr, const FramePlan& p, int k) {
  if (p.contacts.empty()) return;
  const FrameStyle& s = p.options.style;
  const double P = p.P, scale = p.view.scale, depth = P * 0.9 * s.joint_radius;
  cairo_set_dash(cr, nullptr, 0, 0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (size_t c = 0; c < p.contacts[k].size(); ++c) {
    const ContactDef& def = p.options.contacts[c];
    const FramePlan::ContactAt& a = p.contacts[k][c];
    const auto [point_body, target_body] = p.contact_bodies[c];
    const Vec2 pp = to_pixel(p.view, a.p), pa = to_pixel(p.view, a.a);
    cairo_set_line_width(cr, P * s.line_width);
    set_colour(cr, shape_colour(s, target_body));
    if (def.target == ContactDef::Target::line) {
      const Vec2 pb = to_pixel(p.view, a.b), d = pb - pa;
      // the obstacle's side: the right of a -> b in the world, which the image's flipped y turns
      // into the left of a -> b in pixels
      const Vec2 obstacle = d.norm() > 0 ? Vec2(Vec2(-d.y(), d.x()) / d.norm()) : Vec2(0, 1);
      draw_hatched_line(cr, pa, pb, obstacle, depth, shape_colour(s, target_body),
                        P * s.line_width);
    } else if (def.target == ContactDef::Target::slot) {
      draw_slot(cr, pa, to_pixel(p.view, a.b), def.width / 2 * scale, depth,
                shape_colour(s, target_body), P * s.line_width);
    } else if (def.target == ContactDef::Target::profile) {
      if (a.b != a.a) profile_outline(cr, p, *def.profile, a.a, a.b);
    } else if (def.target == ContactDef::Target::circle || def.target == ContactDef::Target::hole) {
      const double R = def.target_radius * scale;
      circle(cr, pa, R);
      cairo_set_line_width(cr, P * 0.6 * s.line_width);
      hatched_circle(cr, pa, R, std::min(depth, 0.5 * R),
                     def.target == ContactDef::Target::circle ? 1 : -1);
    }
    cairo_set_line_width(cr, P * s.line_width);
    set_colour(cr, shape_colour(s, point_body));
    circle(cr, pp, std::max(def.radius * scale, P * 0.6 * s.joint_radius));
  }
}

}  // namespace mo2d::detail
