// Vibration modes of a linearization (mo2d/modes.hpp): the eigenvalues lambda of G and their
// eigenvectors. A pair lambda = -zeta omega_n +- i omega_n sqrt(1 - zeta^2) gives the natural
// frequency omega_n = |lambda|, the damping ratio zeta = -Re lambda / |lambda| and the damped
// frequency omega_d = |Im lambda| (Example 4.7: omega = sqrt(-G_{theta_dot, theta}) when
// undamped). The position part of an eigenvector, dz, turned so that its largest component is
// real, is the mode shape; dq0 = dq0/dz dz carries it to every node.
#include "mo2d/modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mo2d/error.hpp"
#include "modes/modes_internal.hpp"

namespace mo2d {

namespace {

using cd = std::complex<double>;

Mode mode_of(const StateSpace& ss, cd lambda, const Eigen::VectorXcd& x, double zero) {
  Mode md;
  md.eigenvalue = lambda;
  md.omega_n = std::abs(lambda);
  md.omega_d = std::abs(lambda.imag());
  md.hz = md.omega_n / (2 * std::numbers::pi);
  md.rigid = md.omega_n <= zero;
  md.oscillatory = !md.rigid && md.omega_d > zero;
  md.damping_ratio = md.rigid ? 0.0 : -lambda.real() / md.omega_n;
  md.x = x;
  md.dz = Eigen::VectorXd::Zero(ss.p);
  if (ss.p > 0) {
    Eigen::Index k = 0;
    const double big = x.head(ss.p).cwiseAbs().maxCoeff(&k);
    if (big > 0) {
      const cd turn = std::conj(x[k]) / std::abs(x[k]);
      md.dz = (x.head(ss.p) * turn).real() / big;
    }
  }
  md.dq0 = ss.dq0_dz * md.dz;
  return md;
}

// largest node displacement of a mode's dq0
double largest_node_move(const Model& m, const Mode& md) {
  double big = 0;
  for (const Body& b : m.bodies)
    for (const NodeRef& n : b.nodes)
      if (n.var >= 0) big = std::max(big, std::hypot(md.dq0[n.var], md.dq0[n.var + 1]));
  return big;
}

}  // namespace

std::vector<Mode> vibration_modes(const StateSpace& ss, const ModesOptions& o) {
  std::vector<Mode> modes;
  if (ss.n() == 0) return modes;
  detail::check_eigen_budget("vibration modes", ss, o.max_seconds, o.max_memory);
  poll_interrupt();
  Eigen::EigenSolver<MatrixXd> es(ss.G);
  poll_interrupt();
  if (es.info() != Eigen::Success)
    throw Error("vibration modes: the eigenvalues of G did not converge", "G", ss.t);
  const Eigen::VectorXcd& lam = es.eigenvalues();
  const double zero = 1e-7 * std::max(1.0, lam.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < lam.size(); ++i) {
    if (lam[i].imag() < -zero) continue;  // the conjugate of a pair counted once
    modes.push_back(mode_of(ss, lam[i], es.eigenvectors().col(i), zero));
  }
  auto rank = [](const Mode& md) { return md.rigid ? 2 : md.oscillatory ? 0 : 1; };
  std::stable_sort(modes.begin(), modes.end(), [&](const Mode& a, const Mode& b) {
    if (rank(a) != rank(b)) return rank(a) < rank(b);
    return a.omega_n < b.omega_n;
  });
  return modes;
}

std::vector<NodeShape> mode_node_shapes(const Model& m, const Mode& mode, double amplitude) {
  const double big = largest_node_move(m, mode);
  const double s = big > 0 ? amplitude / big : 0.0;
  std::vector<NodeShape> out;
  for (const Body& b : m.bodies)
    for (size_t k = 0; k < b.nodes.size(); ++k) {
      const NodeRef& n = b.nodes[k];
      NodeShape ns{b.node_names[k], 0, 0};
      if (n.var >= 0) {
        ns.dx = s * mode.dq0[n.var];
        ns.dy = s * mode.dq0[n.var + 1];
      }
      out.push_back(ns);
    }
  return out;
}

Eigen::VectorXd mode_step(const Model& m, const Mode& mode, double amplitude) {
  const double big = largest_node_move(m, mode);
  if (big <= 0) return Eigen::VectorXd::Zero(mode.dz.size());
  return mode.dz * (amplitude / big);
}

}  // namespace mo2d
