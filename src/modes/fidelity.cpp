// The fidelity report (mo2d/fidelity.hpp; docs/reduction.md, "Which springs to reduce"): each
// compliant element's own frequency omega = sqrt(k / m_r), 1 / m_r = g^T (C^T M C)^-1 g, against
// the time scales of the run.
#include "mo2d/fidelity.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "dynamics/chain.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

bool same_point(const BodyPoint& x, const BodyPoint& y) {
  return x.body == y.body && x.ci == y.ci && x.cj == y.cj && x.gamma == y.gamma && x.rho == y.rho &&
         x.fixed == y.fixed;
}

// d law / d (the element's own coordinate) and d law / d (its rate): the law on Jets with the
// direction 1 on the arguments `own` (or `own_rate`) says of the element.
template <class Own, class OwnRate>
std::array<double, 2> law_slopes(const Model& m, const CompiledLaw& law, const VectorXd& q0,
                                 const VectorXd& q1, double t, Own own, OwnRate own_rate) {
  const int n = static_cast<int>(law.args.size());
  std::vector<Jet> x(n);
  for (int k = 0; k < n; ++k) x[k] = Jet(quantity_value(m, law.args[k], q0, q1));
  std::array<double, 2> out{};
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k < n; ++k)
      x[k].d = (pass == 0 ? own(law.args[k]) : own_rate(law.args[k])) ? 1 : 0;
    out[pass] = law.f(std::span<const Jet>(x.data(), n), Jet(t)).d;
  }
  return out;
}

// Basis C of the allowed velocities (null space of A) and the reduced mass matrix C^T M C.
struct Allowed {
  MatrixXd C, Mr;
};
// skip_row: a velocity row left out (a reduced spring's own, to free its length).
Allowed allowed_motion(const Model& m, const VectorXd& q0, double t, int skip_row = -1) {
  Allowed a;
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  if (m.m1 > 0) velocity_jacobian(m, q0, t, A, b);
  if (skip_row >= 0) {
    A.middleRows(skip_row, m.m1 - skip_row - 1) = A.bottomRows(m.m1 - skip_row - 1).eval();
    A.conservativeResize(m.m1 - 1, Eigen::NoChange);
  }
  if (A.rows() == 0)
    a.C = MatrixXd::Identity(m.n1, m.n1);
  else
    a.C = Eigen::FullPivLU<MatrixXd>(A).kernel();
  a.Mr = a.C.transpose() * mass_matrix(m) * a.C;
  return a;
}

// m_r of the rate g . q1 (g over q1): 1 / (g_r^T Mr^-1 g_r), inf where g_r = 0 (the element's
// coordinate cannot move), 0 where Mr is singular along it (no inertia).
double reflected_inertia(const Allowed& a, const VectorXd& g) {
  const VectorXd gr = a.C.transpose() * g;
  if (gr.norm() <= 1e-12 * g.norm()) return std::numeric_limits<double>::infinity();
  const Eigen::LDLT<MatrixXd> ldlt(a.Mr);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) return 0;
  return 1 / gr.dot(ldlt.solve(gr));
}

// dq/dt . e_j for every quasi-velocity j: the gradient of a rate quantity over q1.
VectorXd rate_gradient(const Model& m, const Quantity& rate, const VectorXd& q0) {
  VectorXd g(m.n1), e = VectorXd::Zero(m.n1);
  for (int j = 0; j < m.n1; ++j) {
    e[j] = 1;
    g[j] = quantity_value(m, rate, q0, e);
    e[j] = 0;
  }
  return g;
}

std::string verdict(const CompliantElement& c, const RunTimeScale& s) {
  if (c.reduced && c.omega == 0) return "reduced (" + c.reduction + "): rigid, no mode";
  if (c.omega == 0) return "no stiffness at this configuration";
  if (std::isinf(c.inertia))
    return std::string(c.reduced ? "reduced (" + c.reduction + "); " : "") +
           "cannot move (its length is held by the constraints)";
  if (c.inertia == 0) return "no inertia along it: a massless, infinitely fast mode";
  char buf[200];
  const double rel = c.omega * s.output_interval / std::numbers::pi;  // omega / omega_out
  if (c.reduced)
    std::snprintf(buf, sizeof buf, "reduced (%s): its mode is removed (error ~ %.1e)",
                  c.reduction.c_str(), c.error_output);
  else if (rel > 10)
    std::snprintf(buf, sizeof buf,
                  "faster than the outputs resolve: reduce: constraint, or reduce: "
                  "quasi_steady to keep its stretch T/k (error ~ %.1e)",
                  c.error_output);
  else if (rel > 1)
    std::snprintf(buf, sizeof buf, "near the output rate: reduce only if %.1e is acceptable",
                  c.error_output);
  else
    std::snprintf(buf, sizeof buf, "resolved by the outputs: keep it");
  std::string v = buf;
  if (s.step > 0 && !c.reduced && c.omega * s.step > 2.78)
    v += "; UNSTABLE with RK4 at this step (omega h > 2.78)";
  return v;
}

