// Stage 1b of build_model: bodies given by their shape (BodyDef::shape). Their node positions in
// Flat are a sketch; this stage places each such body rigidly where the joints close, nearest to
// its sketch (the problem and the method: sketch_solve.hpp), and writes the placed positions back
// into Flat, so that the later stages see exact positions as if the user had written them. The
// ground and the bodies without a shape are held where they are written. Runs only when some body
// has a shape (otherwise Flat is untouched).
#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>

#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/sketch_solve.hpp"

namespace mo2d::build {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}
std::string point_str(const Vec2& p) {
  std::ostringstream s;  // one stream: GCC 12 warns (-Wrestrict, a false positive) on "(" + string
  s.precision(4);
  s << '(' << p.x() << ", " << p.y() << ')';
  return s.str();
}

// The inverse of a placement: p = R x + o -> x.
Vec2 unplace(const Placement& f, const Vec2& p) {
  return Placement{{0, 0}, -f.angle}.apply(p - f.offset);
}

// A joint as the sketch sees it: its closure, its words for messages and the bodies it joins
// (flat body indices, -1 the ground) for the loop of an error.
struct JointInfo {
  std::string what;     // "revolute joint 'rocker_pin'"
  std::string element;  // "rocker_pin" (full name)
  std::string nodes;    // "nodes 'coupler.B' and 'rocker.B'"
  int body1 = -1, body2 = -1;
};

struct Setup {
  Elements el;
  std::vector<int> free_of_body;  // flat body -> free body, -1 without a shape
  std::vector<int> body_of_free;
  sketch::Problem problem;
  std::vector<JointInfo> joints;  // every joint (also those without a closure), for the loops
};

void check_shapes(const Flat& flat) {
  for (const auto& owned : flat.bodies) {
    const BodyDef& d = owned.def;
    if (d.shape.empty()) continue;
    if (d.shape.size() != d.nodes.size())
      throw Error("body '" + d.name + "': its shape has " + std::to_string(d.shape.size()) +
                      " point(s) for " + std::to_string(d.nodes.size()) +
                      " node(s) (one per node, in the order of the nodes)",
                  d.name);
    for (size_t k = 0; k < d.shape.size(); ++k)
      if (!d.shape[k].allFinite())
        throw Error(
            "body '" + d.name + "': the shape of node '" + d.nodes[k].name + "' is not finite",
            d.name);
  }
}

sketch::Point point_of(const Setup& s, int e) {
  const int b = s.el.body[e];
  if (b >= 0 && s.free_of_body[b] >= 0) return {s.free_of_body[b], s.el.local[e], {0, 0}};
  return {-1, -1, s.el.position[e]};
}

bool is_free(const Setup& s, int e) {
  return s.el.body[e] >= 0 && s.free_of_body[s.el.body[e]] >= 0;
}

// Length of the axis i -> j of a joint, from the shape when its body has one.
double axis_length(const Setup& s, const Flat& flat, int ei, int ej) {
  const int b = s.el.body[ei];
  if (b >= 0 && s.free_of_body[b] >= 0) {
    const auto& shape = flat.bodies[b].def.shape;
    return (shape[s.el.local[ej]] - shape[s.el.local[ei]]).norm();
  }
  return (s.el.position[ej] - s.el.position[ei]).norm();
}

// Closures of the joints that touch a body with a shape; joints that validate refuses (same
// body, two ground nodes, an axis across bodies or of zero length) are left to it.
void add_joints(const Flat& flat, Setup& s) {
  for (const auto& j : flat.revolutes) {
    const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
    const int ea = s.el.resolve(j.prefix, j.def.node_a, what);
    const int eb = s.el.resolve(j.prefix, j.def.node_b, what);
    s.joints.push_back({what, j.prefix + j.def.name,
                        "nodes '" + s.el.label[ea] + "' and '" + s.el.label[eb] + "'",
                        s.el.body[ea], s.el.body[eb]});
    if (s.el.body[ea] == s.el.body[eb] || (!is_free(s, ea) && !is_free(s, eb))) continue;
    sketch::Closure c;
    c.a = point_of(s, ea);
    c.b = point_of(s, eb);
    c.joint = static_cast<int>(s.joints.size()) - 1;
    s.problem.closures.push_back(c);
  }
  auto axis_joint = [&](const std::string& what, const std::string& element,
                        const std::string& from, const std::string& to, const std::string& slider,
                        const std::string& prefix, const char* slider_word) {
    const int ei = s.el.resolve(prefix, from, what), ej = s.el.resolve(prefix, to, what);
    const int es = s.el.resolve(prefix, slider, what);
    s.joints.push_back({what, element,
                        std::string(slider_word) + " '" + s.el.label[es] + "' and axis '" +
                            s.el.label[ei] + "' -> '" + s.el.label[ej] + "'",
                        s.el.body[ei], s.el.body[es]});
    if (s.el.body[ej] != s.el.body[ei] || s.el.body[es] == s.el.body[ei]) return;
    if (!is_free(s, ei) && !is_free(s, es)) return;
    if (!(axis_length(s, flat, ei, ej) >= 1e-9 * s.problem.size)) return;
    sketch::Closure c;
    c.on_line = true;
    c.a = point_of(s, ei);
    c.b = point_of(s, ej);
    c.c = point_of(s, es);
    c.joint = static_cast<int>(s.joints.size()) - 1;
    s.problem.closures.push_back(c);
  };
  for (const auto& j : flat.prismatics)
    axis_joint("prismatic joint '" + j.prefix + j.def.name + "'", j.prefix + j.def.name,
               j.def.axis_from, j.def.axis_to, j.def.slider, j.prefix, "slider");
  for (const auto& j : flat.slots)
    axis_joint("pin-in-slot joint '" + j.prefix + j.def.name + "'", j.prefix + j.def.name,
               j.def.axis_from, j.def.axis_to, j.def.pin, j.prefix, "pin");
}

