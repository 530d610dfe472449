// Forward dynamics: consistent initial state, accelerations (augmented Lagrangian, Lagrange, null
// space), projection on the constraint manifolds, fixed-step and SUNDIALS CVODE integration.
#include "mo2d/forward.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "constraints.hpp"
#include "cpu_time.hpp"
#include "mo2d/detail/small_lu.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d {

const char* to_string(Integrator i) {
  switch (i) {
    case Integrator::cvode_bdf: return "cvode_bdf";
    case Integrator::cvode_adams: return "cvode_adams";
    case Integrator::rk4: return "rk4";
    case Integrator::baumgarte: return "baumgarte";
  }
  return "?";
}
const char* to_string(Formulation f) {
  switch (f) {
    case Formulation::augmented_lagrangian: return "augmented_lagrangian";
    case Formulation::lagrange: return "lagrange";
    case Formulation::null_space: return "null_space";
  }
  return "?";
}

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

double kinetic_energy(const Model& m, const VectorXd& q1) {
  VectorXd local(m.n_slots), Mq(m.n1);
  body_inertia(m, q1, local);
  Mq.setZero();
  scatter_local(m, local, Mq);
  return 0.5 * q1.dot(Mq);
}

State consistent_state(const Model& m, const InitialConditions& ic, double t0) {
  VectorXd q0 = m.q0;
  std::vector<int> fixed;
  for (const auto& [label, value] : ic.positions) {
    const int k = m.coordinate(label);
    if (!std::isfinite(value))
      throw Error("initial value of '" + label + "' is not finite", label);
    if (std::find(fixed.begin(), fixed.end(), k) != fixed.end())
      throw Error("initial position of '" + label + "' is given twice", label);
    q0[k] = value;
    fixed.push_back(k);
  }
  State s;
  s.t = t0;
  s.q0 = assemble(m, q0, t0, fixed, 1e-13);
  if (static_cast<int>(ic.velocities.size()) != m.dof) {
    std::string list;
    for (const auto& [l, v] : ic.velocities) list += (list.empty() ? "" : ", ") + l;
    throw Error("initial state of '" + m.name + "': " + std::to_string(m.dof) +
                    " independent velocities are needed, " + std::to_string(ic.velocities.size()) +
                    " given" + (list.empty() ? "" : " (" + list + ")"),
                m.name, t0);
  }
  MatrixXd K = MatrixXd::Zero(m.n1, m.n1);
  VectorXd b(m.m1), rhs(m.n1);
  velocity_jacobian(m, s.q0, t0, K.topRows(m.m1), b);
  rhs.head(m.m1) = b;
  for (int k = 0; k < m.dof; ++k) {
    const auto& [label, value] = ic.velocities[k];
    if (!std::isfinite(value)) throw Error("initial velocity '" + label + "' is not finite", label);
    K(m.m1 + k, m.rate(label)) = 1.0;
    rhs[m.m1 + k] = value;
  }
  detail::SmallLU lu(m.n1);
  if (lu.compute(K) < 1e-10) {
    std::string list;
    for (const auto& [l, v] : ic.velocities) list += (list.empty() ? "" : ", ") + l;
    throw Error("initial state of '" + m.name + "': the velocities " + list +
                    " are not independent at this configuration (singular start)",
                ic.velocities.empty() ? m.name : ic.velocities[0].first, t0);
  }
  s.q1 = rhs;
  lu.solve_in_place(s.q1);
  return s;
}

namespace {

// Workspace of one forward run.
struct ForwardData {
  const Model& m;
  const ForwardOptions& o;
  MatrixXd M, M0, W0, B, A, Psi, H, KKT, K, S, CtMC;
  VectorXd b, c, f, Bu, u, lambda, rhs, a, psi, tmp0, tmp1, local, ap, red, dq0, dq1, r1;
  Eigen::LLT<MatrixXd> llt_H, llt_G0, llt_G1;
  detail::SmallLU lu_kkt, lu_K;
  std::vector<detail::SlotEntry> entries;  // reactions: A entries attributed to body slots
  std::vector<double> edge_force;
  std::vector<int> edge_offset;
  VectorXd reactions, la, w, lam_ls;
  Eigen::LLT<MatrixXd> llt_AAt;
  Eigen::LLT<MatrixXd> llt_red;
  std::vector<int> independent;  // null space: independent quasi-velocities
  double alpha = 0;
  ForwardStats stats;
  double last_pivot = 1;

