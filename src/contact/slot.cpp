// A pin in a slot (slot.hpp, slot_set.hpp): the slot's checks and three parts, their gaps, and the
// run's switch of a pin into and out of its slot.
#include "contact/slot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/slot_set.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {
namespace {

Vec2 position(const Model& m, const BodyPoint& p, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  return p.body < 0 ? p.fixed
                    : local_position_of_point(m.bodies[p.body], q0, p.ci, p.cj, p.gamma, p.rho);
}

Jet coordinate(double p, double v) {
  return {p, v, 0.0};
}

const char* part_name(int part) {
  return part == kSlotLeft ? "left" : part == kSlotRight ? "right" : "end";
}

}  // namespace

void check_slot(const ContactDef& c) {
  if (!(std::isfinite(c.width) && c.width > 2 * c.radius))
    throw Error("contact '" + c.name +
                    "': a slot's width must be more than the pin's diameter 2 r = " +
                    fmt(2 * c.radius) + " m (got " + fmt(c.width) + ")",
                c.name);
  if (c.a == c.b)
    throw Error(
        "contact '" + c.name + "': the slot's ends a and b are the same point ('" + c.a + "')",
        c.name);
  if (c.law.friction > 0)
    throw Error("contact '" + c.name + "': friction in a slot is not modelled (friction " +
                    fmt(c.law.friction) + "; use friction: 0)",
                c.name);
}

void check_slot_points(const Model& m, const CompiledContact& c) {
  const ContactDef& d = c.def;
  if (c.a.body != c.b.body)
    throw Error("contact '" + d.name + "': the slot's ends '" + d.a + "' and '" + d.b +
                    "' are not on one body (or both on the ground)",
                d.name);
  const double L = (position(m, c.b, m.q0) - position(m, c.a, m.q0)).norm();
  if (!(L > d.radius))
    throw Error("contact '" + d.name + "': the slot from '" + d.a + "' to '" + d.b + "' is " +
                    fmt(L) + " m long, not longer than the pin's radius " + fmt(d.radius) + " m",
                d.name);
}

void compile_contacts(const Model& m, const ContactDef& c, std::vector<CompiledContact>& out) {
  CompiledContact cc = compile_contact(m, c);
  if (c.target != ContactDef::Target::slot) {
    out.push_back(std::move(cc));
    return;
  }
  for (int part : {kSlotLeft, kSlotRight, kSlotEnd}) {
    CompiledContact p = cc;
    p.part = part;
    p.def.name = c.name + "." + part_name(part);
    out.push_back(std::move(p));
  }
}

void slot_gap_into(const Model& m, const CompiledContact& c,
                   const Eigen::Ref<const Eigen::VectorXd>& q0,
                   const Eigen::Ref<const Eigen::VectorXd>& q1, GapValue& out) {
  if (c.part < 0)
    throw Error(
        "contact '" + c.def.name +
            "': a slot has three gaps (its walls and its end), not one: slots are supported "
            "by forward dynamics only (not by contact_gap or inverse dynamics yet)",
        c.def.name);
  const PointState P = point_state(m, c.p, q0, q1), A = point_state(m, c.a, q0, q1),
                   B = point_state(m, c.b, q0, q1);
  const Jet g = slot_gap(coordinate(P.p.x(), P.v.x()), coordinate(P.p.y(), P.v.y()),
                         coordinate(A.p.x(), A.v.x()), coordinate(A.p.y(), A.v.y()),
                         coordinate(B.p.x(), B.v.x()), coordinate(B.p.y(), B.v.y()), c.def.radius,
                         c.def.width, c.part, c.inside);
  const LineGradient d = slot_gradient(P.p, A.p, B.p, c.def.width, c.part, c.inside);
  add_point_gradient(m, c.p, d.dP, out.J);
  add_point_gradient(m, c.a, d.dA, out.J);
  add_point_gradient(m, c.b, d.dB, out.J);
  // the value as gap_only computes it (the Jets' hypot rounds differently): the run compares the
  // two's signs (a slack reset on one, the condition on the other), which must agree at a contact
  out.g = slot_gap_only(m, c, q0);
  out.rate = g.d;
  out.curvature = g.dd;
}

