// Cross-check panels (crosscheck_picture.hpp): each a Plot of the project's renderer, drawn to an
// image and stacked.
#include "crosscheck_picture.hpp"

#include <cmath>

#include "mo2d/render/image.hpp"

namespace mo2d::cli {

namespace {

std::vector<double> column(const Eigen::MatrixXd& M, Eigen::Index c) {
  const Eigen::VectorXd v = M.col(c);
  return {v.data(), v.data() + v.size()};
}

Plot panel(const CrosscheckReport& r, const std::string& title, const std::string& y) {
  Plot p;
  p.title = r.mechanism + ": " + title;
  p.x.label = "time (s)";
  p.y.label = y;
  p.width = 800, p.height = 330;
  return p;
}

// The reaction force magnitude of joint j (columns joint.Fx, joint.Fy at 2j, 2j + 1).
std::vector<double> magnitude(const Eigen::MatrixXd& R, Eigen::Index j) {
  std::vector<double> out(static_cast<size_t>(R.rows()));
  for (Eigen::Index i = 0; i < R.rows(); ++i)
    out[static_cast<size_t>(i)] = std::hypot(R(i, 2 * j), R(i, 2 * j + 1));
  return out;
}

std::string joint_of(const std::string& label) {
  const auto dot = label.rfind('.');
  return dot == std::string::npos ? label : label.substr(0, dot);
}

}  // namespace

std::vector<Plot> crosscheck_panels(const CrosscheckReport& r) {
  const std::vector<double> t(r.time.data(), r.time.data() + r.time.size());
  const auto& palette = okabe_ito();
  std::vector<Plot> out;
  Plot efforts = panel(r, "mo2d (solid) and Box2D (dashed) efforts", "effort (N\u00B7m, N)");
  Plot diff = panel(r, "effort difference Box2D \u2212 mo2d", "difference (N\u00B7m, N)");
  for (std::size_t k = 0; k < r.effort_labels.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    const Rgb colour = palette[k % palette.size()];
    const std::vector<double> a = column(r.mo2d_efforts, c), b = column(r.box2d_efforts, c);
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) d[i] = b[i] - a[i];
    efforts.series.push_back({r.effort_labels[k] + " (mo2d)", t, a, colour, false, false});
    efforts.series.push_back({r.effort_labels[k] + " (Box2D)", t, b, colour, true, false});
    diff.series.push_back({r.effort_labels[k], t, d, colour, false, false});
  }
  if (!r.effort_labels.empty()) out.push_back(std::move(efforts)), out.push_back(std::move(diff));
  const Eigen::Index joints = r.mo2d_reactions.cols() / 2;
  if (joints > 0 && r.box2d_reactions.cols() == r.mo2d_reactions.cols()) {
    Plot forces = panel(r, "joint reaction |F|, mo2d (solid) and Box2D (dashed)", "|F| (N)");
    Plot fdiff = panel(r, "reaction difference |F| Box2D \u2212 mo2d", "difference (N)");
    for (Eigen::Index j = 0; j < joints; ++j) {
      const std::string name = joint_of(r.reaction_labels[static_cast<size_t>(2 * j)]);
      const Rgb colour = palette[static_cast<size_t>(j) % palette.size()];
      const std::vector<double> a = magnitude(r.mo2d_reactions, j);
      const std::vector<double> b = magnitude(r.box2d_reactions, j);
      std::vector<double> d(a.size());
      for (std::size_t i = 0; i < a.size(); ++i) d[i] = b[i] - a[i];
      forces.series.push_back({name + " (mo2d)", t, a, colour, false, false});
      forces.series.push_back({name + " (Box2D)", t, b, colour, true, false});
      fdiff.series.push_back({name, t, d, colour, false, false});
    }
    out.push_back(std::move(forces));
    out.push_back(std::move(fdiff));
  }
  return out;
}

int write_crosscheck_picture(const CrosscheckReport& r, const std::string& path) {
  const std::vector<Plot> panels = crosscheck_panels(r);
  Image sheet;
  for (const Plot& p : panels) {
    const Image im = render_plot(p);
    sheet.width = im.width;
    sheet.height += im.height;
    sheet.argb.insert(sheet.argb.end(), im.argb.begin(), im.argb.end());
  }
  if (!panels.empty()) write_png(sheet, path);
  return static_cast<int>(panels.size());
}

}  // namespace mo2d::cli