  ForwardData(const Model& model, const ForwardOptions& opt) : m(model), o(opt) {
    M = mass_matrix(m);
    B = input_matrix(m);
    A = MatrixXd::Zero(m.m1, m.n1);
    Psi = MatrixXd::Zero(m.m0, m.n0);
    H = MatrixXd::Zero(m.n1, m.n1);
    b = c = VectorXd::Zero(m.m1);
    f = Bu = rhs = a = ap = tmp0 = tmp1 = VectorXd::Zero(m.n1);
    u = VectorXd::Zero(m.n_inputs());
    lambda = VectorXd::Zero(m.m1);
    psi = VectorXd::Zero(m.m0);
    local = VectorXd::Zero(m.n_slots);
    KKT = MatrixXd::Zero(m.n1 + m.m1, m.n1 + m.m1);
    lu_kkt = detail::SmallLU(m.n1 + m.m1);
    K = MatrixXd::Zero(m.n1, m.n1);
    lu_K = detail::SmallLU(m.n1);
    S = MatrixXd::Zero(m.n1, m.dof);
    CtMC = MatrixXd::Zero(m.dof, m.dof);
    red = VectorXd::Zero(m.dof);
    // penalty: large against the mass, as in Bayo & Garcia de Jalon's augmented Lagrangian
    const double mscale = std::max(M.diagonal().maxCoeff(), 1e-12);
    alpha = o.penalty > 0 ? o.penalty : 1e7 * mscale;
    // position metric: the mass of the node coordinates, kept definite for massless nodes
    M0 = M.topLeftCorner(m.n0, m.n0);
    M0.diagonal().array() += 1e-6 * mscale;
    W0 = MatrixXd::Zero(m.n0, m.n0);
    dq0 = VectorXd::Zero(m.n0);
    dq1 = VectorXd::Zero(m.n1);
    r1 = VectorXd::Zero(m.m1);
    edge_force.assign(detail::merge_edge_layout(m, edge_offset), 0.0);
    reactions = VectorXd::Zero(m.n_reactions());
    la = VectorXd::Zero(m.n_slots);
    w = VectorXd::Zero(m.n1);
    lam_ls = VectorXd::Zero(m.m1);
  }

  void inputs(double t) {
    for (int k = 0; k < m.n_inputs(); ++k) {
      const bool has = k < static_cast<int>(o.efforts.size()) && o.efforts[k];
      u[k] = has ? o.efforts[k](t) : 0.0;
      if (!std::isfinite(u[k]))
        throw Error("effort of input '" + m.inputs[k].label + "' is not finite at t = " + fmt(t),
                    m.inputs[k].label, t);
    }
    Bu.noalias() = B * u;
  }

  void choose_independent(const VectorXd& q0, double t) {
    velocity_jacobian(m, q0, t, A, b);
    Eigen::ColPivHouseholderQR<MatrixXd> qr(A);
    const auto& p = qr.colsPermutation().indices();
    independent.assign(p.data() + (m.n1 - m.dof), p.data() + m.n1);
  }

