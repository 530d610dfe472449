// Newton's restitution with Coulomb friction at an impact (friction_impact.hpp).
#include "contact/friction_impact.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/impact.hpp"

namespace mo2d::detail {
namespace {

// A contact's mode: open, closed and sticking, closed and sliding with v_t+ >= 0 (P_t = -mu P_n)
// or <= 0 (P_t = +mu P_n); closed and frictionless (P_t = 0, v_t+ free).
enum ImpactMode { kOpen = 0, kStick = 1, kSlipForward = 2, kSlipBack = 3, kFree = 4 };

struct ImpactProblem {
  const Eigen::MatrixXd& W;
  const Eigen::VectorXd &rate, &vt, &e, &mu;
  int k;
};

// The impulses of one combination of modes, if its equations are solvable and its inequalities
// hold.
bool try_impact_modes(const ImpactProblem& p, const std::vector<int>& mode, Eigen::VectorXd& Pn,
                      Eigen::VectorXd& Pt) {
  const int k = p.k;
  // unknowns: P_n of each closed contact, P_t of each sticking one; equations: w_n = 0 for each
  // closed contact, v_t+ = 0 for each sticking one
  std::vector<int> un, ut;
  for (int i = 0; i < k; ++i) {
    if (mode[i] != kOpen) un.push_back(i);
    if (mode[i] == kStick) ut.push_back(i);
  }
  const int nu = static_cast<int>(un.size()), nt = static_cast<int>(ut.size());
  // P_t of a sliding contact = s mu P_n: the column of P_n carries s mu times the tangent column
  auto slide = [&](int i) {
    return mode[i] == kSlipForward ? -p.mu[i] : mode[i] == kSlipBack ? p.mu[i] : 0.0;
  };
  auto column = [&](int row, int i, bool tangent) {  // d(row) / d(unknown of contact i)
    if (tangent) return p.W(row, k + i);
    return p.W(row, i) + slide(i) * p.W(row, k + i);
  };
  Eigen::MatrixXd A(nu + nt, nu + nt);
  Eigen::VectorXd b(nu + nt);
  for (int r = 0; r < nu + nt; ++r) {
    const int row = r < nu ? un[r] : k + ut[r - nu];
    b[r] = r < nu ? -(1 + p.e[un[r]]) * p.rate[un[r]] : -p.vt[ut[r - nu]];
    for (int c = 0; c < nu; ++c) A(r, c) = column(row, un[c], false);
    for (int c = 0; c < nt; ++c) A(r, nu + c) = column(row, ut[c], true);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(nu + nt);
  const double scale = std::max({p.rate.cwiseAbs().maxCoeff(), p.vt.cwiseAbs().maxCoeff(), 1e-300});
  const double tol = 1e-10 * scale;
  if (nu + nt > 0) {
    x = A.completeOrthogonalDecomposition().solve(b);
    if (!((A * x - b).cwiseAbs().maxCoeff() <= tol)) return false;
  }
  Pn.setZero();
  Pt.setZero();
  for (int c = 0; c < nu; ++c) Pn[un[c]] = x[c];
  for (int c = 0; c < nt; ++c) Pt[ut[c]] = x[nu + c];
  for (int i = 0; i < k; ++i)
    if (mode[i] == kSlipForward || mode[i] == kSlipBack) Pt[i] = slide(i) * Pn[i];
  const double ptol = 1e-10 * std::max(Pn.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::VectorXd wn = p.W.topLeftCorner(k, k) * Pn + p.W.topRightCorner(k, k) * Pt +
                             (Eigen::VectorXd::Ones(k) + p.e).cwiseProduct(p.rate);
  const Eigen::VectorXd vt =
      p.vt + p.W.bottomLeftCorner(k, k) * Pn + p.W.bottomRightCorner(k, k) * Pt;
  for (int i = 0; i < k; ++i) {
    if (mode[i] == kOpen) {
      if (!(wn[i] >= -tol)) return false;
      continue;
    }
    if (!(Pn[i] >= -ptol)) return false;
    if (mode[i] == kStick && !(std::abs(Pt[i]) <= p.mu[i] * Pn[i] + ptol)) return false;
    if (mode[i] == kSlipForward && !(vt[i] >= -tol)) return false;
    if (mode[i] == kSlipBack && !(vt[i] <= tol)) return false;
  }
  Pn = Pn.cwiseMax(0.0);
  return true;
}

}  // namespace

bool solve_friction_impact(const Eigen::MatrixXd& W, const Eigen::VectorXd& rate,
                           const Eigen::VectorXd& tangent_rate, const Eigen::VectorXd& e,
                           const Eigen::VectorXd& mu, Eigen::VectorXd& Pn, Eigen::VectorXd& Pt) {
  const int k = static_cast<int>(rate.size());
  Pn = Eigen::VectorXd::Zero(k);
  Pt = Eigen::VectorXd::Zero(k);
  if (k > kMaxImpactContacts) return false;
  const ImpactProblem p{W, rate, tangent_rate, e, mu, k};
  for (int closed = 0; closed <= k; ++closed)
    for (unsigned set = 0; set < (1U << k); ++set) {
      if (__builtin_popcount(set) != closed) continue;
      // the closed contacts' tangential modes: stick (0), slide forward (1), back (2) in base 3,
      // stick first; a frictionless contact closed without a tangential condition
      std::vector<int> idx;
      for (int i = 0; i < k; ++i)
        if (set & (1U << i)) idx.push_back(i);
      int combos = 1;
      for (int i : idx) combos *= mu[i] > 0 ? 3 : 1;
      for (int c = 0; c < combos; ++c) {
        std::vector<int> mode(static_cast<size_t>(k), kOpen);
        int code = c;
        for (int i : idx) {
          const int sub = mu[i] > 0 ? code % 3 : -1;
          if (mu[i] > 0) code /= 3;
          mode[static_cast<size_t>(i)] = sub < 0 ? kFree : kStick + sub;
        }
        if (try_impact_modes(p, mode, Pn, Pt)) return true;
      }
    }
  return false;
}

}  // namespace mo2d::detail
