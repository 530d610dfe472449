// The quasi-steady-state model of a spring (mo2d/quasi_steady.hpp): the equilibrium length under
// the tension (Newton on a tension law) and its settling at every projection of a forward run.
#include "mo2d/quasi_steady.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "dynamics/derivatives.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward_data.hpp"
#include "run/format.hpp"

namespace mo2d {
namespace {

using detail::fmt;

// Which of the element's own quantities a law argument is: its length (1), extension or angle
// from rest (2), rate (3), or another quantity of the state (0). Labels as compile_law resolved
// them (spring_quantity; a torsional spring's "angle" and "rate").
int own_quantity(const std::string& label, const std::string& name, bool torsional) {
  for (const auto& [suffix, kind] :
       {std::pair{"length", 1}, std::pair{"extension", 2}, std::pair{"rate", 3}}) {
    if (torsional && kind != 3) continue;
    if (label == suffix || label == name + "." + suffix) return kind;
  }
  if (torsional && (label == "angle" || label == name + ".angle")) return 2;
  return 0;
}

// The law of a quasi-steady element for Newton: its compiled law, name, rest value (a length, or
// 0 for an angle from rest) and what it is (for messages).
struct LawOf {
  const CompiledLaw& law;
  const std::string& name;
  double rest;
  bool torsional;
};

[[noreturn]] void no_length(const LawOf& e, double T, double t, const std::string& why) {
  throw Error(std::string(e.torsional ? "torsional spring '" : "spring '") + e.name +
                  "' (reduce: quasi_steady): no equilibrium " +
                  (e.torsional ? "angle for the torque " + fmt(T) + " N m"
                               : "length for the tension " + fmt(T) + " N") +
                  " at t = " + fmt(t) + " s (" + why +
                  "); keep it as a spring (no reduce) or use reduce: constraint",
              e.name, t);
}

// Newton on law(l, rate 0) - T = 0 from l (the law's derivative by its Jet).
double law_root(const Model& m, const LawOf& e, double T, double l, const Eigen::VectorXd& q0,
                const Eigen::VectorXd& q1, double t) {
  const CompiledLaw& law = e.law;
  const size_t n = law.args.size();
  std::array<Jet, kMaxLawArgs> x;
  std::array<int, kMaxLawArgs> own{};
  for (size_t k = 0; k < n; ++k) {
    own[k] = own_quantity(law.labels[k], e.name, e.torsional);
    if (own[k] == 0) x[k] = Jet(quantity_value(m, law.args[k], q0, q1));
  }
  const double tol = 1e-13 * std::max({std::abs(l), e.rest, e.torsional ? 1.0 : 0.0});
  for (int it = 0; it < 50; ++it) {
    for (size_t k = 0; k < n; ++k) {
      if (own[k] == 1) x[k] = Jet::variable(l);
      if (own[k] == 2) x[k] = Jet::variable(l - e.rest);
      if (own[k] == 3) x[k] = Jet(0.0);
    }
    const Jet f = detail::call_law(
        law, std::span<const Jet>(x.data(), n), t,
        e.torsional ? "torque law of torsional spring" : "tension law of spring", e.name);
    if (!std::isfinite(f.v) || !std::isfinite(f.d)) no_length(e, T, t, "the law is not finite");
    if (f.d == 0) no_length(e, T, t, "its derivative is 0 at " + fmt(l));
    const double step = (f.v - T) / f.d;
    l -= step;
    if (std::abs(step) <= tol) return l;
  }
  no_length(e, T, t, "Newton on the law did not converge");
}

HeldLength& cell(const std::shared_ptr<double>& p) {
  return *reinterpret_cast<HeldLength*>(p.get());
}

// One held cell of a model: a quasi-steady spring, torsional spring or chain span, and whether
// its row is in the model (a chain's taut span; the other span's cell waits at rest).
struct Held {
  HeldLength* h;
  double rest;  // the cell's value at rest
  const ReducedSpring* spring = nullptr;
  const ReducedTorsional* torsional = nullptr;
  const ChainLoad* chain = nullptr;
  int span = -1;
  bool active = true;
};

std::vector<Held> held_cells(const Model& m) {
  std::vector<Held> out;
  for (const ReducedSpring& s : m.reduced_springs)
    if (s.held_length)
      out.push_back({.h = &held_of(s), .rest = s.spring.rest_length, .spring = &s});
  for (const ReducedTorsional& s : m.reduced_torsional)
    if (s.held_angle) out.push_back({.h = &cell(s.held_angle), .rest = 0, .torsional = &s});
  for (const ChainLoad& c : m.chains)
    for (int span : {0, 1})
      if (c.held[span])
        out.push_back({.h = &cell(c.held[span]),
                       .rest = span == 0 ? c.rest_upper : c.rest_lower,
                       .chain = &c,
                       .span = span,
                       .active = c.active_span == span && c.constraint >= 0});
  return out;
}

std::string held_name(const Held& e) {
  if (e.spring) return e.spring->spring.name;
  if (e.torsional) return e.torsional->spring.name;
  return e.chain->name + (e.span == 0 ? ".upper" : ".lower");
}

void reset_cell(HeldLength& h, double rest) {
  h.length = rest;
  h.rate = h.t0 = 0;
}

// The reaction column of a chain's taut span ("name.upper.tension" or "name.lower.tension").
int span_reaction(const Model& m, const ChainLoad& c, int span) {
  const std::string label = c.name + (span == 0 ? ".upper.tension" : ".lower.tension");
  for (int j = 0; j < m.n_reactions(); ++j)
    if (m.reactions[j].label == label) return j;
  throw Error("quasi-steady chain '" + c.name + "': no reaction " + label, c.name);
}

// The held value of e under its row's reaction at the state (a length, or an angle from rest).
double equilibrium(const Model& m, const Held& e, const Eigen::VectorXd& reactions,
                   const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double t) {
  if (e.spring) return quasi_steady_length(m, *e.spring, reactions[e.spring->reaction], q0, q1, t);
  if (e.torsional) {
    const TorsionalLoad& l = e.torsional->spring;
    const double tau = reactions[e.torsional->reaction];  // on body 2
    if (!l.torque) return -tau / l.stiffness;             // tau = -k a: a = -tau / k
    return law_root(m, {l.torque, l.name, 0.0, true}, tau, e.h->at(t), q0, q1, t);
  }
  const ChainLoad& c = *e.chain;  // T = k (l - rest) at zero rate: l = rest + T / k
  return e.rest + reactions[span_reaction(m, c, e.span)] / c.stiffness;
}

// Set by a run of several legs (inextensible chains' span switching) on its thread while it holds
// the cells: the legs' own runs neither claim nor reset them.
thread_local bool t_legs_held = false;

}  // namespace

bool has_quasi_steady(const Model& m) {
  return !held_cells(m).empty();
}

void reset_quasi_steady(const Model& m) {
  for (const Held& e : held_cells(m)) reset_cell(*e.h, e.rest);
}

double quasi_steady_length(const Model& m, const ReducedSpring& s, double T,
                           const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double t) {
  if (!s.spring.tension) return s.spring.rest_length + T / s.spring.stiffness;  // l_0 + T / k
  const double from = s.held_length ? held_of(s).at(t) : s.spring.rest_length;
  return law_root(m, {s.spring.tension, s.spring.name, s.spring.rest_length, false}, T, from, q0,
                  q1, t);
}

namespace detail {

QuasiSteadyRun::QuasiSteadyRun(const Model& m, bool legs) : m_(m) {
  if (t_legs_held) return;  // a leg of a run that holds the cells (legs_ false: nothing to undo)
  for (const Held& e : held_cells(m)) {
    if (e.h->in_use.exchange(true)) {
      for (HeldLength* other : held_) other->in_use = false;
      throw Error("forward dynamics of '" + m.name + "': the quasi-steady element '" +
                      held_name(e) +
                      "' is held by another forward run on this model (or a copy of it): the "
                      "held lengths are the model's, one run at a time; build a model per thread",
                  held_name(e));
    }
    held_.push_back(e.h);
  }
  owns_ = true;
  reset_quasi_steady(m);
  if (legs) legs_ = t_legs_held = true;
}

QuasiSteadyRun::~QuasiSteadyRun() {
  if (!owns_) return;
  if (legs_) t_legs_held = false;
  reset_quasi_steady(m_);
  for (HeldLength* h : held_) h->in_use = false;
}

HeldValues save_held(const Model& m) {
  HeldValues v;
  for (const Held& e : held_cells(m)) {
    const HeldLength& h = *e.h;
    v.push_back({h.length, h.rate, h.t0});
  }
  return v;
}

void restore_held(const Model& m, const HeldValues& v) {
  size_t i = 0;
  for (const Held& e : held_cells(m)) {
    if (i >= v.size()) break;
    HeldLength& h = *e.h;
    const std::array<double, 3>& x = v[i++];
    h.length = x[0], h.rate = x[1], h.t0 = x[2];
  }
}

void hold_still(const Model& m, double t) {
  for (const Held& e : held_cells(m)) {
    HeldLength& h = *e.h;
    h.length = h.at(t);
    h.rate = 0;
    h.t0 = t;
  }
}

double release_span(const ChainLoad& c, int span, double rest) {
  HeldLength& h = held_of(c, span);
  const double stretch = h.length - rest;
  h.length = rest;
  return stretch;
}

namespace {

// One pass: the reactions at the state, each active held value moved to its equilibrium at t
// (its rate kept); returns the largest move.
double settle_pass(ForwardData& d, double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  const Model& m = d.m;
  d.accelerations(t, q0, q1, false);
  d.compute_reactions(t, q0, q1);
  double moved = 0;
  for (const Held& e : held_cells(m)) {
    if (!e.active) continue;
    const double L = equilibrium(m, e, d.reactions, q0, q1, t);
    moved = std::max(moved, std::abs(L - e.h->at(t)));
    e.h->length = L;
    e.h->t0 = t;
  }
  return moved;
}

// The equilibrium values of the active cells at the state (t, q0, q1) (one evaluation of the
// accelerations and reactions), into L (the cells' order).
void equilibria(ForwardData& d, double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                std::vector<double>& L) {
  d.accelerations(t, q0, q1, false);
  d.compute_reactions(t, q0, q1);
  L.clear();
  for (const Held& e : held_cells(d.m))
    L.push_back(e.active ? equilibrium(d.m, e, d.reactions, q0, q1, t) : e.rest);
}

// The time step of the one-sided differences of rates_along_motion (s): round-off of the
// equilibrium (~1e-13 of T / k) over it stays far below the rate, its truncation (eps L'' / 2)
// far below what the next settling corrects.
constexpr double kRateStep = 1e-6;

// The settled values at t become the start of the next interval: L(t') = L_n + Ldot_n (t' - t_n)
// with Ldot_n the derivative of the equilibrium value along the motion, d/dt L_eq(t, q0, q1)
// (Ldot = Tdot / k for a linear spring): one-sided differences over (t, q0, q1) -+ eps (q0', a),
// q0' = q1.head(n0), a the accelerations at the state (d.a, of the last settle_pass). Their minmod
// (the smaller when of one sign, else 0): at a jump of the loads within eps of t (a torque step,
// an event located next to it) one side sees the jump and is not used. Not the secant of the
// settled values over the last step: the velocities are projected on the rate, and T depends on
// the velocities (bearing damping, reflected along the span), so the secant carried the jump of
// T at the last projection divided by the step, a loop gain c / (k h) that made the half-bike's
// scenario 2 diverge once the step fell below c / k. A chain's idle span waits at rest (its
// history forgotten: it engages from its rest length).
void rates_along_motion(ForwardData& d, double t, const Eigen::VectorXd& q0,
                        const Eigen::VectorXd& q1) {
  const Model& m = d.m;
  const Eigen::VectorXd a = d.a;
  std::vector<double> L, side[2];
  for (const Held& e : held_cells(m)) L.push_back(e.h->length);
  for (int s : {0, 1}) {
    const double eps = s == 0 ? kRateStep : -kRateStep;
    const Eigen::VectorXd p0 = q0 + eps * q1.head(m.n0), p1 = q1 + eps * a;
    equilibria(d, t + eps, p0, p1, side[s]);
  }
  size_t i = 0;
  for (const Held& e : held_cells(m)) {
    HeldLength& h = *e.h;
    double fwd = (side[0][i] - L[i]) / kRateStep, bwd = (L[i] - side[1][i]) / kRateStep;
    ++i;
    if (!std::isfinite(bwd)) bwd = fwd;  // a load not finite before the start (sqrt(t) at t0 = 0)
    if (!std::isfinite(fwd)) fwd = bwd;
    if (!e.active) {
      reset_cell(h, e.rest);
      continue;
    }
    h.rate = !(fwd * bwd > 0) ? 0.0 : std::abs(fwd) < std::abs(bwd) ? fwd : bwd;
    h.t0 = t;
  }
}

}  // namespace

void settle_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1,
                         double tol_pos, double tol_vel) {
  const Model& m = d.m;
  // the rates first (at the state projected with the values held so far, their equilibrium
  // values there), then the values settled with the velocities on the new rates: the state ends
  // where its held values are their equilibrium (T depends on the velocities)
  d.project_held(t, q0, q1, tol_pos, tol_vel);
  settle_pass(d, t, q0, q1);
  rates_along_motion(d, t, q0, q1);
  for (int pass = 0; pass < 30; ++pass) {
    d.project_held(t, q0, q1, tol_pos, tol_vel);
    if (settle_pass(d, t, q0, q1) <= tol_pos) return;
  }
  std::ostringstream w;
  w << "quasi-steady elements of '" << m.name << "': their lengths do not settle at t = " << fmt(t)
    << " s (the tension changes with the length as fast as the elements' own law: they are not "
       "fast against their loads; keep them as springs)";
  throw Error(w.str(), m.name, t);
}

void start_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1) {
  const Model& m = d.m;
  std::string names;
  for (const Held& e : held_cells(m))
    if (e.span <= 0) names += (names.empty() ? "'" : ", '") + held_name(e) + "'";
  // cvode_bdf projects too, but its step history does not follow the held lengths' updates at
  // its projections (measured: on the mass-spring-mass it fails at the first step)
  if (!d.projects() || d.o.integrator == Integrator::cvode_bdf)
    throw Error("forward dynamics of '" + m.name + "': the quasi-steady elements " + names +
                    " (reduce or fidelity quasi_steady) need an explicit integrator that projects "
                    "(dopri5, rk4, erk6, erk8), not " +
                    to_string(d.o.integrator),
                m.name);
  if (!t_legs_held) reset_quasi_steady(m);  // a leg goes on from the lengths the last one held
  const double tol = 1e-13 * m.scale;
  d.project(t, q0, q1, tol, tol);
}

}  // namespace detail
}  // namespace mo2d