  // a1 = accelerations at (t, q0, q1). With baumgarte, A a = c - alpha (A q1 - b).
  void accelerations(double t, const VectorXd& q0, const VectorXd& q1, bool baumgarte) {
    ++stats.rhs_evaluations;
    velocity_jacobian(m, q0, t, A, b);
    acceleration_rhs(m, q0, q1, t, c);
    if (baumgarte) c.noalias() -= o.baumgarte_alpha * (A * q1 - b);
    body_applied(m, q0, q1, t, local);
    f.setZero();
    scatter_local(m, local, f);
    inputs(t);
    rhs = f + Bu;
    switch (o.formulation) {
      case Formulation::augmented_lagrangian: {
        H = M;
        H.noalias() += alpha * A.transpose() * A;
        llt_H.compute(H);
        ++stats.factorizations;
        if (llt_H.info() != Eigen::Success)
          throw Error("forward dynamics of '" + m.name + "': the mass matrix is not positive on "
                      "the mechanism's motions at t = " + fmt(t) +
                      " (a body without mass or inertia?)",
                      m.name, t);
        // Iterate in residual form (warm start: the previous multipliers): with
        // r1 = f + B u - M a - A^T lambda and r2 = c - A a,  H da = r1 + alpha A^T r2,
        // a += da, lambda -= alpha (c - A a). Being written on the true residuals, the
        // iteration also refines away the rounding of the (ill-conditioned) H solves.
        // Iterate in residual form, warm-started from the last multipliers (reset if not
        // finite): r1 = f + B u - M a - A^T lambda, r2 = c - A a; H da = r1 + alpha A^T r2,
        // a += da, lambda -= alpha (c - A a). Written on the true residuals, the iteration also
        // refines away the rounding of the (ill-conditioned) H solves. It stops when converged or
        // when the residual no longer halves: at the rounding floor, or where the Jacobian loses
        // rank -- there the penalty regularizes the constraint instead of enforcing it with
        // unbounded multipliers.
        if (!lambda.allFinite()) lambda.setZero();
        a.setZero();
        double prev = INFINITY;
        int it = 0;
        // scale of r2: |c|, plus a constant term so that a state at rest (c = 0) is judged on the
        // absolute residual
        const double c_floor = 0.1 * (1 + A.cwiseAbs().maxCoeff());
        for (; it < 40; ++it) {
          tmp0 = rhs;
          tmp0.noalias() -= M * a;
          tmp1.noalias() = A.transpose() * lambda;
          tmp0 -= tmp1;                                        // r1
          ap.head(m.m1) = c;
          ap.head(m.m1).noalias() -= A * a;                    // r2
          const double s1 = rhs.lpNorm<Eigen::Infinity>() + tmp1.lpNorm<Eigen::Infinity>() + 1e-300;
          const double s2 = c.lpNorm<Eigen::Infinity>() + c_floor;
          const double e = std::max(tmp0.lpNorm<Eigen::Infinity>() / s1,
                                    ap.head(m.m1).lpNorm<Eigen::Infinity>() / s2);
          if (it > 0 && (e <= 1e-14 || e > 0.5 * prev)) break;
          prev = e;
          tmp0.noalias() += alpha * A.transpose() * ap.head(m.m1);
          llt_H.solveInPlace(tmp0);
          a += tmp0;
          ap.head(m.m1) = c;
          ap.head(m.m1).noalias() -= A * a;
          lambda.noalias() -= alpha * ap.head(m.m1);
        }
        stats.solver_iterations += it;
        if (!lambda.allFinite()) lambda.setZero();
        break;
      }
      case Formulation::lagrange: {
        KKT.setZero();
        KKT.topLeftCorner(m.n1, m.n1) = M;
        KKT.topRightCorner(m.n1, m.m1) = A.transpose();
        KKT.bottomLeftCorner(m.m1, m.n1) = A;
        ++stats.factorizations;
        const double r = lu_kkt.compute(KKT);
        if (r < 1e-14)
          throw Error("forward dynamics of '" + m.name + "': [M A^T; A 0] is singular at t = " +
                          fmt(t) + " s (singular configuration; use the augmented Lagrangian)",
                      m.name, t);
        VectorXd& x = tmp1;
        x.resize(m.n1 + m.m1);
        x.head(m.n1) = rhs;
        x.tail(m.m1) = c;
        lu_kkt.solve_in_place(x);
        a = x.head(m.n1);
        lambda = x.tail(m.m1);
        break;
      }
      case Formulation::null_space: {
        if (independent.empty()) choose_independent(q0, t);
        auto build = [&] {
          K.setZero();
          K.topRows(m.m1) = A;
          for (int k = 0; k < m.dof; ++k) K(m.m1 + k, independent[k]) = 1.0;
          ++stats.factorizations;
          return lu_K.compute(K);
        };
        if (build() < 1e-8) {  // partition switch: re-choose the independent variables
          choose_independent(q0, t);
          velocity_jacobian(m, q0, t, A, b);
          if (build() < 1e-14)
            throw Error("forward dynamics of '" + m.name + "': no independent coordinates at t = " +
                            fmt(t) + " s (singular configuration; use the augmented Lagrangian)",
                        m.name, t);
        }
        // a = a_p + C x with a_p = K^-1 [c; 0], C = K^-1 [0; I]; C^T M C x = C^T (f + B u - M a_p)
        ap.setZero();
        ap.head(m.m1) = c;
        lu_K.solve_in_place(ap);
        for (int k = 0; k < m.dof; ++k) {
          auto col = S.col(k);
          col.setZero();
          col[m.m1 + k] = 1.0;
          lu_K.solve_in_place(col);
        }
        CtMC.noalias() = S.transpose() * M * S;
        red.noalias() = S.transpose() * (rhs - M * ap);
        llt_red.compute(CtMC);
        if (llt_red.info() != Eigen::Success)
          throw Error("forward dynamics of '" + m.name + "': the reduced mass matrix C^T M C is "
                      "not positive definite at t = " + fmt(t) + " (a body without mass?)",
                      m.name, t);
        llt_red.solveInPlace(red);
        a = ap;
        a.noalias() += S * red;
        break;
      }
    }
    if (!q0.allFinite() || !q1.allFinite())
      throw Error("forward dynamics of '" + m.name + "': the integrator produced a non-finite state "
                  "at t = " + fmt(t), m.name, t);
    if (!a.allFinite())
      throw Error("forward dynamics of '" + m.name + "': non-finite accelerations at t = " + fmt(t),
                  m.name, t);
  }

  // Project q0 on psi = 0 and q1 on A q1 = b, mass-orthogonally and regularized by the
  // augmented-Lagrangian penalty (Bayo, Cuadrado): (W + alpha J^T J) dx = -alpha J^T r, iterated.
  // In regular directions each iteration divides the residual by ~alpha sigma^2 / m (~1e7); in a
  // direction where the Jacobian loses rank (sigma -> 0) the correction vanishes instead of
  // blowing up as 1/sigma, so a state near a singular position is not thrown onto another branch.
  void project(double t, VectorXd& q0, VectorXd& q1, double tol_pos, double tol_vel) {
    ++stats.projections;
    if (m.m0 > 0) {
      for (int it = 0; it < 6; ++it) {
        position_jacobian(m, q0, t, psi, Psi);
        if (psi.lpNorm<Eigen::Infinity>() <= tol_pos) break;
        W0 = M0;
        W0.noalias() += alpha * Psi.transpose() * Psi;
        llt_G0.compute(W0);
        dq0.noalias() = -alpha * Psi.transpose() * psi;
        llt_G0.solveInPlace(dq0);
        q0 += dq0;
      }
    }
    if (m.m1 == 0) return;
    velocity_jacobian(m, q0, t, A, b);
    bool factored = false;
    for (int it = 0; it < 6; ++it) {
      r1.noalias() = A * q1;
      r1 -= b;
      if (r1.lpNorm<Eigen::Infinity>() <= tol_vel) break;
      if (!factored) {
        H = M;
        H.noalias() += alpha * A.transpose() * A;
        llt_G1.compute(H);
        factored = true;
      }
      dq1.noalias() = -alpha * A.transpose() * r1;
      llt_G1.solveInPlace(dq1);
      q1 += dq1;
    }
  }