double slot_gap_only(const Model& m, const CompiledContact& c,
                     const Eigen::Ref<const Eigen::VectorXd>& q0) {
  if (c.part < 0) {
    GapValue unused;
    slot_gap_into(m, c, q0, q0, unused);  // throws
  }
  const Vec2 P = position(m, c.p, q0), A = position(m, c.a, q0), B = position(m, c.b, q0);
  return slot_gap(P.x(), P.y(), A.x(), A.y(), B.x(), B.y(), c.def.radius, c.def.width, c.part,
                  c.inside);
}

SlotRegions::SlotRegions(std::vector<CompiledContact>& contacts) : cs_(contacts) {
  for (size_t i = 0; i < cs_.size(); ++i)
    if (cs_[i].part == kSlotLeft) {
      const std::string& n = cs_[i].def.name;
      slots_.push_back({i, n.substr(0, n.size() - 5), 0.0});  // "NAME.left"
    }
}

double SlotRegions::raw(const Model& m, const Slot& s, const Eigen::VectorXd& q0, int& side) const {
  const CompiledContact& c = cs_[s.first];
  const SlotCoordinates x =
      slot_coordinates(position(m, c.p, q0), position(m, c.a, q0), position(m, c.b, q0));
  const double half = c.def.width / 2;
  const double f[3] = {x.L - x.s, half - std::abs(x.l), x.s};  // mouth, wall, closed end
  side = 0;
  if (c.inside) {
    for (int k = 1; k < 3; ++k)
      if (f[k] < f[side]) side = k;
    return f[side];
  }
  for (int k = 1; k < 3; ++k)
    if (-f[k] > -f[side]) side = k;
  return -f[side];
}

void SlotRegions::start(const Model& m, const Eigen::VectorXd& q0) {
  for (Slot& s : slots_) {
    for (size_t k = 0; k < 3; ++k) cs_[s.first + k].inside = false;
    int side = 0;
    const bool in = raw(m, s, q0, side) < 0;  // outside's condition negative: inside
    for (size_t k = 0; k < 3; ++k) cs_[s.first + k].inside = in;
    s.slack = 0;
  }
}

double SlotRegions::condition(const Model& m, const Eigen::VectorXd& q0) const {
  double c = 1e300;
  int side = 0;
  for (const Slot& s : slots_) c = std::min(c, raw(m, s, q0, side) + s.slack);
  return c;
}

void SlotRegions::step_end(const Model& m, const Eigen::VectorXd& q0) {
  int side = 0;
  for (Slot& s : slots_) {
    if (s.unslack) s.slack = 0, s.unslack = false;
    s.unslack = s.slack > 0 && raw(m, s, q0, side) > 0;
  }
}

int SlotRegions::handle(const Model& m, double t, const Eigen::VectorXd& q0,
                        std::vector<ContactEvent>& events) {
  int switched = 0;
  for (Slot& s : slots_) {
    int side = 0;
    const double c = raw(m, s, q0, side);
    if (!(c + s.slack <= 0)) continue;
    CompiledContact& left = cs_[s.first];
    const bool in = left.inside;
    if (side != 0) {
      const SlotCoordinates x = slot_coordinates(position(m, left.p, q0), position(m, left.a, q0),
                                                 position(m, left.b, q0));
      throw Error("contact '" + s.name + "': the pin '" + left.def.point +
                      (in ? "' leaves its slot through " : "' enters its slot through ") +
                      (side == 1 ? "a wall" : "the closed end") + " at t = " + fmt(t) + " s (s = " +
                      fmt(x.s) + " m along the slot of length " + fmt(x.L) + " m, l = " + fmt(x.l) +
                      " m across it, half width " + fmt(left.def.width / 2) +
                      " m): a pin enters and leaves a slot through its mouth; the slot's "
                      "outside is not modelled" +
                      (in ? " (a compliant wall penetrated through?)" : ""),
                  s.name, t);
    }
    for (size_t k = 0; k < 3; ++k) cs_[s.first + k].inside = !in;
    const double now = raw(m, s, q0, side);
    s.slack = std::abs(now) * (1 + 16 * std::numeric_limits<double>::epsilon()) + 1e-300;
    events.push_back(
        {in ? ContactEvent::Kind::leave : ContactEvent::Kind::enter, t, s.name, 0, 0, 0, 0, 0});
    ++switched;
  }
  return switched;
}

}  // namespace mo2d::detail