void complete(CompliantElement& c, const RunTimeScale& s) {
  c.omega = c.stiffness > 0 ? std::sqrt(c.stiffness / c.inertia) : 0;
  if (c.stiffness > 0 && c.inertia == 0) c.omega = std::numeric_limits<double>::infinity();
  if (std::isinf(c.inertia)) c.omega = 0;
  const double kc = c.stiffness * c.inertia;
  c.damping_ratio = kc > 0 && std::isfinite(kc) ? c.damping / (2 * std::sqrt(kc)) : 0;
  if (c.omega > 0) {
    const double w_out = std::numbers::pi / s.output_interval;
    const double w_run = 2 * std::numbers::pi / s.duration;
    c.error_output = (w_out / c.omega) * (w_out / c.omega);
    c.error_run = (w_run / c.omega) * (w_run / c.omega);
    if (s.step > 0) c.steps_per_period = 2 * std::numbers::pi / (c.omega * s.step);
  }
  c.verdict = verdict(c, s);
}

CompliantElement spring_element(const Model& m, const SpringLoad& s, const Allowed& a,
                                const VectorXd& q0, const VectorXd& q1, double t) {
  CompliantElement c;
  c.name = s.name;
  c.kind = "spring";
  c.stiffness = s.stiffness;
  c.damping = s.damping;
  if (s.tension) {
    using K = Quantity::Kind;
    const auto own = [&](const Quantity& q) {
      return q.kind == K::distance && same_point(q.a, s.a) && same_point(q.b, s.b);
    };
    const auto own_rate = [&](const Quantity& q) {
      return q.kind == K::distance_rate && same_point(q.a, s.a) && same_point(q.b, s.b);
    };
    const auto [k, d] = law_slopes(m, s.tension, q0, q1, t, own, own_rate);
    c.stiffness = k;
    c.damping = d;
  }
  Quantity rate;
  rate.kind = Quantity::Kind::distance_rate;
  rate.a = s.a;
  rate.b = s.b;
  c.inertia = reflected_inertia(a, rate_gradient(m, rate, q0));
  return c;
}

CompliantElement torsional_element(const Model& m, const TorsionalLoad& l, const Allowed& a,
                                   const VectorXd& q0, const VectorXd& q1, double t) {
  CompliantElement c;
  c.name = l.name;
  c.kind = "torsional spring";
  c.stiffness = l.stiffness;
  c.damping = l.damping;
  using K = Quantity::Kind;
  if (l.torque) {  // torque = -k angle - c rate: the slopes are -k and -c
    const auto own = [&](const Quantity& q) {
      return q.kind == K::relative_angle && q.body1 == l.body1 && q.body2 == l.body2;
    };
    const auto own_rate = [&](const Quantity& q) {
      return q.kind == K::relative_rate && q.body1 == l.body1 && q.body2 == l.body2;
    };
    const auto [k, d] = law_slopes(m, l.torque, q0, q1, t, own, own_rate);
    c.stiffness = -k;
    c.damping = -d;
  }
  Quantity rate;
  rate.kind = K::relative_rate;
  rate.body1 = l.body1;
  rate.body2 = l.body2;
  c.inertia = reflected_inertia(a, rate_gradient(m, rate, q0));
  return c;
}