  // Reactions of a recorded state with accelerations `a` (least-squares multipliers of
  // A^T lambda = B u - (M a - f); regularized where A loses rank).
  void compute_reactions(double t, const VectorXd& q0, const VectorXd& q1) {
    A.setZero();
    entries.clear();
    detail::SlotRecordSink sink{A, m, entries};
    for (const auto& k : m.constraints) detail::velocity_rows(m, k, q0, t, b, sink);
    body_inertia(m, a, la);
    body_applied(m, q0, q1, t, local);
    la -= local;  // M a - f, body-local
    w.setZero();
    scatter_local(m, la, w);
    inputs(t);
    if (m.m1 > 0) {
      MatrixXd G = A * A.transpose();
      G.diagonal().array() += 1e-14 * std::max(1.0, G.diagonal().maxCoeff());
      llt_AAt.compute(G);
      lam_ls.noalias() = A * (Bu - w);
      llt_AAt.solveInPlace(lam_ls);
    }
    detail::joint_reactions(m, entries, lam_ls, u, la, edge_force, edge_offset, reactions);
  }

  double pivot_indicator(double t, const VectorXd& q0) {
    velocity_jacobian(m, q0, t, A, b);
    if (m.m1 == 0) return 1.0;
    MatrixXd G = A * A.transpose();
    detail::SmallLU lu(m.m1);
    return lu.compute(G);
  }
};

// ---- output recording -----------------------------------------------------------------------------
struct Recorder {
  const Model& m;
  ForwardResult& r;
  ForwardData& d;
  int k = 0;
  void record(double t, const VectorXd& q0, const VectorXd& q1, double work, double dissipated) {
    r.time[k] = t;
    r.q0.row(k) = q0.transpose();
    r.q1.row(k) = q1.transpose();
    d.accelerations(t, q0, q1, d.o.integrator == Integrator::baumgarte);
    r.a1.row(k) = d.a.transpose();
    d.compute_reactions(t, q0, q1);
    r.reactions.row(k) = d.reactions.transpose();
    r.efforts.row(k) = d.u.transpose();
    r.kinetic[k] = kinetic_energy(m, q1);
    r.potential[k] = potential_energy(m, q0);
    r.input_work[k] = work;
    r.dissipated[k] = dissipated;
    VectorXd psi(m.m0);
    position_residual(m, q0, t, psi);
    r.residuals(k, 0) = m.m0 ? psi.lpNorm<Eigen::Infinity>() : 0.0;
    velocity_jacobian(m, q0, t, d.A, d.b);
    r.residuals(k, 1) = m.m1 ? (d.A * q1 - d.b).lpNorm<Eigen::Infinity>() : 0.0;
    const double piv = d.pivot_indicator(t, q0);
    d.stats.min_pivot_ratio = std::min(d.stats.min_pivot_ratio, piv);
    if (piv < d.o.singular_warning && d.stats.warnings.size() < 20)
      d.stats.warnings.push_back("near-singular configuration at t = " + fmt(t) +
                                 " s (constraint Jacobian pivot ratio " + fmt(piv) + ")");
    ++k;
  }
};

// ---- fixed-step Runge-Kutta (rk4 with projection; baumgarte without) ----------------------------
void run_rk4(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
             Recorder& rec) {
  const bool baum = o.integrator == Integrator::baumgarte;
  const int n0 = m.n0, n1 = m.n1;
  VectorXd q0 = s0.q0, q1 = s0.q1;
  double W = 0, D = 0, t = o.t0;
  // state derivative: (q1.head(n0), a1, input power u.B^T q1, damper power)
  VectorXd k0[4], k1[4], kw(4), kd(4);
  for (int i = 0; i < 4; ++i) k0[i].resize(n0), k1[i].resize(n1);
  VectorXd y0(n0), y1(n1);
  auto deriv = [&](int i, double tt, const VectorXd& x0, const VectorXd& x1) {
    d.accelerations(tt, x0, x1, baum);
    k0[i] = x1.head(n0);
    k1[i] = d.a;
    kw[i] = d.Bu.dot(x1);
    kd[i] = damping_power(m, x0, x1);
  };
  auto event = [&](double tt, const VectorXd& x0, const VectorXd& x1) {
    return o.stop_when ? o.stop_when(tt, x0, x1) : 1.0;
  };
  const double tol_pos = 1e-13 * m.scale, tol_vel = 1e-13 * m.scale;
  rec.record(t, q0, q1, W, D);
  double g_prev = event(t, q0, q1);
  for (int k = 1; k < o.samples; ++k) {
    const double t_out = o.t0 + (o.t1 - o.t0) * k / (o.samples - 1);
    const int nsteps = std::max(1, static_cast<int>(std::ceil((t_out - t) / o.step - 1e-9)));
    const double h = (t_out - t) / nsteps;
    for (int s = 0; s < nsteps; ++s) {
      auto step = [&](double hh, VectorXd& x0, VectorXd& x1, double& w, double& dd, double tt) {
        deriv(0, tt, x0, x1);
        y0 = x0 + 0.5 * hh * k0[0];
        y1 = x1 + 0.5 * hh * k1[0];
        deriv(1, tt + 0.5 * hh, y0, y1);
        y0 = x0 + 0.5 * hh * k0[1];
        y1 = x1 + 0.5 * hh * k1[1];
        deriv(2, tt + 0.5 * hh, y0, y1);
        y0 = x0 + hh * k0[2];
        y1 = x1 + hh * k1[2];
        deriv(3, tt + hh, y0, y1);
        x0 += (hh / 6) * (k0[0] + 2 * k0[1] + 2 * k0[2] + k0[3]);
        x1 += (hh / 6) * (k1[0] + 2 * k1[1] + 2 * k1[2] + k1[3]);
        w += (hh / 6) * (kw[0] + 2 * kw[1] + 2 * kw[2] + kw[3]);
        dd += (hh / 6) * (kd[0] + 2 * kd[1] + 2 * kd[2] + kd[3]);
        if (!baum) d.project(tt + hh, x0, x1, tol_pos, tol_vel);
        ++d.stats.steps;
      };
      const VectorXd q0s = q0, q1s = q1;
      const double Ws = W, Ds = D, ts = t;
      step(h, q0, q1, W, D, t);
      t = ts + h;
      if (o.stop_when) {
        const double g = event(t, q0, q1);
        if ((g_prev < 0) != (g < 0) && g_prev != 0) {
          // locate the crossing by the secant on the step, then redo the step up to it
          double lo = 0, hi = h, glo = g_prev, ghi = g;
          for (int it = 0; it < 40; ++it) {
            const double mid = lo + (hi - lo) * glo / (glo - ghi);
            VectorXd a0 = q0s, a1 = q1s;
            double w = Ws, dd = Ds;
            step(mid, a0, a1, w, dd, ts);
            const double gm = event(ts + mid, a0, a1);
            if ((gm < 0) == (glo < 0)) lo = mid, glo = gm; else hi = mid, ghi = gm;
            if (std::abs(hi - lo) < 1e-13 * std::max(1.0, std::abs(ts)) || gm == 0) {
              q0 = a0, q1 = a1, W = w, D = dd, t = ts + mid;
              break;
            }
          }
          d.stats.stopped_by_event = true;
          d.stats.t_end = t;
          rec.record(t, q0, q1, W, D);
          return;
        }
        g_prev = g;
      }
    }
    t = t_out;
    rec.record(t, q0, q1, W, D);
  }
  d.stats.t_end = t;
}

// ---- SUNDIALS CVODE ----------------------------------------------------------------------------
struct CvodeUser {
  const Model* m;
  ForwardData* d;
  VectorXd q0, q1;
  bool baumgarte = false;
  std::string last_error;  // message of the last failed right-hand side evaluation
};

int cv_rhs(realtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  const double* yd = N_VGetArrayPointer(y);
  double* out = N_VGetArrayPointer(ydot);
  u->q0 = Eigen::Map<const VectorXd>(yd, m.n0);
  u->q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
  try {
    u->d->accelerations(t, u->q0, u->q1, u->baumgarte);
  } catch (const Error& e) {
    u->last_error = e.what();
    return 1;  // recoverable: CVODE retries with a smaller step
  }
  Eigen::Map<VectorXd>(out, m.n0) = u->q1.head(m.n0);
  Eigen::Map<VectorXd>(out + m.n0, m.n1) = u->d->a;

  out[m.n0 + m.n1] = u->d->Bu.dot(u->q1);
  out[m.n0 + m.n1 + 1] = damping_power(m, u->q0, u->q1);
  return 0;
}

int cv_proj(realtype t, N_Vector ycur, N_Vector corr, realtype eps, N_Vector err, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  ForwardData& d = *u->d;
  const double* y = N_VGetArrayPointer(ycur);
  double* c = N_VGetArrayPointer(corr);
  VectorXd q0 = Eigen::Map<const VectorXd>(y, m.n0), q1 = Eigen::Map<const VectorXd>(y + m.n0, m.n1);
  const VectorXd q0s = q0, q1s = q1;
  // Project well below the solver's own tolerance: CVODE measures the correction in its error
  // weights (1 / (rtol |y| + atol)), so a projection left at a looser level than atol makes every
  // step look inaccurate and drives the step size to zero. (eps: CVODE's projection tolerance.)
  (void)eps;
  const double tol = std::max(1e-3 * d.o.atol, 4e-16 * m.scale);
  d.project(t, q0, q1, tol, tol);
  Eigen::Map<VectorXd>(c, m.n0) = q0 - q0s;
  Eigen::Map<VectorXd>(c + m.n0, m.n1) = q1 - q1s;

  c[m.n0 + m.n1] = c[m.n0 + m.n1 + 1] = 0;
  if (err) {  // project the error estimate on the tangent spaces
    double* e = N_VGetArrayPointer(err);
    Eigen::Map<VectorXd> e0(e, m.n0), e1(e + m.n0, m.n1);
    if (m.m0) {
      position_jacobian(m, q0, t, d.psi, d.Psi);
      MatrixXd G = d.Psi * d.Psi.transpose();
      G.diagonal().array() += 1e-13 * std::max(1.0, G.diagonal().maxCoeff());
      e0 -= d.Psi.transpose() * G.llt().solve(d.Psi * e0);
    }
    if (m.m1) {
      velocity_jacobian(m, q0, t, d.A, d.b);
      MatrixXd G = d.A * d.A.transpose();
      G.diagonal().array() += 1e-13 * std::max(1.0, G.diagonal().maxCoeff());
      e1 -= d.A.transpose() * G.llt().solve(d.A * e1);
    }
  }
  return 0;
}

int cv_root(realtype t, N_Vector y, realtype* g, void* user) {
  auto* u = static_cast<CvodeUser*>(user);
  const Model& m = *u->m;
  const double* yd = N_VGetArrayPointer(y);
  const VectorXd q0 = Eigen::Map<const VectorXd>(yd, m.n0);
  const VectorXd q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
  g[0] = u->d->o.stop_when(t, q0, q1);
  return 0;
}

// CVODE's messages go to the run's warnings, not to stderr.
void cv_error_handler(int code, const char* module, const char* function, char* msg, void* data) {
  auto* stats = static_cast<ForwardStats*>(data);
  if (stats->warnings.size() < 20)
    stats->warnings.push_back(std::string(code < 0 ? "error" : "warning") + " in " + module + " " +
                              function + ": " + msg);
}

struct SundialsDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};

