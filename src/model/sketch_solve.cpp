// The placement of bodies given by their shape nearest to their sketch (sketch_solve.hpp: the
// problem, the two phases and their stopping tests).
#include "model/sketch_solve.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace mo2d::build::sketch {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

Vec2 perp(const Vec2& v) {
  return {-v.y(), v.x()};
}
double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Singular values below this fraction of the largest are a rank loss of B (dimensionless: B maps
// node displacements to gaps, both in m).
constexpr double kRankThreshold = 1e-10;

class Solver {
 public:
  explicit Solver(const Problem& p) : p_(p) {
    for (const FreeBody& b : p.bodies) {
      col_.push_back(n_);
      n_ += b.rotates() ? 3 : 2;
    }
    for (const Closure& c : p.closures) {
      row_.push_back(m_);
      m_ += c.on_line ? 1 : 2;
    }
  }

  int vars() const { return n_; }

  VectorXd start() const {
    VectorXd x(n_);
    for (size_t b = 0; b < p_.bodies.size(); ++b) {
      const Pose pose = best_fit(p_.bodies[b].shape, p_.bodies[b].sketch);
      x.segment<2>(col_[b]) = pose.origin;
      if (p_.bodies[b].rotates()) x[col_[b] + 2] = pose.angle;
    }
    return x;
  }

  Pose pose(const VectorXd& x, size_t b) const {
    return {x.segment<2>(col_[b]), p_.bodies[b].rotates() ? x[col_[b] + 2] : 0.0};
  }

  // Closure residuals g (m_) and, if G, their Jacobian G (m_ x n_).
  void closures(const VectorXd& x, VectorXd& g, MatrixXd* G) const {
    g.resize(m_);
    if (G) G->setZero(m_, n_);
    for (size_t k = 0; k < p_.closures.size(); ++k) {
      const Closure& c = p_.closures[k];
      const int r = row_[k];
      if (!c.on_line) {
        g.segment<2>(r) = point(x, c.a) - point(x, c.b);
        if (G)
          for (int d = 0; d < 2; ++d) {
            add_derivative(x, c.a, r + d, Vec2::Unit(d), *G);
            add_derivative(x, c.b, r + d, -Vec2::Unit(d), *G);
          }
        continue;
      }
      const Vec2 pi = point(x, c.a), d = point(x, c.b) - pi, rr = point(x, c.c) - pi;
      const double len = d.norm(), h = cross(d, rr) / len;
      g[r] = h;
      if (!G) continue;
      const Vec2 dh_dd = Vec2(rr.y(), -rr.x()) / len - h * d / (len * len);
      const Vec2 dh_dr = Vec2(-d.y(), d.x()) / len;
      add_derivative(x, c.a, r, -dh_dd - dh_dr, *G);
      add_derivative(x, c.b, r, dh_dd, *G);
      add_derivative(x, c.c, r, dh_dr, *G);
    }
  }

  // S = blockdiag(L_b^-T): Δx = S y for a scaled step y (|y| = the nodes' displacement).
  MatrixXd scaling(const VectorXd& x) const {
    MatrixXd S = MatrixXd::Zero(n_, n_);
    for (size_t b = 0; b < p_.bodies.size(); ++b) {
      const FreeBody& body = p_.bodies[b];
      const int c = col_[b];
      if (!body.rotates()) {  // one node: H = I
        S.block<2, 2>(c, c).setIdentity();
        continue;
      }
      Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
      const Pose ps = pose(x, b);
      for (const Vec2& s : body.shape) {
        const Vec2 t = perp(ps.apply(s) - ps.origin);  // d p_k / d theta
        H(0, 0) += 1;
        H(1, 1) += 1;
        H(0, 2) += t.x();
        H(1, 2) += t.y();
        H(2, 2) += t.squaredNorm();
      }
      H(2, 0) = H(0, 2);
      H(2, 1) = H(1, 2);
      const Eigen::Matrix3d L = Eigen::LLT<Eigen::Matrix3d>(H).matrixL();
      const Eigen::Matrix3d LT = L.transpose();
      S.block<3, 3>(c, c) = LT.inverse();
    }
    return S;
  }

  // f = ½ |r|², r_k = p_k - sketch_k; grad = ∂f/∂x.
  double objective(const VectorXd& x, VectorXd* grad) const {
    double f = 0;
    if (grad) grad->setZero(n_);
    for (size_t b = 0; b < p_.bodies.size(); ++b) {
      const FreeBody& body = p_.bodies[b];
      const Pose ps = pose(x, b);
      for (size_t k = 0; k < body.shape.size(); ++k) {
        const Vec2 pk = ps.apply(body.shape[k]), r = pk - body.sketch[k];
        f += 0.5 * r.squaredNorm();
        if (!grad) continue;
        grad->segment<2>(col_[b]) += r;
        if (body.rotates()) (*grad)[col_[b] + 2] += perp(pk - ps.origin).dot(r);
      }
    }
    return f;
  }

  // Phase 1: minimum-norm Gauss-Newton on g = 0 until |g| stops decreasing; returns |g|_inf at
  // x. A step is tried whole, then halved (three times); where no such step decreases |g|_2
  // (near a rank loss of B, where the Gauss-Newton step is huge, or at the least-squares
  // minimum of an open loop) the Levenberg-Marquardt steps y = -sum_i s_i / (s_i^2 + mu) (u_i .
  // g) v_i with mu = 1e-8 ... 1e2 s_max^2 (the SVD B = sum_i s_i u_i v_i^T).
  double close(VectorXd& x) const {
    if (m_ == 0) return 0;
    VectorXd g, gt;
    MatrixXd G;
    for (int it = 0; it < kMaxClosureIterations; ++it) {
      closures(x, g, &G);
      const double norm2 = g.norm();
      if (!(norm2 > 0)) break;
      const MatrixXd S = scaling(x);
      Eigen::JacobiSVD<MatrixXd> svd(G * S, Eigen::ComputeThinU | Eigen::ComputeThinV);
      svd.setThreshold(kRankThreshold);
      const VectorXd ug = svd.matrixU().transpose() * g;
      const VectorXd& sv = svd.singularValues();
      auto try_step = [&](double mu, double alpha) {
        VectorXd y = VectorXd::Zero(n_);
        for (Eigen::Index i = 0; i < sv.size(); ++i) {
          if (mu == 0 && !(sv[i] > kRankThreshold * sv[0])) break;
          y += (sv[i] / (sv[i] * sv[i] + mu) * ug[i]) * svd.matrixV().col(i);
        }
        const VectorXd xt = x - alpha * (S * y);
        closures(xt, gt, nullptr);
        if (!gt.allFinite() || !(gt.norm() <= (1 - 1e-4 * alpha) * norm2)) return false;
        x = xt;
        return true;
      };
      bool accepted = false;
      for (double alpha = 1; alpha >= 0.125 && !accepted; alpha *= 0.5)
        accepted = try_step(0, alpha);
      const double s2 = sv.size() ? sv[0] * sv[0] : 0.0;
      for (double mu = 1e-8; mu <= 1e2 && !accepted; mu *= 10) accepted = try_step(mu * s2, 1);
      if (!accepted) break;
    }
    closures(x, g, nullptr);
    return g.lpNorm<Eigen::Infinity>();
  }

  // Phase 2's step at x: the tangential part S t, t = -N N^T Q^T r, and the closing part S y_n,
  // y_n = -B^+ g; returns |t| (m).
  double step(const VectorXd& x, VectorXd& tangent, VectorXd& closing) const {
    const MatrixXd S = scaling(x);
    VectorXd grad;
    objective(x, &grad);
    const VectorXd q = S.transpose() * grad;  // Q^T r
    VectorXd t = -q, yn = VectorXd::Zero(n_);
    if (m_ > 0) {
      VectorXd g;
      MatrixXd G;
      closures(x, g, &G);
      Eigen::JacobiSVD<MatrixXd> svd(G * S, Eigen::ComputeFullU | Eigen::ComputeFullV);
      svd.setThreshold(kRankThreshold);
      const auto N = svd.matrixV().rightCols(n_ - svd.rank());
      t = -N * (N.transpose() * q);
      yn = -svd.solve(g);
    }
    tangent = S * t;
    closing = S * yn;
    return t.norm();
  }

  static constexpr int kMaxClosureIterations = 200;

 private:
  Vec2 point(const VectorXd& x, const Point& q) const {
    if (q.body < 0) return q.fixed;
    return pose(x, q.body).apply(p_.bodies[q.body].shape[q.node]);
  }
  // G(row, .) += w . d point / d x
  void add_derivative(const VectorXd& x, const Point& q, int row, const Vec2& w,
                      MatrixXd& G) const {
    if (q.body < 0) return;
    const int c = col_[q.body];
    G(row, c) += w.x();
    G(row, c + 1) += w.y();
    if (p_.bodies[q.body].rotates()) {
      const Pose ps = pose(x, q.body);
      G(row, c + 2) += w.dot(perp(ps.apply(p_.bodies[q.body].shape[q.node]) - ps.origin));
    }
  }

  const Problem& p_;
  std::vector<int> col_, row_;
  int n_ = 0, m_ = 0;
};

// Phase 2 (sketch_solve.hpp): from a closed x, toward the nearest closed configuration.
void nearest(const Solver& s, const Problem& p, VectorXd& x, Result& res) {
  constexpr int kMaxIterations = 500;
  const double converged = 1e-14 * p.size, near = 1e-6 * p.size;
  VectorXd t, dn, t_trial, dn_trial;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double tn = s.step(x, t, dn);
    res.tangential = tn;
    if (tn <= converged) {
      res.nearest = true;
      return;
    }
    const double f = s.objective(x, nullptr);
    bool accepted = false;
    for (double alpha = 1; alpha >= 1.0 / 1024; alpha *= 0.5) {
      VectorXd xt = x + alpha * t + dn;
      if (!(s.close(xt) <= p.tolerance)) continue;
      const bool better =
          tn > near ? s.objective(xt, nullptr) < f : s.step(xt, t_trial, dn_trial) < tn;
      if (better) {
        x = xt;
        accepted = true;
        break;
      }
    }
    if (!accepted) {  // no decrease: at the optimum to round-off, or stuck
      res.nearest = tn <= 1e-10 * p.size;
      return;
    }
  }
  res.nearest = false;
}

}  // namespace

