// Tables: checks of the points, the spline's second derivatives at the knots (moments), and the
// evaluation of a piece on a Jet (see mo2d/table.hpp).
#include "mo2d/table.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace mo2d {

namespace {

std::string str(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

// The moments M_i = S''(x_i) of the C² cubic spline through (x, y). Continuity of S' at an
// interior knot i (with h_i = x_i+1 - x_i and delta_i = (y_i+1 - y_i) / h_i) is
//   h_i-1 M_i-1 + 2 (h_i-1 + h_i) M_i + h_i M_i+1 = 6 (delta_i - delta_i-1);
// the two end rows are not-a-knot (S''' continuous at x_1 and x_n-2), or, periodic, the same row
// at knot 0 with its neighbours taken across the wrap (M_n-1 = M_0).
std::vector<double> moments(const std::vector<double>& x, const std::vector<double>& y,
                            bool periodic) {
  const int n = static_cast<int>(x.size());
  std::vector<double> h(n - 1), delta(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    delta[i] = (y[i + 1] - y[i]) / h[i];
  }
  if (n == 2 && !periodic) return {0.0, 0.0};  // the straight line
  if (n == 3 && !periodic) {                   // not-a-knot on 3 points: the parabola
    const double m = 2 * (delta[1] - delta[0]) / (h[0] + h[1]);
    return {m, m, m};
  }
  const int m = periodic ? n - 1 : n;  // unknowns
  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
  auto row = [&](int r, int left, int i, int right) {  // the continuity row of knot i
    const int il = (i - 1 + (n - 1)) % (n - 1);        // interval before knot i (wrapped)
    const int ir = i % (n - 1);                        // interval after it
    a.emplace_back(r, left, h[il]);
    a.emplace_back(r, i % m, 2 * (h[il] + h[ir]));
    a.emplace_back(r, right, h[ir]);
    rhs[r] = 6 * (delta[ir] - delta[il]);
  };
  if (periodic) {
    for (int i = 0; i < m; ++i) row(i, (i - 1 + m) % m, i, (i + 1) % m);
  } else {
    for (int i = 1; i + 1 < n; ++i) row(i, i - 1, i, i + 1);
    // h1 (M1 - M0) = h0 (M2 - M1), and the same at the other end
    a.emplace_back(0, 0, -h[1]);
    a.emplace_back(0, 1, h[0] + h[1]);
    a.emplace_back(0, 2, -h[0]);
    a.emplace_back(n - 1, n - 3, -h[n - 2]);
    a.emplace_back(n - 1, n - 2, h[n - 3] + h[n - 2]);
    a.emplace_back(n - 1, n - 1, -h[n - 3]);
  }
  Eigen::SparseMatrix<double> matrix(m, m);
  matrix.setFromTriplets(a.begin(), a.end());  // duplicates (short periodic tables) are summed
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(matrix);
  if (lu.info() != Eigen::Success) throw Error("table: the spline's equations are singular");
  const Eigen::VectorXd sol = lu.solve(rhs);
  std::vector<double> out(sol.data(), sol.data() + m);
  if (periodic) out.push_back(out.front());
  return out;
}

}  // namespace

LookupTable::LookupTable(std::string name, std::vector<double> x, std::vector<double> y,
                         TableOptions options)
    : name_(std::move(name)), x_(std::move(x)), y_(std::move(y)), options_(options) {
  const std::string what = "table '" + name_ + "': ";
  if (x_.size() != y_.size())
    throw Error(what + std::to_string(x_.size()) + " x values but " + std::to_string(y_.size()) +
                    " y values",
                name_);
  if (x_.size() < 2)
    throw Error(what + "at least 2 points are needed, got " + std::to_string(x_.size()), name_);
  for (size_t i = 0; i < x_.size(); ++i) {
    if (!std::isfinite(x_[i]) || !std::isfinite(y_[i]))
      throw Error(what + "point " + std::to_string(i) + " (" + str(x_[i]) + ", " + str(y_[i]) +
                      ") is not finite",
                  name_);
    if (i > 0 && !(x_[i] > x_[i - 1]))
      throw Error(what + "x must increase: x = " + str(x_[i]) + " at point " + std::to_string(i) +
                      " after x = " + str(x_[i - 1]),
                  name_);
  }
  if (options_.extrapolation == Extrapolation::periodic) {
    double scale = 0;
    for (double v : y_) scale = std::max(scale, std::abs(v));
    if (std::abs(y_.back() - y_.front()) > 1e-9 * scale)
      throw Error(what + "a periodic table ends where it starts, one period later: y = " +
                      str(y_.back()) + " at x = " + str(x_.back()) + " but y = " + str(y_.front()) +
                      " at x = " + str(x_.front()),
                  name_);
    y_.back() = y_.front();
  }
  fit();
}

void LookupTable::fit() {
  const size_t n = x_.size();
  pieces_.resize(n - 1);
  if (options_.interpolation == Interpolation::linear) {
    for (size_t i = 0; i + 1 < n; ++i)
      pieces_[i] = {y_[i], (y_[i + 1] - y_[i]) / (x_[i + 1] - x_[i]), 0, 0};
    return;
  }
  const std::vector<double> m = moments(x_, y_, options_.extrapolation == Extrapolation::periodic);
  for (size_t i = 0; i + 1 < n; ++i) {
    const double h = x_[i + 1] - x_[i];
    const double delta = (y_[i + 1] - y_[i]) / h;
    pieces_[i] = {y_[i], delta - h * (2 * m[i] + m[i + 1]) / 6, m[i] / 2,
                  (m[i + 1] - m[i]) / (6 * h)};
  }
}

double LookupTable::wrap(double x) const {
  const double x0 = x_min(), period = x_max() - x0;
  double r = std::fmod(x - x0, period);
  if (r < 0) r += period;
  if (r >= period) r = 0;  // r + period rounded up to the period
  return x0 + r;
}

Jet LookupTable::operator()(Jet x) const {
  if (!std::isfinite(x.v))
    throw Error("table '" + name_ + "': evaluated at x = " + str(x.v), name_);
  double u = x.v;
  const double x0 = x_min(), x1 = x_max();
  const double slack = 1e-12 * std::max({std::abs(x0), std::abs(x1), x1 - x0});
  if (u < x0 - slack || u > x1 + slack) {
    switch (options_.extrapolation) {
      case Extrapolation::error:
        throw Error("table '" + name_ + "': x = " + str(u) + " is outside the table's range [" +
                        str(x0) + ", " + str(x1) +
                        "] (extrapolation error; clamp or periodic evaluate beyond the ends)",
                    name_);
      case Extrapolation::clamp:
        return Jet(u < x0 ? y_.front() : y_.back());
      case Extrapolation::periodic:
        u = wrap(u);
        break;
    }
  } else if (options_.extrapolation == Extrapolation::periodic && u >= x1) {
    u = x0 + std::max(0.0, u - x1);  // the wrap is C², so either side of it will do
  }
  // the piece whose [x_i, x_i+1) holds u (the last piece up to and beyond x_max)
  const auto it = std::upper_bound(x_.begin() + 1, x_.end() - 1, u);
  const size_t i = static_cast<size_t>(it - x_.begin()) - 1;
  const Piece& p = pieces_[i];
  const double s = u - x_[i];
  const double f = p.a + s * (p.b + s * (p.c + s * p.d));
  const double f1 = p.b + s * (2 * p.c + 3 * s * p.d);
  const double f2 = 2 * p.c + 6 * s * p.d;
  return chain(x, f, f1, f2);
}

}  // namespace mo2d