void check_flag(int flag, const char* call, double t) {
  if (flag < 0)
    throw Error(std::string("SUNDIALS ") + call + " failed (flag " + std::to_string(flag) +
                    ") at t = " + fmt(t),
                call, t);
}

void run_cvode(const Model& m, ForwardData& d, const State& s0, const ForwardOptions& o,
               Recorder& rec) {
  const int n = m.n0 + m.n1 + 2;  // q0, q1, input work, dissipated energy
  SUNContext ctx = nullptr;
  check_flag(SUNContext_Create(nullptr, &ctx), "SUNContext_Create", o.t0);
  std::unique_ptr<std::remove_pointer_t<SUNContext>, SundialsDeleter> ctx_guard(ctx);
  N_Vector y = N_VNew_Serial(n, ctx);
  std::unique_ptr<std::remove_pointer_t<N_Vector>, void (*)(N_Vector)> y_guard(y, N_VDestroy);
  N_Vector atol = N_VNew_Serial(n, ctx);
  std::unique_ptr<std::remove_pointer_t<N_Vector>, void (*)(N_Vector)> a_guard(atol, N_VDestroy);
  double* yd = N_VGetArrayPointer(y);
  Eigen::Map<VectorXd>(yd, m.n0) = s0.q0;
  Eigen::Map<VectorXd>(yd + m.n0, m.n1) = s0.q1;
  yd[n - 2] = yd[n - 1] = 0;
  N_VConst(o.atol, atol);
  // the quadratures are integrated to the state's accuracy but do not control the step
  N_VGetArrayPointer(atol)[n - 2] = N_VGetArrayPointer(atol)[n - 1] = 1e6;
  const bool bdf = o.integrator == Integrator::cvode_bdf;
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  if (!mem) throw Error("SUNDIALS CVodeCreate failed", "CVodeCreate", o.t0);
  std::unique_ptr<void, void (*)(void*)> mem_guard(mem, [](void* p) { CVodeFree(&p); });
  CvodeUser user{&m, &d, VectorXd(m.n0), VectorXd(m.n1), false, {}};
  check_flag(CVodeInit(mem, cv_rhs, o.t0, y), "CVodeInit", o.t0);
  check_flag(CVodeSetUserData(mem, &user), "CVodeSetUserData", o.t0);
  check_flag(CVodeSetErrHandlerFn(mem, cv_error_handler, &d.stats), "CVodeSetErrHandlerFn", o.t0);
  check_flag(CVodeSVtolerances(mem, o.rtol, atol), "CVodeSVtolerances", o.t0);
  check_flag(CVodeSetMaxNumSteps(mem, o.max_steps), "CVodeSetMaxNumSteps", o.t0);
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  SUNNonlinearSolver NLS = nullptr;
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, void (*)(SUNMatrix)> A_guard(nullptr, SUNMatDestroy);
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, int (*)(SUNLinearSolver)> LS_guard(nullptr, SUNLinSolFree);
  std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, int (*)(SUNNonlinearSolver)> NLS_guard(nullptr, SUNNonlinSolFree);
  if (bdf) {
    A = SUNDenseMatrix(n, n, ctx);
    A_guard.reset(A);
    LS = SUNLinSol_Dense(y, A, ctx);
    LS_guard.reset(LS);
    check_flag(CVodeSetLinearSolver(mem, LS, A), "CVodeSetLinearSolver", o.t0);
    check_flag(CVodeSetProjFn(mem, cv_proj), "CVodeSetProjFn", o.t0);
  } else {
    NLS = SUNNonlinSol_FixedPoint(y, 0, ctx);
    NLS_guard.reset(NLS);
    check_flag(CVodeSetNonlinearSolver(mem, NLS), "CVodeSetNonlinearSolver", o.t0);
  }
  if (o.stop_when) check_flag(CVodeRootInit(mem, 1, cv_root), "CVodeRootInit", o.t0);
  VectorXd q0 = s0.q0, q1 = s0.q1;
  rec.record(o.t0, q0, q1, 0.0, 0.0);
  double t = o.t0;
  for (int k = 1; k < o.samples; ++k) {
    const double t_out = o.t0 + (o.t1 - o.t0) * k / (o.samples - 1);
    check_flag(CVodeSetStopTime(mem, t_out), "CVodeSetStopTime", t);
    int flag = CVode(mem, t_out, y, &t, CV_NORMAL);
    if (flag < 0) {
      std::ostringstream s;
      s << "forward dynamics of '" << m.name << "' stopped at t = " << fmt(t)
        << " s: CVODE could not continue (flag " << flag << ")";
      if (!user.last_error.empty()) s << " after: " << user.last_error;
      q0 = Eigen::Map<const VectorXd>(yd, m.n0);
      const double piv = d.pivot_indicator(t, q0);
      if (piv < o.singular_warning)
        s << "; the constraint Jacobian is near-singular there (pivot ratio " << fmt(piv) << ")";
      s << "; configuration:";
      for (int j = 0; j < std::min(m.n0, 12); ++j) s << " " << m.coordinate_labels[j] << "=" << fmt(q0[j]);
      throw Error(s.str(), m.name, t);
    }
    q0 = Eigen::Map<const VectorXd>(yd, m.n0);
    q1 = Eigen::Map<const VectorXd>(yd + m.n0, m.n1);
    rec.record(t, q0, q1, yd[n - 2], yd[n - 1]);
    if (flag == CV_ROOT_RETURN) {
      d.stats.stopped_by_event = true;
      break;
    }
  }
  d.stats.t_end = t;
  long v = 0;
  CVodeGetNumSteps(mem, &v);
  d.stats.steps = v;
  CVodeGetNumErrTestFails(mem, &v);
  d.stats.error_test_failures = v;
  if (bdf) {
    CVodeGetNumLinSolvSetups(mem, &v);
    d.stats.factorizations = v;
    CVodeGetNumProjEvals(mem, &v);
    d.stats.projections = v;
  }
}

}  // namespace

