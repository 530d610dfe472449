// add_design_columns (mo2d/design.hpp): the four-bar, frame and bearing columns of a run, appended
// to its output columns; and the bearing loads, magnitude and direction of each joint's reaction.
#include <cmath>
#include <sstream>

#include "design/design_internal.hpp"
#include "mo2d/error.hpp"

namespace mo2d::design_detail {

Block bearing_columns(const Trajectory& r) {
  Block out;
  std::vector<int> fx;
  const auto& l = r.reaction_labels;
  for (size_t k = 0; k + 1 < l.size(); ++k) {
    const std::string& a = l[k];
    if (a.size() < 3 || a.compare(a.size() - 3, 3, ".Fx") != 0) continue;
    const std::string joint = a.substr(0, a.size() - 3);
    if (l[k + 1] != joint + ".Fy") continue;
    fx.push_back(static_cast<int>(k));
    out.labels.push_back(joint + ".load");
    out.labels.push_back(joint + ".load_angle");
  }
  const Eigen::Index N = r.time.size();
  out.values.resize(N, static_cast<Eigen::Index>(out.labels.size()));
  for (Eigen::Index k = 0; k < N; ++k)
    for (size_t j = 0; j < fx.size(); ++j) {
      const double x = r.reactions(k, fx[j]), y = r.reactions(k, fx[j] + 1);
      out.values(k, 2 * j) = std::hypot(x, y);
      out.values(k, 2 * j + 1) = std::atan2(y, x);
    }
  return out;
}

}  // namespace mo2d::design_detail

namespace mo2d {

void add_design_columns(const Model& m, Trajectory& r, const DesignRequest& q) {
  using namespace design_detail;
  const Eigen::Index N = r.time.size();
  if (r.q0.rows() != N || r.q1.rows() != N || r.q0.cols() != m.n0 || r.q1.cols() != m.n1 ||
      r.reactions.rows() != N || r.reactions.cols() != m.n_reactions())
    throw Error("design: the trajectory's states do not match the model '" + m.name + "'",
                "design");
  std::vector<design_detail::Block> blocks;
  for (const FourBarDef& f : q.four_bars) blocks.push_back(four_bar_columns(m, r, f));
  if (q.frame) blocks.push_back(frame_columns(m, r, q.moment_about));
  if (q.bearings) blocks.push_back(bearing_columns(r));
  Eigen::Index n = 0;
  for (const design_detail::Block& b : blocks)
    for (const std::string& l : b.labels) {
      for (const std::string& had : r.output_labels)
        if (l == had) throw Error("design: column '" + l + "' is already in the trajectory", l);
      ++n;
    }
  Eigen::MatrixXd values(N, r.outputs.cols() + n);
  if (r.outputs.cols() > 0) values.leftCols(r.outputs.cols()) = r.outputs;
  Eigen::Index c = r.outputs.cols();
  for (const design_detail::Block& b : blocks)
    for (Eigen::Index j = 0; j < b.values.cols(); ++j, ++c)
      for (Eigen::Index k = 0; k < N; ++k) {
        const double v = b.values(k, j);
        if (!std::isfinite(v)) {
          std::ostringstream s;
          s << "design: '" << b.labels[j] << "' is not finite (" << v << ") at t = " << r.time[k]
            << " s";
          throw Error(s.str(), b.labels[j], r.time[k]);
        }
        values(k, c) = v;
      }
  r.outputs = std::move(values);
  for (const design_detail::Block& b : blocks)
    r.output_labels.insert(r.output_labels.end(), b.labels.begin(), b.labels.end());
}

}  // namespace mo2d
