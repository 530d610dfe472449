#pragma once
// Chain and belt drives (ChainDef, ChainLoad): the exact open-belt geometry of two pitch circles
// on moving bodies, the material length of each span, and its generalized force (internal header
// of src/dynamics/; Gamba 2009 §2.2 and §2.5, with the erratum of ../shared/seeds/README.md).
//
// Centres c_a, c_b (radii r_a, r_b), d = c_b - c_a = D (cos beta, sin beta). The outer common
// tangents touch both circles where the radius has direction u = (cos phi, sin phi), with
//   phi = beta + alpha (upper span), beta - alpha (lower span),  cos alpha = (r_a - r_b) / D,
// since (c_b + r_b u - c_a - r_a u) . u = D cos alpha + r_b - r_a = 0. The span runs from
// P_a = c_a + r_a u to P_b = c_b + r_b u: length L = sqrt(D^2 - (r_a - r_b)^2) = D sin alpha,
// unit vector t = (d + (r_b - r_a) u) / L.
//
// Material length. Mark a point of the chain on each sprocket (angles theta_a, theta_b, the
// bodies' unwrapped angles). On sprocket a the chain wraps counter-clockwise from the upper
// tangent point (phi_u) to the lower one; on b from the lower to the upper. The chain between the
// marks through the upper span is the arc r_a (theta_a - phi_u) on a, the span, the arc
// r_b (phi_u - theta_b) on b; the arcs do not stretch, so
//   l_u = L + (r_b - r_a)(beta + alpha) + r_a theta_a - r_b theta_b + const_u
//   l_l = L + (r_a - r_b)(beta - alpha) - r_a theta_a + r_b theta_b + const_l
// The terms (r_b - r_a)(beta +- alpha) are the change of wrap angle when the centre line turns
// or the centres move apart; Gamba's printed extension (e_u = r_ws theta_rw + AC - r_ds theta_ds
// - l0) leaves them out, and its forces then have no potential. With dL = sin alpha dD +
// (r_a - r_b) d alpha, dl/dD = sin alpha and dl/dbeta = +-(r_b - r_a), which is exactly
//   dl_u/dt = t_u . (v_b - v_a) + r_a w_a - r_b w_b,   dl_l/dt = t_l . (v_b - v_a) - r_a w_a + r_b
//   w_b
// (t . e_D = sin alpha, D t . e_beta = +-(r_b - r_a)): the rate of separation of the material
// points at the tangent points along the span (Gamba's A.13, "material body velocity").
//
// Forces (generalized force -T dl/dq, power -T dl/dt): T t at c_a and -T t at c_b, torques
// -+ T r_a on a and +- T r_b on b (upper, lower): the tension T t applied at the material tangent
// points. Tension laws: bilateral T = k e + c de/dt, e = l - rest; unilateral the same while
// e > 0, clipped at 0 (slack), with the elastic energy k e^2 / 2 while e > 0.
//
// Written once for double and Jet (the exact directional derivatives of
// dynamics/derivatives.cpp evaluate the same code on Jets).
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mo2d/error.hpp"
#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

inline double value_of(double x) {
  return x;
}
inline double value_of(const Jet& x) {
  return x.v;
}

// The state of a chain's sprockets: centres, their velocities, unwrapped angles and rates.
template <class S>
struct ChainInput {
  S ax, ay, bx, by;      // centres
  S vax, vay, vbx, vby;  // their velocities
  S theta_a, theta_b;    // unwrapped angles (0 on the ground)
  S wa, wb;              // rotation rates
};

// One span: material length, its rate, and the unit vector from P_a to P_b.
template <class S>
struct Span {
  S length, rate, tx, ty;
};
template <class S>
struct Spans {
  Span<S> upper, lower;
  S L;  // the straight length between the tangent points (both spans)
};

// How far the line of centres may turn from its initial direction (rad).
inline constexpr double kChainMaxTurn = 3.0;

