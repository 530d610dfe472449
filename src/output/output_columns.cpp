// The columns a run adds on request (mo2d/output_columns.hpp): loads' values and powers, named
// points, centres of mass, from the recorded state of every sample.
#include "mo2d/output_columns.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "dynamics/points.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "model/suggest.hpp"

namespace mo2d {

namespace {

// The named points asked for, as indices into Model::points.
std::vector<int> requested_points(const Model& m, const OutputRequest& q) {
  std::vector<int> out;
  if (q.all_points) {
    for (int k = 0; k < static_cast<int>(m.points.size()); ++k) out.push_back(k);
    return out;
  }
  std::vector<std::string> names;
  for (const NamedPoint& p : m.points) names.push_back(p.name);
  for (const std::string& name : q.points) {
    bool found = false;
    for (int k = 0; k < static_cast<int>(names.size()); ++k)
      if (names[k] == name) out.push_back(k), found = true;
    if (!found)
      throw Error("outputs: no named point '" + name + "'" + did_you_mean(name, names) +
                      (names.empty() ? " (the model has no named points: System::add_point)" : ""),
                  name);
  }
  return out;
}

// Bodies whose centre of mass is written: every body with a mass.
bool has_com(const Body& b) {
  return b.mass > 0;
}

// The law columns compiled against m (an Error naming the column and an unknown quantity).
std::vector<CompiledLaw> compiled_output_columns(const Model& m, const OutputRequest& q) {
  std::vector<CompiledLaw> out;
  for (const auto& [name, law] : q.columns)
    out.push_back(compile_law(m, law, "outputs.columns." + name, name));
  return out;
}

// The loads' values and powers at one state, in the order of output_column_labels.
template <class Put>
void put_load_values(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& q0,
                     const Eigen::Ref<const Eigen::VectorXd>& q1, double t, Put& put) {
  for (const PointLoad& f : m.forces) {  // F . v of the point it acts on
    const Vec2 F = point_force(m, f, q0, q1, t);
    const BodyPoint bp{f.body, f.ci, f.cj, f.gamma, f.rho, Vec2(0, 0)};
    for (double v : {F.x(), F.y(), F.dot(detail::point_state(m, bp, q0, q1).v)}) put(v);
  }
  for (const TorqueLoad& tq : m.torques) {
    const double tau = torque_value(m, tq, q0, q1, t);
    put(tau);
    put(tau * omega_value(m.bodies[tq.body].omega, q1));
  }
  for (const SpringLoad& s : m.springs) {
    const SpringValue v = spring_value(m, s, q0, q1, t);
    for (double x : {v.length, v.rate, v.tension, -v.tension * v.rate}) put(x);
  }
  for (const ReducedSpring& s : m.reduced_springs) {
    const detail::PointState a = detail::point_state(m, s.spring.a, q0, q1),
                             b = detail::point_state(m, s.spring.b, q0, q1);
    const Vec2 d = b.p - a.p;
    const double l = d.norm();
    put(l);
    put(l > 0 ? d.dot(b.v - a.v) / l : 0.0);
  }
  for (const TorsionalLoad& s : m.torsional_springs) {
    const TorsionalValue v = torsional_value(m, s, q0, q1, t);
    for (double x : {v.torque, v.rate, v.torque * v.rate}) put(x);
  }
  for (const ReducedTorsional& s : m.reduced_torsional) {
    auto th = [&](int b) { return b < 0 ? 0.0 : body_angle(m.bodies[b], q0); };
    auto w = [&](int b) { return b < 0 ? 0.0 : omega_value(m.bodies[b].omega, q1); };
    put(std::remainder(th(s.spring.body2) - th(s.spring.body1) - s.spring.rest,
                       2 * std::numbers::pi));
    put(w(s.spring.body2) - w(s.spring.body1));
  }
  for (const ChainLoad& s : m.chains) {
    const ChainValue v = chain_value(m, s, q0, q1, t);
    if (s.fidelity == ChainFidelity::inextensible) {
      put(v.upper_length);
      put(v.lower_length);
      continue;
    }
    for (double x : {v.upper_length, v.upper_tension, v.lower_length, v.lower_tension, v.power})
      put(x);
  }
}

void output_values_at(const Model& m, const OutputRequest& q,
                      const std::vector<CompiledLaw>& columns,
                      const Eigen::Ref<const Eigen::VectorXd>& q0,
                      const Eigen::Ref<const Eigen::VectorXd>& q1, double t,
                      Eigen::Ref<Eigen::VectorXd> out) {
  Eigen::Index c = 0;
  auto put = [&](double v) {
    if (c >= out.size()) throw Error("outputs: more values than columns", "outputs", t);
    out[c++] = v;
  };
  auto put_state = [&](const detail::PointState& s) {
    for (double v : {s.p.x(), s.p.y(), s.v.x(), s.v.y()}) put(v);
  };
  if (q.loads) put_load_values(m, q0, q1, t, put);
  for (int k : requested_points(m, q)) put_state(detail::point_state(m, m.points[k].point, q0, q1));
  if (q.com)
    for (const Body& b : m.bodies)
      if (has_com(b))
        put_state({com_position(b, q0),
                   detail::local_velocity_of_point(b, q1, b.ci, b.cj, b.gamma, b.rho)});
  for (std::size_t k = 0; k < columns.size(); ++k)
    put(law_value(m, columns[k], q0, q1, t, "output column", q.columns[k].first));
  if (c != out.size()) throw Error("outputs: fewer values than columns", "outputs", t);
}

}  // namespace

std::vector<std::string> output_column_labels(const Model& m, const OutputRequest& q) {
  std::vector<std::string> l;
  auto add = [&](const std::string& name, std::initializer_list<const char*> fields) {
    for (const char* f : fields) l.push_back(name + "." + f);
  };
  if (q.loads) {
    for (const PointLoad& f : m.forces) add(f.name, {"fx", "fy", "power"});
    for (const TorqueLoad& t : m.torques) add(t.name, {"torque", "power"});
    for (const SpringLoad& s : m.springs) add(s.name, {"length", "rate", "tension", "power"});
    // reduced to a constraint: the tension is the reaction "S.tension", the power 0
    for (const ReducedSpring& s : m.reduced_springs) add(s.spring.name, {"length", "rate"});
    for (const TorsionalLoad& s : m.torsional_springs) add(s.name, {"torque", "rate", "power"});
    // reduced: the torque is the reaction "K.torque"; the angle from rest and its rate
    for (const ReducedTorsional& s : m.reduced_torsional) add(s.spring.name, {"angle", "rate"});
    for (const ChainLoad& s : m.chains)
      if (s.fidelity == ChainFidelity::inextensible)  // tensions: the reactions; power 0
        add(s.name, {"upper.length", "lower.length"});
      else
        add(s.name, {"upper.length", "upper.tension", "lower.length", "lower.tension", "power"});
  }
  for (int k : requested_points(m, q)) add(m.points[k].name, {"x", "y", "vx", "vy"});
  if (q.com)
    for (const Body& b : m.bodies)
      if (has_com(b)) add(b.name + ".com", {"x", "y", "vx", "vy"});
  for (const auto& column : q.columns) l.push_back(column.first);
  return l;
}

void output_column_values(const Model& m, const OutputRequest& q,
                          const Eigen::Ref<const Eigen::VectorXd>& q0,
                          const Eigen::Ref<const Eigen::VectorXd>& q1, double t,
                          Eigen::Ref<Eigen::VectorXd> out) {
  output_values_at(m, q, compiled_output_columns(m, q), q0, q1, t, out);
}

void add_output_columns(const Model& m, Trajectory& r, const OutputRequest& q) {
  if (q.empty()) return;
  const std::vector<std::string> labels = output_column_labels(m, q);
  for (const std::string& l : labels)
    for (const std::string& had : r.output_labels)
      if (l == had) throw Error("outputs: column '" + l + "' is already in the trajectory", l);
  const Eigen::Index N = r.time.size(), n = static_cast<Eigen::Index>(labels.size());
  if (r.q0.rows() != N || r.q1.rows() != N || r.q0.cols() != m.n0 || r.q1.cols() != m.n1)
    throw Error("outputs: the trajectory's states do not match the model '" + m.name + "'",
                "outputs");
  Eigen::MatrixXd values(N, r.outputs.cols() + n);
  if (r.outputs.cols() > 0) values.leftCols(r.outputs.cols()) = r.outputs;
  Eigen::VectorXd row(n);
  const std::vector<CompiledLaw> columns = compiled_output_columns(m, q);  // once, not per sample
  for (Eigen::Index k = 0; k < N; ++k) {
    output_values_at(m, q, columns, r.q0.row(k).transpose(), r.q1.row(k).transpose(), r.time[k],
                     row);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!std::isfinite(row[j])) {
        std::ostringstream s;
        s << "outputs: '" << labels[j] << "' is not finite at t = " << r.time[k] << " s";
        throw Error(s.str(), labels[j], r.time[k]);
      }
      values(k, r.outputs.cols() + j) = row[j];
    }
  }
  r.outputs = std::move(values);
  r.output_labels.insert(r.output_labels.end(), labels.begin(), labels.end());
}

}  // namespace mo2d
