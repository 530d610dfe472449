// Newton's restitution over the contacts closing at once (impact.hpp).
#include "contact/impact.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>

#include "contact/friction_impact.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/kinematics.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

bool solve_lcp_enumerate(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, Eigen::VectorXd& P) {
  const int k = static_cast<int>(q.size());
  if (k > kMaxImpactContacts) return false;
  const double tol = 1e-10 * std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  P = Eigen::VectorXd::Zero(k);
  // by the number of active contacts: the fewest that work (the unique one for W > 0)
  for (int size = 0; size <= k; ++size)
    for (unsigned set = 0; set < (1U << k); ++set) {
      if (__builtin_popcount(set) != size) continue;
      std::vector<int> idx;
      for (int i = 0; i < k; ++i)
        if (set & (1U << i)) idx.push_back(i);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(k);
      if (size > 0) {
        Eigen::MatrixXd Ws(size, size);
        Eigen::VectorXd qs(size);
        for (int r = 0; r < size; ++r) {
          qs[r] = -q[idx[r]];
          for (int c = 0; c < size; ++c) Ws(r, c) = W(idx[r], idx[c]);
        }
        const Eigen::VectorXd xs = Ws.completeOrthogonalDecomposition().solve(qs);
        if (!((Ws * xs - qs).cwiseAbs().maxCoeff() <= tol)) continue;
        for (int r = 0; r < size; ++r) x[idx[r]] = xs[r];
      }
      const Eigen::VectorXd w = W * x + q;
      const double xtol = 1e-10 * std::max(x.cwiseAbs().maxCoeff(), 1e-300);
      if (x.minCoeff() >= -xtol && w.minCoeff() >= -tol) {
        P = x.cwiseMax(0.0);
        return true;
      }
    }
  return false;
}

ImpactResult newton_impact(const Model& m, double t, const Eigen::VectorXd& q0,
                           const Eigen::VectorXd& q1, const Eigen::MatrixXd& J,
                           const Eigen::VectorXd& rate, const Eigen::VectorXd& e,
                           const std::string& names, const ImpactFriction* friction) {
  const int n = m.n1, rows = m.m1, k = static_cast<int>(J.rows());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + rows, n + rows);
  Eigen::MatrixXd A(rows, n);
  Eigen::VectorXd b(rows);
  velocity_jacobian(m, q0, t, A, b);
  K.topLeftCorner(n, n) = mass_matrix(m);
  K.topRightCorner(n, rows) = A.transpose();
  K.bottomLeftCorner(rows, n) = A;
  const bool rough = friction && friction->mu.size() == k && friction->mu.maxCoeff() > 0;
  const int cols = rough ? 2 * k : k;  // the tangents' directions after the normals'
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + rows, cols);
  rhs.topLeftCorner(n, k) = J.transpose();
  if (rough) rhs.block(0, k, n, k) = friction->J.transpose();
  const Eigen::MatrixXd X = K.fullPivLu().solve(rhs).topRows(n);  // x_j
  ImpactResult out;
  out.tangent_impulse = Eigen::VectorXd::Zero(k);
  out.tangent_rate = friction && friction->rate.size() == k ? friction->rate : out.tangent_impulse;
  bool solved = false;
  if (rough) {
    Eigen::MatrixXd JJ(2 * k, n);
    JJ << J, friction->J;
    const Eigen::MatrixXd W = JJ * X;
    solved = solve_friction_impact(W, rate, friction->rate, e, friction->mu, out.impulse,
                                   out.tangent_impulse);
    out.rate =
        rate + W.topLeftCorner(k, k) * out.impulse + W.topRightCorner(k, k) * out.tangent_impulse;
    out.tangent_rate = friction->rate + W.bottomLeftCorner(k, k) * out.impulse +
                       W.bottomRightCorner(k, k) * out.tangent_impulse;
    out.q1 = q1 + X.leftCols(k) * out.impulse + X.rightCols(k) * out.tangent_impulse;
  } else {
    const Eigen::MatrixXd W = J * X;
    const Eigen::VectorXd q = (Eigen::VectorXd::Ones(k) + e).cwiseProduct(rate);
    solved = solve_lcp_enumerate(0.5 * (W + W.transpose()), q, out.impulse);
    out.q1 = q1 + X * out.impulse;
    out.rate = rate + W * out.impulse;
  }
  if (!solved)
    throw Error("impact of contact" + std::string(k > 1 ? "s " : " ") + names +
                    " at t = " + fmt(t) + " s: Newton's restitution" +
                    std::string(rough ? " with Coulomb friction" : "") + " has no solution (" +
                    std::to_string(k) + " contacts; at most " + std::to_string(kMaxImpactContacts) +
                    " closing at once are solved)",
                names, t);
  out.energy_lost = -out.impulse.dot(rate + out.rate) / 2;  // impact.hpp
  if (rough)  // the tangential impulses' work too (friction_impact.hpp)
    out.energy_lost -= out.tangent_impulse.dot(friction->rate + out.tangent_rate) / 2;
  out.constraint_work = kinetic_energy(m, out.q1) - kinetic_energy(m, q1) + out.energy_lost;
  if (!out.q1.allFinite())
    throw Error("impact of " + names + " at t = " + fmt(t) + " s: non-finite velocities after it",
                names, t);
  return out;
}

}  // namespace mo2d::detail