Setup make_setup(const Flat& flat, const BuildOptions& options) {
  Setup s;
  Model scratch;  // collect_elements writes the scale
  s.el = collect_elements(flat, options, scratch);
  s.problem.size = scratch.scale;
  s.problem.tolerance = options.assembly_tolerance * scratch.scale;
  for (size_t b = 0; b < flat.bodies.size(); ++b) {
    const BodyDef& d = flat.bodies[b].def;
    if (d.shape.empty()) {
      s.free_of_body.push_back(-1);
      continue;
    }
    if (d.shape.size() >= 2 && !((d.shape[1] - d.shape[0]).norm() >= 1e-9 * scratch.scale))
      throw Error("body '" + d.name +
                      "': the first two nodes of its shape coincide (a body needs "
                      "two distinct reference nodes)",
                  d.name);
    s.free_of_body.push_back(static_cast<int>(s.problem.bodies.size()));
    s.body_of_free.push_back(static_cast<int>(b));
    sketch::FreeBody fb;
    fb.shape = d.shape;
    for (const auto& n : d.nodes) fb.sketch.push_back(n.position);
    s.problem.bodies.push_back(std::move(fb));
  }
  add_joints(flat, s);
  return s;
}

// The bodies of a loop through joint `j`: a path from its body 2 back to its body 1 through the
// other joints (breadth first), written "ground -> crank -> coupler -> rocker -> ground".
std::string loop_through(const Flat& flat, const std::vector<JointInfo>& joints, int j) {
  const int NB = static_cast<int>(flat.bodies.size());
  auto vertex = [NB](int b) { return b < 0 ? NB : b; };
  auto name = [&](int v) { return v == NB ? std::string("ground") : flat.bodies[v].def.name; };
  const int from = vertex(joints[j].body2), to = vertex(joints[j].body1);
  std::vector<int> parent(NB + 1, -2);
  std::deque<int> queue{from};
  parent[from] = -1;
  while (!queue.empty() && parent[to] == -2) {
    const int v = queue.front();
    queue.pop_front();
    for (size_t k = 0; k < joints.size(); ++k) {
      if (static_cast<int>(k) == j) continue;
      const int a = vertex(joints[k].body1), b = vertex(joints[k].body2);
      const int w = a == v ? b : b == v ? a : -1;
      if (w < 0 || parent[w] != -2) continue;
      parent[w] = v;
      queue.push_back(w);
    }
  }
  if (parent[to] == -2) return "";
  std::string path = name(to);
  for (int v = to; v != from;) {
    v = parent[v];
    path = name(v) + " -> " + path;
  }
  return name(to) + " -> " + path;
}

[[noreturn]] void refuse_open(const Flat& flat, const Setup& s, const sketch::Result& r) {
  std::vector<size_t> open;  // closures left open, largest gap first
  for (size_t k = 0; k < r.gaps.size(); ++k)
    if (!(r.gaps[k] <= s.problem.tolerance)) open.push_back(k);
  std::stable_sort(open.begin(), open.end(),
                   [&](size_t a, size_t b) { return r.gaps[a] > r.gaps[b]; });
  const JointInfo& j = s.joints[s.problem.closures[open[0]].joint];
  const std::string loop = loop_through(flat, s.joints, s.problem.closures[open[0]].joint);
  std::string gaps;
  double total = 0;
  for (size_t k = 0; k < open.size(); ++k) {
    total += r.gaps[open[k]];
    if (k < 4)
      gaps += std::string(k ? ", " : "") + "'" +
              s.joints[s.problem.closures[open[k]].joint].element + "' by " + num(r.gaps[open[k]]) +
              " m";
  }
  if (open.size() > 4) gaps += ", ...";
  throw Error("the bodies given by their shape cannot be assembled: " + j.what + " (" + j.nodes +
                  ") stays open" + (loop.empty() ? std::string() : " in the loop " + loop) +
                  "; closing the joints as far as the shapes allow leaves open " + gaps + " (" +
                  num(total) +
                  " m in all). The shapes are exact: no configuration closes "
                  "the loop with these lengths (or the sketch is too far from one that does)",
              j.element);
}