// Throws when the geometry does not exist (one pitch circle inside the other), or when the line
// of centres turns by more than kChainMaxTurn.
template <class S>
Spans<S> chain_spans(const ChainLoad& c, const ChainInput<S>& in, double t) {
  using std::atan2;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S dx = in.bx - in.ax, dy = in.by - in.ay;
  const double dr = c.radius_a - c.radius_b;
  const S D2 = dx * dx + dy * dy;
  if (!(value_of(D2) > dr * dr))
    throw Error("chain '" + c.name + "': the centre distance " +
                    std::to_string(std::sqrt(value_of(D2))) +
                    " m is not larger than |r_a - r_b| = " + std::to_string(std::abs(dr)) +
                    " m at t = " + std::to_string(t) + " s (no open-belt geometry)",
                c.name, t);
  const S L = sqrt(D2 - dr * dr);
  const S alpha = atan2(L, S(dr));
  S beta = atan2(dy, dx);  // unwrapped near the initial direction
  const double k = std::round((value_of(beta) - c.beta0) / (2 * std::numbers::pi));
  beta = beta - 2 * std::numbers::pi * k;
  // The wrap term needs beta unwrapped; it is tracked within +-(pi - margin) of its initial
  // direction only, and past that the length would jump by 2 pi (r_b - r_a): an error, not that.
  if (std::abs(value_of(beta) - c.beta0) > kChainMaxTurn)
    throw Error("chain '" + c.name + "': the line of centres turned " +
                    std::to_string(value_of(beta) - c.beta0) +
                    " rad from its initial direction at t = " + std::to_string(t) +
                    " s; chains whose line of centres turns by more than 3 rad are not supported",
                c.name, t);
  const S wrap = S(c.printed_extension ? 0.0 : 1.0);
  const S vx = in.vbx - in.vax, vy = in.vby - in.vay;
  auto span = [&](double side, double offset) {  // side +1: upper, -1: lower
    const S phi = beta + side * alpha;
    const S ux = cos(phi), uy = sin(phi);
    const S tx = (dx - dr * ux) / L, ty = (dy - dr * uy) / L;
    const S turn = side * (c.radius_a * in.theta_a - c.radius_b * in.theta_b);
    const S length = L - side * dr * phi * wrap + turn + offset;
    const S rate = tx * vx + ty * vy + side * (c.radius_a * in.wa - c.radius_b * in.wb);
    return Span<S>{length, rate, tx, ty};
  };
  return {span(1, c.offset_upper), span(-1, c.offset_lower), L};
}

// A span's tension and its elastic part (the one with a potential), from its extension and rate.
template <class S>
struct SpanTension {
  S T, elastic;
  bool acting;
};
template <class S>
SpanTension<S> span_tension(const ChainLoad& c, const Span<S>& s, double rest) {
  // inextensible: the tension is the multiplier of the span's row (no force here)
  if (c.fidelity == ChainFidelity::inextensible) return {S(0.0), S(0.0), false};
  const S e = s.length - rest;
  if (c.fidelity == ChainFidelity::unilateral && !(value_of(e) > 0)) return {S(0.0), S(0.0), false};
  const S T = c.stiffness * e + c.damping * s.rate;
  if (c.fidelity == ChainFidelity::unilateral && value_of(T) < 0)
    return {S(0.0), c.stiffness * e, true};
  return {T, c.stiffness * e, true};
}

using ChainVec = Eigen::Ref<const Eigen::VectorXd>;

// Every chain's generalized force added to the body-local slots (body_applied), and its
// directional derivative along (dq0, dq1) (body_applied_derivative). Throw on a geometry that
// does not exist or a tension that is not finite, naming the chain and the time.
void add_chain_forces(const Model& m, const ChainVec& q0, const ChainVec& q1, double t,
                      double* local);
void add_chain_forces_derivative(const Model& m, const ChainVec& q0, const ChainVec& q1,
                                 const ChainVec& dq0, const ChainVec& dq1, double t,
                                 double* dlocal);
// Elastic energy of every chain's spans (potential_energy), their damping power
// (damping_power) and its derivative.
double chain_potential(const Model& m, const ChainVec& q0);
double chain_damping_power(const Model& m, const ChainVec& q0, const ChainVec& q1);
double chain_damping_power_derivative(const Model& m, const ChainVec& q0, const ChainVec& q1,
                                      const ChainVec& dq0, const ChainVec& dq1);
// The rates of the upper and lower spans' material lengths at (q0, q1), linear in q1 (the
// fidelity report takes their gradient over q1).
std::array<double, 2> chain_span_rates(const Model& m, const ChainLoad& c, const ChainVec& q0,
                                       const ChainVec& q1, double t);
// m with each inextensible chain in the span mode spans[k] (k-th inextensible chain; 0 upper,
// 1 lower, -1 slack: its row removed) and mode_fixed (src/model/inextensible_chains.cpp).
Model chain_mode_model(const Model& m, const std::vector<int>& spans);
// The positions q0 assembled (assemble(), tolerance tol) with each inextensible chain in the mode
// of its span lengths there, once the rest of the mechanism is: spans[k] of the k-th -1 (slack:
// both spans shorter than their rest lengths by more than 1e-9 of them), else 0 upper or 1 lower
// (the span at or beyond its length; src/model/inextensible_chains.cpp).
struct ChainStart {
  Eigen::VectorXd q0;
  std::vector<int> spans;
};
ChainStart chain_start(const Model& m, const Eigen::VectorXd& q0, double t,
                       const std::vector<int>& fixed, double tol);
// The tolerance of assembling q0 onto a span's row at an engagement, relative to m.scale.
double span_assembly_tolerance(const Model& m, const Eigen::VectorXd& q0);
// Sets beta0, the offsets (l = L at m.q0) and the default rest lengths (NaN: the initial L).
void init_chain(const Model& m, ChainLoad& c);

}  // namespace mo2d::detail
