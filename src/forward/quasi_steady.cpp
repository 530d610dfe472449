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

// Which of the spring's own quantities a law argument is: its length (1), extension (2), rate
// (3), or another quantity of the state (0). Labels as compile_law resolved them (spring_quantity).
int own_quantity(const std::string& label, const std::string& name) {
  for (const auto& [suffix, kind] :
       {std::pair{"length", 1}, std::pair{"extension", 2}, std::pair{"rate", 3}})
    if (label == suffix || label == name + "." + suffix) return kind;
  return 0;
}

[[noreturn]] void no_length(const ReducedSpring& s, double T, double t, const std::string& why) {
  throw Error("spring '" + s.spring.name + "' (reduce: quasi_steady): no equilibrium length for " +
                  "the tension " + fmt(T) + " N at t = " + fmt(t) + " s (" + why +
                  "); keep it as a spring (no reduce) or use reduce: constraint",
              s.spring.name, t);
}

// Newton on T_law(l, rate 0) - T = 0 from l (the law's derivative by its Jet).
double law_length(const Model& m, const ReducedSpring& s, double T, double l,
                  const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double t) {
  const CompiledLaw& law = s.spring.tension;
  const size_t n = law.args.size();
  std::array<Jet, kMaxLawArgs> x;
  std::array<int, kMaxLawArgs> own{};
  for (size_t k = 0; k < n; ++k) {
    own[k] = own_quantity(law.labels[k], s.spring.name);
    if (own[k] == 0) x[k] = Jet(quantity_value(m, law.args[k], q0, q1));
  }
  const double tol = 1e-13 * std::max(std::abs(l), s.spring.rest_length);
  for (int it = 0; it < 50; ++it) {
    for (size_t k = 0; k < n; ++k) {
      if (own[k] == 1) x[k] = Jet::variable(l);
      if (own[k] == 2) x[k] = Jet::variable(l - s.spring.rest_length);
      if (own[k] == 3) x[k] = Jet(0.0);
    }
    const Jet f = detail::call_law(law, std::span<const Jet>(x.data(), n), t,
                                   "tension law of spring", s.spring.name);
    if (!std::isfinite(f.v) || !std::isfinite(f.d)) no_length(s, T, t, "the law is not finite");
    if (f.d == 0) no_length(s, T, t, "d tension / d length = 0 at l = " + fmt(l) + " m");
    const double step = (f.v - T) / f.d;
    l -= step;
    if (std::abs(step) <= tol) return l;
  }
  no_length(s, T, t, "Newton on the tension law did not converge");
}

}  // namespace

bool has_quasi_steady(const Model& m) {
  for (const ReducedSpring& s : m.reduced_springs)
    if (s.held_length) return true;
  return false;
}

void reset_quasi_steady(const Model& m) {
  for (const ReducedSpring& s : m.reduced_springs) {
    if (!s.held_length) continue;
    HeldLength& h = held_of(s);
    h.length = s.spring.rest_length;
    h.rate = h.t0 = h.prev_length = 0;
    h.prev_t = NAN;
  }
}

double quasi_steady_length(const Model& m, const ReducedSpring& s, double T,
                           const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double t) {
  if (!s.spring.tension) return s.spring.rest_length + T / s.spring.stiffness;  // l_0 + T / k
  const double from = s.held_length ? held_of(s).at(t) : s.spring.rest_length;
  return law_length(m, s, T, from, q0, q1, t);
}

namespace detail {

QuasiSteadyRun::QuasiSteadyRun(const Model& m) : m_(m) {
  for (const ReducedSpring& s : m.reduced_springs) {
    if (!s.held_length) continue;
    HeldLength& h = held_of(s);
    if (h.in_use.exchange(true)) {
      for (HeldLength* other : held_) other->in_use = false;
      throw Error("forward dynamics of '" + m.name + "': the quasi-steady spring '" +
                      s.spring.name +
                      "' is held by another forward run on this model (or a copy of it): the "
                      "held lengths are the model's, one run at a time; build a model per thread",
                  s.spring.name);
    }
    held_.push_back(&h);
  }
}

QuasiSteadyRun::~QuasiSteadyRun() {
  reset_quasi_steady(m_);
  for (HeldLength* h : held_) h->in_use = false;
}

namespace {

// One pass: T at the state, each held length moved to L_law(T) at t (its rate kept); returns
// the largest move.
double settle_pass(ForwardData& d, double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  const Model& m = d.m;
  d.accelerations(t, q0, q1, false);
  d.compute_reactions(t, q0, q1);
  double moved = 0;
  for (const ReducedSpring& s : m.reduced_springs) {
    if (!s.held_length) continue;
    HeldLength& h = held_of(s);
    const double L = quasi_steady_length(m, s, d.reactions[s.reaction], q0, q1, t);
    moved = std::max(moved, std::abs(L - h.at(t)));
    h.length = L;
    h.t0 = t;
  }
  return moved;
}

// The settled lengths at t become the start of the next interval: L(t') = L_n + Ldot_n (t' - t_n)
// with Ldot_n the rate since the last settling (0 at the first).
void extrapolate(const Model& m, double t) {
  for (const ReducedSpring& s : m.reduced_springs) {
    if (!s.held_length) continue;
    HeldLength& h = held_of(s);
    h.rate = std::isfinite(h.prev_t) && t != h.prev_t ? (h.length - h.prev_length) / (t - h.prev_t)
                                                      : 0.0;
    h.prev_length = h.length;
    h.prev_t = t;
  }
}

}  // namespace

void settle_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1,
                         double tol_pos, double tol_vel) {
  const Model& m = d.m;
  d.project_held(t, q0, q1, tol_pos, tol_vel);
  for (int pass = 0; pass < 30; ++pass) {
    if (settle_pass(d, t, q0, q1) <= tol_pos) {
      extrapolate(m, t);
      d.project_held(t, q0, q1, tol_pos, tol_vel);  // the velocity rows' new rate
      return;
    }
    d.project_held(t, q0, q1, tol_pos, tol_vel);
  }
  std::ostringstream w;
  w << "quasi-steady springs of '" << m.name << "': their lengths do not settle at t = " << fmt(t)
    << " s (the tension changes with the length as fast as the springs' own law: they are not "
       "fast against their loads; keep them as springs)";
  throw Error(w.str(), m.name, t);
}

void start_quasi_steady(ForwardData& d, double t, Eigen::VectorXd& q0, Eigen::VectorXd& q1) {
  const Model& m = d.m;
  std::string names;
  for (const ReducedSpring& s : m.reduced_springs)
    if (s.held_length) names += (names.empty() ? "'" : ", '") + s.spring.name + "'";
  // cvode_bdf projects too, but its step history does not follow the held lengths' updates at
  // its projections (measured: on the mass-spring-mass it fails at the first step)
  if (!d.projects() || d.o.integrator == Integrator::cvode_bdf)
    throw Error("forward dynamics of '" + m.name + "': the quasi-steady springs " + names +
                    " (reduce: quasi_steady) need an explicit integrator that projects (dopri5, "
                    "rk4, erk6, erk8), not " +
                    to_string(d.o.integrator),
                m.name);
  reset_quasi_steady(m);
  const double tol = 1e-13 * m.scale;
  d.project(t, q0, q1, tol, tol);
}

}  // namespace detail
}  // namespace mo2d