Pose best_fit(const std::vector<Vec2>& shape, const std::vector<Vec2>& sketch) {
  Vec2 cs(0, 0), cp(0, 0);
  for (size_t k = 0; k < shape.size(); ++k) {
    cs += shape[k];
    cp += sketch[k];
  }
  cs /= static_cast<double>(shape.size());
  cp /= static_cast<double>(shape.size());
  double dot = 0, crs = 0;
  for (size_t k = 0; k < shape.size(); ++k) {
    const Vec2 a = shape[k] - cs, b = sketch[k] - cp;
    dot += a.dot(b);
    crs += cross(a, b);
  }
  Pose pose;
  pose.angle = shape.size() >= 2 ? std::atan2(crs, dot) : 0.0;
  pose.origin = cp - Placement{{0, 0}, pose.angle}.apply(cs);
  return pose;
}

Result solve_sketch(const Problem& problem) {
  const Solver s(problem);
  VectorXd x = s.start();
  Result res;
  res.closed = s.close(x) <= problem.tolerance;
  if (res.closed) nearest(s, problem, x, res);
  for (size_t b = 0; b < problem.bodies.size(); ++b) res.poses.push_back(s.pose(x, b));
  VectorXd g;
  s.closures(x, g, nullptr);
  int r = 0;
  for (const Closure& c : problem.closures) {
    res.gaps.push_back(c.on_line ? std::abs(g[r]) : g.segment<2>(r).norm());
    r += c.on_line ? 1 : 2;
  }
  return res;
}

}  // namespace mo2d::build::sketch