ForwardResult forward_dynamics(const Model& m, const State& initial, const ForwardOptions& o) {
  if (!(o.samples >= 2) || !std::isfinite(o.t0) || !std::isfinite(o.t1) || !(o.t1 > o.t0))
    throw Error("forward dynamics: need samples >= 2 and finite t0 < t1", "options");
  if ((o.integrator == Integrator::rk4 || o.integrator == Integrator::baumgarte) &&
      !(o.step > 0 && std::isfinite(o.step)))
    throw Error("forward dynamics: the fixed step must be positive (got " + fmt(o.step) + ")",
                "step");
  if ((o.integrator == Integrator::cvode_bdf || o.integrator == Integrator::cvode_adams) &&
      !(o.rtol > 0 && o.atol > 0))
    throw Error("forward dynamics: tolerances must be positive", "rtol");
  if (initial.q0.size() != m.n0 || initial.q1.size() != m.n1)
    throw Error("forward dynamics: the initial state does not match the model's variables", m.name);
  if (static_cast<int>(o.efforts.size()) > m.n_inputs())
    throw Error("forward dynamics: more efforts (" + std::to_string(o.efforts.size()) +
                    ") than inputs (" + std::to_string(m.n_inputs()) + ")",
                m.name);
  ForwardData d(m, o);
  ForwardResult r;
  r.coordinate_labels = m.coordinate_labels;
  r.rate_labels = m.rate_labels;
  r.input_labels = m.input_labels();
  r.reaction_labels = m.reaction_labels();
  const int N = o.samples;
  r.efforts = MatrixXd::Zero(N, m.n_inputs());
  r.reactions = MatrixXd::Zero(N, m.n_reactions());
  r.time = VectorXd::Zero(N);
  r.q0 = MatrixXd::Zero(N, m.n0);
  r.q1 = MatrixXd::Zero(N, m.n1);
  r.a1 = MatrixXd::Zero(N, m.n1);
  r.kinetic = r.potential = r.input_work = r.dissipated = VectorXd::Zero(N);
  r.residuals = MatrixXd::Zero(N, 2);
  Recorder rec{m, r, d};
  const double start = detail::cpu_seconds();
  State s0 = initial;
  s0.t = o.t0;
  switch (o.integrator) {
    case Integrator::rk4:
    case Integrator::baumgarte:
      run_rk4(m, d, s0, o, rec);
      break;
    case Integrator::cvode_bdf:
    case Integrator::cvode_adams:
      run_cvode(m, d, s0, o, rec);
      break;
  }
  d.stats.cpu_seconds = detail::cpu_seconds() - start;
  // trim to the recorded samples (an event may stop early)
  const int used = rec.k;
  r.time.conservativeResize(used);
  r.q0.conservativeResize(used, Eigen::NoChange);
  r.q1.conservativeResize(used, Eigen::NoChange);
  r.a1.conservativeResize(used, Eigen::NoChange);
  r.kinetic.conservativeResize(used);
  r.potential.conservativeResize(used);
  r.input_work.conservativeResize(used);
  r.dissipated.conservativeResize(used);
  r.residuals.conservativeResize(used, Eigen::NoChange);
  r.efforts.conservativeResize(used, Eigen::NoChange);
  r.reactions.conservativeResize(used, Eigen::NoChange);
  r.stats = d.stats;
  return r;
}