// Writes the placed positions back into Flat: nodes, the centre-of-mass point, and the points of
// forces, named points, springs and chains on the body, which its frame gives.
void place(Flat& flat, const Setup& s, const sketch::Result& r, SketchReport& report) {
  for (size_t f = 0; f < s.body_of_free.size(); ++f) {
    BodyDef& d = flat.bodies[s.body_of_free[f]].def;
    const sketch::Pose& pose = r.poses[f];
    for (size_t k = 0; k < d.nodes.size(); ++k) {
      report.nodes.push_back({d.name + "." + d.nodes[k].name, d.nodes[k].position, {0, 0}, 0});
      d.nodes[k].position = pose.apply(d.shape[k]);
    }
    if (d.com && d.com->kind == CenterOfMass::Kind::point) d.com->point = pose.apply(d.com->point);
  }
  auto pose_of = [&](const std::string& prefix, const std::string& body) -> const sketch::Pose* {
    for (size_t f = 0; f < s.body_of_free.size(); ++f)
      if (flat.bodies[s.body_of_free[f]].def.name == prefix + body) return &r.poses[f];
    return nullptr;
  };
  for (auto& force : flat.forces)
    if (const sketch::Pose* p = pose_of(force.prefix, force.def.body))
      force.def.point = p->apply(unplace(flat.frames[force.owner], force.def.point));
  for (auto& point : flat.points)
    if (const sketch::Pose* p = pose_of(point.prefix, point.def.body))
      point.def.point = p->apply(unplace(flat.frames[point.owner], point.def.point));
  for (auto& spring : flat.springs) {
    if (const sketch::Pose* p = pose_of(spring.prefix, spring.def.body_a))
      spring.def.point_a = p->apply(unplace(flat.frames[spring.owner], spring.def.point_a));
    if (const sketch::Pose* p = pose_of(spring.prefix, spring.def.body_b))
      spring.def.point_b = p->apply(unplace(flat.frames[spring.owner], spring.def.point_b));
  }
  for (auto& chain : flat.chains) {
    if (const sketch::Pose* p = pose_of(chain.prefix, chain.def.body_a))
      chain.def.centre_a = p->apply(unplace(flat.frames[chain.owner], chain.def.centre_a));
    if (const sketch::Pose* p = pose_of(chain.prefix, chain.def.body_b))
      chain.def.centre_b = p->apply(unplace(flat.frames[chain.owner], chain.def.centre_b));
  }
}

}  // namespace

SketchReport resolve_sketches(Flat& flat, const BuildOptions& options) {
  SketchReport report;
  bool any = false;
  for (const auto& b : flat.bodies) any = any || !b.def.shape.empty();
  if (!any) return report;
  check_shapes(flat);
  const Setup s = make_setup(flat, options);
  const sketch::Result r = sketch::solve_sketch(s.problem);
  if (!r.closed) refuse_open(flat, s, r);
  place(flat, s, r, report);
  report.nearest = r.nearest;
  if (!r.nearest)
    report.warnings.push_back(
        "the bodies given by their shape were placed where their joints close, but not exactly "
        "at the configuration nearest to their sketch (the distance to it still decreases by " +
        num(r.tangential) + " m per step): the sketch may be far from the configuration");
  return report;
}

void complete_sketch_report(Model& m) {
  for (SketchedNode& n : m.sketch.nodes) {
    for (const Body& b : m.bodies)
      for (size_t k = 0; k < b.node_names.size(); ++k)
        if (b.node_names[k] == n.label) n.assembled = node_position(b.nodes[k], m.q0);
    n.moved = (n.assembled - n.sketch).norm();
    if (n.moved > SketchReport::kSketchWarnFraction * m.scale)
      m.sketch.warnings.push_back(
          "node '" + n.label + "' moved " + num(n.moved) + " m from its sketch " +
          point_str(n.sketch) + " to " + point_str(n.assembled) + " (" +
          num(100 * n.moved / m.scale) + " % of the mechanism's size " + num(m.scale) +
          " m): the sketch is far from the assembled configuration, which may be on another "
          "branch than the one sketched");
  }
}

}  // namespace mo2d::build
