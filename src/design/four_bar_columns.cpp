// The columns of a four-bar loop in a run (mo2d/design.hpp): input and output angles,
// transmission angle, velocity ratio, and coupler points on the other assembly branch; the loop's
// lengths at the initial configuration.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "design/design_internal.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "model/suggest.hpp"

namespace mo2d::design_detail {

namespace {

double wrap_pi(double a) {
  return std::remainder(a, 2 * std::numbers::pi);
}

// The loop's four nodes, the pivots checked to be fixed.
struct Loop {
  NodeAt a0, a, b, b0;
};
Loop find_loop(const Model& m, const FourBarDef& f) {
  const std::string what = "four-bar '" + f.name + "'";
  Loop l{find_node(m, f.input_pivot, what + ": input pivot"),
         find_node(m, f.input_pin, what + ": input pin"),
         find_node(m, f.output_pin, what + ": output pin"),
         find_node(m, f.output_pivot, what + ": output pivot")};
  for (const auto& [node, label] : {std::pair{&l.a0, &f.input_pivot}, {&l.b0, &f.output_pivot}})
    if (node->ref.var >= 0)
      throw Error(what + ": the pivot '" + *label + "' is not fixed to the ground", f.name);
  for (const auto& [node, label] : {std::pair{&l.a, &f.input_pin}, {&l.b, &f.output_pin}})
    if (node->ref.var < 0)
      throw Error(what + ": the pin '" + *label + "' is fixed to the ground", f.name);
  return l;
}

}  // namespace

NodeAt find_node(const Model& m, const std::string& label, const std::string& what) {
  for (size_t g = 0; g < m.ground_names.size(); ++g)
    if (m.ground_names[g] == label) return {NodeRef{.var = -1, .fixed = m.ground_positions[g]}, -1};
  std::vector<std::string> names = m.ground_names;
  for (size_t b = 0; b < m.bodies.size(); ++b)
    for (size_t k = 0; k < m.bodies[b].node_names.size(); ++k) {
      if (m.bodies[b].node_names[k] == label) return {m.bodies[b].nodes[k], static_cast<int>(b)};
      names.push_back(m.bodies[b].node_names[k]);
    }
  throw Error(what + ": no node '" + label + "'" + did_you_mean(label, names), label);
}

Block four_bar_columns(const Model& m, const Trajectory& r, const FourBarDef& f) {
  const Loop l = find_loop(m, f);
  std::vector<int> points;
  for (const std::string& name : f.coupler_points) {
    int found = -1;
    std::vector<std::string> names;
    for (size_t k = 0; k < m.points.size(); ++k) {
      names.push_back(m.points[k].name);
      if (m.points[k].name == name) found = static_cast<int>(k);
    }
    if (found < 0)
      throw Error(
          "four-bar '" + f.name + "': no named point '" + name + "'" + did_you_mean(name, names),
          name);
    if (l.a.body != l.b.body || m.points[found].point.body != l.a.body)
      throw Error("four-bar '" + f.name + "': coupler point '" + name +
                      "' needs both pins and the point on one body (the coupler): give the pins "
                      "as nodes of the coupler",
                  name);
    points.push_back(found);
  }
  Block out;
  for (const char* c : {"input_angle", "output_angle", "transmission_angle", "velocity_ratio"})
    out.labels.push_back(f.name + "." + c);
  for (int p : points)
    for (const char* c : {".x", ".y"})
      out.labels.push_back(f.name + ".other." + m.points[p].name + c);
  const Eigen::Index N = r.time.size();
  out.values.resize(N, static_cast<Eigen::Index>(out.labels.size()));
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd q0 = r.q0.row(k).transpose(), q1 = r.q1.row(k).transpose();
    const Vec2 A0 = node_position(l.a0.ref, q0), A = node_position(l.a.ref, q0),
               B = node_position(l.b.ref, q0), B0 = node_position(l.b0.ref, q0);
    const Vec2 vA = node_velocity(l.a.ref, q1), vB = node_velocity(l.b.ref, q1);
    const double ground = angle_of(B0 - A0);
    const double w_in = cross_z(A - A0, vA) / (A - A0).squaredNorm();
    const double w_out = cross_z(B - B0, vB) / (B - B0).squaredNorm();
    const Vec2 BA = A - B, BB0 = B0 - B;
    Eigen::Index c = 0;
    out.values(k, c++) = wrap_pi(angle_of(A - A0) - ground);
    out.values(k, c++) = wrap_pi(angle_of(B - B0) - ground);
    out.values(k, c++) = std::atan2(std::abs(cross_z(BA, BB0)), BA.dot(BB0));
    out.values(k, c++) = w_out / w_in;
    // the other branch: B reflected across the line A - B0, the coupler turned about A with it
    const Vec2 u = (B0 - A).normalized();
    const Vec2 B2 = A + 2 * (B - A).dot(u) * u - (B - A);
    const double turn = angle_of(B2 - A) - angle_of(B - A);
    const Eigen::Rotation2Dd R(turn);
    for (int p : points) {
      const Vec2 P = detail::point_state(m, m.points[p].point, q0, q1).p;
      const Vec2 P2 = A + R * (P - A);
      out.values(k, c++) = P2.x();
      out.values(k, c++) = P2.y();
    }
  }
  return out;
}

}  // namespace mo2d::design_detail

namespace mo2d {

FourBarLengths four_bar_lengths(const Model& m, const FourBarDef& f) {
  using design_detail::find_node;
  const std::string what = "four-bar '" + f.name + "'";
  const Vec2 A0 = node_position(find_node(m, f.input_pivot, what).ref, m.q0),
             A = node_position(find_node(m, f.input_pin, what).ref, m.q0),
             B = node_position(find_node(m, f.output_pin, what).ref, m.q0),
             B0 = node_position(find_node(m, f.output_pivot, what).ref, m.q0);
  return {(B0 - A0).norm(), (A - A0).norm(), (B - A).norm(), (B0 - B).norm()};
}

}  // namespace mo2d