std::vector<std::function<double(double)>> efforts_from_inverse(
    const Model& m, std::vector<Prescribed> prescribed, const InverseOptions& options) {
  struct Shared {
    Model model;
    std::vector<Prescribed> prescribed;
    InverseData data;
    double t = NAN;
    Shared(const Model& mm, std::vector<Prescribed> p, const InverseOptions& o)
        : model(mm), prescribed(std::move(p)), data(model, prescribed, o) {}
    double effort(int k, double t_) {
      if (!(t_ == t)) {
        inverse_dynamics_sample(model, data, t_);
        t = t_;
      }
      return data.u[k];
    }
  };
  auto shared = std::make_shared<Shared>(m, std::move(prescribed), options);
  std::vector<std::function<double(double)>> out;
  for (int k = 0; k < m.n_inputs(); ++k)
    out.push_back([shared, k](double t) { return shared->effort(k, t); });
  return out;
}

std::vector<std::function<double(double)>> efforts_from_samples(const InverseResult& r) {
  std::vector<std::function<double(double)>> out;
  const int n = static_cast<int>(r.time.size());
  if (n < 2) throw Error("efforts_from_samples: need at least two samples", "samples");
  for (int k = 0; k < r.efforts.cols(); ++k) {
    auto t = std::make_shared<VectorXd>(r.time);
    auto u = std::make_shared<VectorXd>(r.efforts.col(k));
    auto du = std::make_shared<VectorXd>(n);
    for (int i = 0; i < n; ++i) {
      const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
      (*du)[i] = ((*u)[b] - (*u)[a]) / ((*t)[b] - (*t)[a]);
    }
    out.push_back([t, u, du, n](double x) {
      if (x <= (*t)[0]) return (*u)[0];
      if (x >= (*t)[n - 1]) return (*u)[n - 1];
      const int i = static_cast<int>(std::upper_bound(t->data(), t->data() + n, x) - t->data()) - 1;
      const double h = (*t)[i + 1] - (*t)[i], s = (x - (*t)[i]) / h;
      const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
      const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
      return h00 * (*u)[i] + h10 * h * (*du)[i] + h01 * (*u)[i + 1] + h11 * h * (*du)[i + 1];
    });
  }
  return out;
}

int ForwardResult::column(const std::string& l) const {
  auto it = std::find(coordinate_labels.begin(), coordinate_labels.end(), l);
  if (it == coordinate_labels.end()) throw Error("unknown coordinate '" + l + "'", l);
  return static_cast<int>(it - coordinate_labels.begin());
}
int ForwardResult::reaction(const std::string& l) const {
  auto it = std::find(reaction_labels.begin(), reaction_labels.end(), l);
  if (it == reaction_labels.end()) throw Error("unknown reaction '" + l + "'", l);
  return static_cast<int>(it - reaction_labels.begin());
}
int ForwardResult::rate_column(const std::string& l) const {
  auto it = std::find(rate_labels.begin(), rate_labels.end(), l);
  if (it == rate_labels.end()) throw Error("unknown quasi-velocity '" + l + "'", l);
  return static_cast<int>(it - rate_labels.begin());
}

}  // namespace mo2d