// A chain's two spans (docs/reduction.md, "Chain and belt drives"): each span's material length
// has a rate linear in q1, dl/dt = t . (v_b - v_a) +- (r_a w_a - r_b w_b), and the stiffness k
// (a unilateral span only while it is taut).
// An inextensible or quasi-steady chain (reduced: `a` frees its taut span's row) reports the
// stiffness it was given (0: none) and its fidelity.
void add_chain_spans(const Model& m, const ChainLoad& c, const Allowed& a, const VectorXd& q0,
                     double t, std::vector<CompliantElement>& out) {
  VectorXd gu(m.n1), gl(m.n1), e = VectorXd::Zero(m.n1);
  for (int j = 0; j < m.n1; ++j) {
    e[j] = 1;
    const std::array<double, 2> r = detail::chain_span_rates(m, c, q0, e, t);
    gu[j] = r[0];
    gl[j] = r[1];
    e[j] = 0;
  }
  for (int span = 0; span < 2; ++span) {
    CompliantElement el;
    el.name = c.name + (span == 0 ? ".upper" : ".lower");
    el.kind = c.fidelity == ChainFidelity::unilateral ? "chain span (taut)" : "chain span";
    if (c.fidelity == ChainFidelity::inextensible) {  // a quasi-steady chain compiles as one
      el.reduced = true;
      el.reduction = c.held[0] ? "fidelity: quasi_steady" : "fidelity: inextensible";
      el.kind = c.active_span == span ? "chain span (taut)" : "chain span";
    }
    el.stiffness = c.stiffness;
    el.damping = c.damping;
    el.inertia = reflected_inertia(a, span == 0 ? gu : gl);
    out.push_back(std::move(el));
  }
}

// A chain's verdict names what exists for it: `fidelity: inextensible` (the span switching by the
// sign of the tension), or a gear pair where the centres are fixed.
void chain_verdict(CompliantElement& c) {
  const std::string key = "reduce: constraint, or reduce: quasi_steady to keep its stretch T/k";
  const auto at = c.verdict.find(key);
  if (at != std::string::npos)
    c.verdict.replace(at, key.size(),
                      "fidelity: inextensible (or a gear pair of ratio r_a/r_b if the centres are "
                      "fixed)");
}

}  // namespace

std::vector<CompliantElement> fidelity_report(const Model& m, const VectorXd& q0,
                                              const VectorXd& q1, double t,
                                              const RunTimeScale& scale) {
  std::vector<CompliantElement> out;
  const Allowed a = allowed_motion(m, q0, t);
  for (const SpringLoad& s : m.springs) out.push_back(spring_element(m, s, a, q0, q1, t));
  for (const TorsionalLoad& l : m.torsional_springs)
    out.push_back(torsional_element(m, l, a, q0, q1, t));
  // a reduced element: its own mode, its row freed
  auto add_reduced = [&](const auto& r, bool held, const auto& element) {
    const Allowed fa = allowed_motion(m, q0, t, m.constraints[r.constraint].row1);
    CompliantElement c = element(m, r.spring, fa, q0, q1, t);
    c.reduced = true;
    c.reduction = held ? "reduce: quasi_steady" : "reduce: constraint";
    out.push_back(std::move(c));
  };
  for (const ReducedSpring& r : m.reduced_springs)
    add_reduced(r, static_cast<bool>(r.held_length), spring_element);
  for (const ReducedTorsional& r : m.reduced_torsional)
    add_reduced(r, static_cast<bool>(r.held_angle), torsional_element);
  for (const ChainLoad& c : m.chains) {  // a reduced chain's mode: its taut span's row freed
    const bool row = c.constraint >= 0 && m.constraints[c.constraint].nrow1 > 0;
    add_chain_spans(m, c, row ? allowed_motion(m, q0, t, m.constraints[c.constraint].row1) : a, q0,
                    t, out);
  }
  for (CompliantElement& c : out) {
    complete(c, scale);
    if (c.kind.starts_with("chain")) chain_verdict(c);
  }
  return out;
}

std::string describe_fidelity(const std::vector<CompliantElement>& report, const RunTimeScale& s) {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "fidelity: run %g s, outputs every %g s (resolve up to %.4g rad/s)%s\n", s.duration,
                s.output_interval, std::numbers::pi / s.output_interval,
                s.step > 0 ? (", fixed step " + std::to_string(s.step) + " s").c_str() : "");
  out += buf;
  if (report.empty()) return out + "  no compliant elements\n";
  std::snprintf(buf, sizeof buf, "  %-20s %-17s %11s %11s %11s %9s %9s  %s\n", "element", "kind",
                "stiffness", "inertia", "omega", "zeta", "error", "verdict");
  out += buf;
  for (const CompliantElement& c : report) {
    std::snprintf(buf, sizeof buf, "  %-20s %-17s %11.4g %11.4g %11.4g %9.3g %9.2g  %s\n",
                  c.name.c_str(), c.kind.c_str(), c.stiffness, c.inertia, c.omega, c.damping_ratio,
                  c.error_output, c.verdict.c_str());
    out += buf;
  }
  return out;
}

}  // namespace mo2d
