// Forward dynamics of inextensible chains: the span switching (docs/reduction.md, "The
// inextensible chain"; Gamba 2009, §2.5, the upper- and lower-span models). A chain can only
// pull, so each chain is in one of three modes: upper span taut (its row l_u = rest_u, tension
// T_u = lambda >= 0), lower span taut, or slack (no row: both spans free, l <= rest). The run is
// a sequence of segments, each integrated by forward_dynamics on the model of its mode
// (chain_mode_model) with a stop condition (ForwardOptions::stop_when, located by the
// integrator's root finding) that is positive inside the mode:
//
//   taut span s:  T_s + tol_T        (the chain would push: it goes slack)
//                 rest_o - l_o + tol_l   (the other span reaches its length too: both taut)
//   slack:        rest_s - l_s + tol_l   for both spans (a span reaches its length: engagement)
//
// tol_T = max(1e-9, rtol) T_max (T_max the largest tension seen, at least 1e-3 N) and tol_l =
// max(1e-9 rest, atol): the run's accuracy, no tighter (a tension or length is known only to the
// integration error; with 1e-9 thresholds the chain four-bar at BDF rtol 1e-4, atol 1e-6 chattered
// past 10000 switches, its located tensions off 0 by 6e-4 N of 64 N, its lengths by 1.2e-9 m of
// 0.3 m). A switch is located where T_s = -tol_T (a time error tol_T / |dT/dt|), an engagement
// tol_l past the length (the assembly puts it back: a jump of at most atol). At an event the
// new mode is chosen deterministically (choose_span): a span whose tension reaches 0 hands over to
// the other span if that one is at its length and then pulls (on fixed centres with the default
// rest lengths both spans are always at their length: a direct switch), else the chain goes
// slack; a slack span reaching its length engages by a perfectly inelastic impact (the velocities
// projected on the new row in the mass metric: [M A^T; A 0] [q1+; mu] = [M q1; b], the chain's
// impulse mu of its row, the kinetic energy lost added to the dissipated energy) and stays taut
// if its tension is then >= -tol_T. The warnings (src/forward/chain_log.hpp) name the chain, the
// span and the time of every slack interval and impulse; direct handovers (energy lost within
// rtol: none on fixed centres) are counted, a closing line per chain. Both spans taut at once,
// an initial span longer than its rest length, and switches that chatter (more than kChatter at
// one instant) are errors naming the chain and the time. The recorded samples are the output
// grid's, one at a switch's instant the new mode's (the loads there are the new ones: the old
// mode's tension past a step of them pushes); the energy terms carry over from leg to leg. A
// quasi-steady chain (ChainLoad::held) switches alike, its taut span at rest + T / k
// (mo2d/quasi_steady.hpp): the run holds its quasi-steady cells across its legs (QuasiSteadyRun),
// reset at its end; a span whose tension reaches 0 is put at its rest length (release_span).
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "dynamics/chain.hpp"
#include "forward/chain_log.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/quasi_steady.hpp"
#include "output/trajectory_labels.hpp"
#include "run/time_grid.hpp"

namespace mo2d::detail {
namespace {

constexpr double kSpanTol = 1e-9;    // floor of the thresholds, relative to rest and T_max
constexpr int kChatter = 8;          // switches at one instant before the run is refused
constexpr int kMaxSwitches = 10000;  // switches in a run before it is refused
const char* const kSpanName[2] = {"upper", "lower"};

const auto& num = chain_log_number;  // 10 significant digits

struct Lengths {
  double gap[2];  // rest - l of each span (>= 0: not longer than its rest length)
};

Lengths lengths(const Model& m, const ChainLoad& c, const VectorXd& q0, const VectorXd& q1,
                double t) {
  const ChainValue v = chain_value(m, c, q0, q1, t);
  return {{c.rest_upper - v.upper_length, c.rest_lower - v.lower_length}};
}

double rest(const ChainLoad& c, int s) {
  return s == 0 ? c.rest_upper : c.rest_lower;
}

// A model of one mode with its event workspace and the reaction columns of the tensions.
struct Mode {
  Model model;
  ForwardData data;
  std::vector<int> tension;  // per inextensible chain: reaction column of its taut span (-1)
  Mode(Model mm, const ForwardOptions& o) : model(std::move(mm)), data(model, o) {
    for (const ChainLoad& c : model.chains) {
      if (c.fidelity != ChainFidelity::inextensible) continue;
      int col = -1;
      if (c.active_span >= 0) {
        const std::string label = c.name + "." + kSpanName[c.active_span] + ".tension";
        for (int j = 0; j < model.n_reactions(); ++j)
          if (model.reactions[j].label == label) col = j;
      }
      tension.push_back(col);
    }
  }
  // The tensions of the taut spans at a state (the least-squares multipliers of the run).
  const VectorXd& reactions(double t, const VectorXd& q0, const VectorXd& q1) {
    data.accelerations(t, q0, q1, false);
    data.compute_reactions(t, q0, q1);
    return data.reactions;
  }
};

class Switcher {
 public:
  Switcher(const Model& m, const ForwardOptions& o) : m_(m), o_(o) {
    for (int i = 0; i < static_cast<int>(m.chains.size()); ++i)
      if (m.chains[i].fidelity == ChainFidelity::inextensible) chains_.push_back(i);
    spans_.assign(chains_.size(), 0);
    log_ = ChainLog(chains_.size());
    watch_.assign(chains_.size(), false);
    inner_ = o;
    rel_tension_ = std::max(kSpanTol, o.rtol);
    inner_.accuracy = 0;
    inner_.stop_when = nullptr;
  }
  Trajectory run(const State& initial);

 private:
  const Model& m_;
  const ForwardOptions& o_;
  ForwardOptions inner_;
  std::vector<int> chains_, spans_;
  // per chain, taut: whether the other span had slack at the segment's start (its reaching its
  // length is then an event); else both are at their length (fixed centres, the default rest
  // lengths) and its staying there is checked at the recorded samples (check_both_taut)
  std::vector<bool> watch_;
  double t_ref_ = 0;        // largest tension seen (N)
  double rel_tension_ = 0;  // tol_T / T_max: max(1e-9, rtol)
  Trajectory out_;
  ChainLog log_;
  int filled_ = 0;
  double off_[kEnergyTerms] = {0, 0, 0, 0};
  int same_instant_ = 0, switches_ = 0;
  // a switch since the last leg: a sample written at its instant holds the old mode's values
  // (the loads there are the new ones: a taut span's tension < 0) and is written again
  bool switched_ = false;
  double last_switch_ = -1e300, slack_since_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();

  double tension_ref() const { return std::max(t_ref_, 1e-3); }
  double tension_tol() const { return rel_tension_ * tension_ref(); }
  double span_tol(const ChainLoad& c, int s) const {  // tol_l
    return std::max(kSpanTol * rest(c, s), o_.atol);
  }
  // the conditions, dimensionless: positive inside the mode
  double tension_cond(double T) const { return (T + tension_tol()) / tension_ref(); }
  double length_cond(const ChainLoad& c, const Lengths& L, int s) const {
    return (L.gap[s] + span_tol(c, s)) / rest(c, s);
  }
  double grid(int k) const { return sample_time(o_.t0, o_.t1, o_.samples, k); }
  const ChainLoad& chain(size_t k) const { return m_.chains[chains_[k]]; }
  void note(size_t k, const std::string& line) {
    if (log_.listed(k)) out_.stats.warnings.push_back(line);
  }
  std::vector<int> modes_with(size_t k, int s) const {
    std::vector<int> v = spans_;
    v[k] = s;
    return v;
  }
  double event(Mode& md, double t, const VectorXd& q0, const VectorXd& q1);
  Trajectory leg(Mode& md, const State& s, double t1, int samples);
  void start(State& s);
  void switch_at(State& s);
  bool engage(State& s, size_t k, int span, const char* why, const std::string& zero = "");
  double impact(State& s, const std::vector<int>& modes, size_t k);
  double tension_in(const std::vector<int>& modes, size_t k, const State& s);
  void start_segment(const State& s);
  void rewrite_last(const State& s);
  void check_both_taut(const Model& mm, const Trajectory& r);
  [[noreturn]] void both_taut(size_t k, double t) const {
    const int sp = spans_[k];
    fail(k, t,
         std::string("both spans taut (the ") + kSpanName[1 - sp] +
             " span reaches its rest length while the " + kSpanName[sp] +
             " span pulls: the centre distance would be locked); fidelity " +
             chain_fidelity_name(chain(k)) +
             " holds one span at a time: use fidelity unilateral or a longer rest length");
  }
  [[noreturn]] void fail(size_t k, double t, const std::string& what) const {
    throw Error("chain '" + chain(k).name + "' (" + chain_fidelity_name(chain(k)) + "): " + what +
                    " at t = " + fmt(t) + " s",
                chain(k).name, t);
  }
};

double Switcher::event(Mode& md, double t, const VectorXd& q0, const VectorXd& q1) {
  double g = 1e300;
  bool need_reactions = false;
  for (size_t k = 0; k < chains_.size(); ++k) need_reactions |= spans_[k] >= 0;
  const VectorXd* r = need_reactions ? &md.reactions(t, q0, q1) : nullptr;
  for (size_t k = 0; k < chains_.size(); ++k) {
    const ChainLoad& c = chain(k);
    const Lengths L = lengths(md.model, c, q0, q1, t);
    const int s = spans_[k];
    if (s >= 0) {
      const double T = (*r)[md.tension[k]];
      t_ref_ = std::max(t_ref_, std::abs(T));
      g = std::min(g, tension_cond(T));
      if (watch_[k]) g = std::min(g, length_cond(c, L, 1 - s));
    } else {
      g = std::min({g, length_cond(c, L, 0), length_cond(c, L, 1)});
    }
  }
  return g;
}

// Which taut chains have slack on their other span at a segment's start.
void Switcher::start_segment(const State& s) {
  for (size_t k = 0; k < chains_.size(); ++k) {
    const int sp = spans_[k];
    watch_[k] = sp >= 0 && lengths(m_, chain(k), s.q0, s.q1, s.t).gap[1 - sp] >
                               10 * span_tol(chain(k), 1 - sp);
  }
}

// A taut chain whose other span was at its length too must keep it there (no stretch beyond
// 1e-6 of its rest length) at every recorded sample of the leg.
void Switcher::check_both_taut(const Model& mm, const Trajectory& r) {
  for (size_t k = 0; k < chains_.size(); ++k) {
    const int sp = spans_[k];
    if (sp < 0 || watch_[k]) continue;
    // a quasi-steady span past a jump of its tension through 0 is at rest + T / k, T < 0 (the
    // other span longer by -T / k) until released
    const int tension =
        chain(k).held[sp] ? r.reaction(chain(k).name + "." + kSpanName[sp] + ".tension") : -1;
    for (Eigen::Index i = 0; i < r.time.size(); ++i) {
      if (tension >= 0 && r.reactions(i, tension) < 0) continue;
      const Lengths L =
          lengths(mm, chain(k), r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
      if (L.gap[1 - sp] < -1e-6 * rest(chain(k), 1 - sp)) both_taut(k, r.time[i]);
    }
  }
}

Trajectory Switcher::leg(Mode& md, const State& s, double t1, int samples) {
  ForwardOptions o = inner_;
  // the run's budgets, not each leg's: what the legs before used is gone
  const double used_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const long steps_left = static_cast<long>(inner_.max_steps) - out_.stats.steps;
  if (steps_left < 1 || used_seconds >= inner_.max_seconds)
    throw Error("forward dynamics of '" + m_.name + "': the run's " +
                    (steps_left < 1
                         ? "step budget (max_steps " + std::to_string(inner_.max_steps)
                         : "wall-time budget (max_seconds " + std::to_string(inner_.max_seconds)) +
                    ") ran out at t = " + std::to_string(s.t) + " s after " +
                    std::to_string(switches_) + " chain span switches",
                steps_left < 1 ? "max_steps" : "max_seconds");
  o.max_steps = static_cast<int>(steps_left);
  o.max_seconds = inner_.max_seconds - used_seconds;
  o.t0 = s.t;
  o.t1 = t1;
  o.samples = samples;
  o.stop_when = [this, &md](double t, const VectorXd& q0, const VectorXd& q1) {
    return event(md, t, q0, q1);
  };
  return forward_run(md.model, s, o);
}

// The tension of chain k's span in `modes` at s (its mode's least-squares multiplier).
double Switcher::tension_in(const std::vector<int>& modes, size_t k, const State& s) {
  Mode md(chain_mode_model(m_, modes), inner_);
  return md.reactions(s.t, s.q0, s.q1)[md.tension[k]];
}

// A perfectly inelastic engagement: s's positions put on the rows of `modes`, its velocities
// projected on them in the mass metric; returns chain k's impulse (N s) and adds the kinetic
// energy lost to the dissipated energy.
double Switcher::impact(State& s, const std::vector<int>& modes, size_t k) {
  const Model mm = chain_mode_model(m_, modes);
  s.q0 = assemble(mm, s.q0, s.t, {}, span_assembly_tolerance(mm, s.q0));
  const int n = mm.n1, rows = mm.m1;
  MatrixXd K = MatrixXd::Zero(n + rows, n + rows);
  const MatrixXd M = mass_matrix(mm);
  MatrixXd A(rows, n);
  VectorXd b(rows), rhs(n + rows);
  velocity_jacobian(mm, s.q0, s.t, A, b);
  K.topLeftCorner(n, n) = M;
  K.topRightCorner(n, rows) = A.transpose();
  K.bottomLeftCorner(rows, n) = A;
  rhs << M * s.q1, b;
  const VectorXd x = K.fullPivLu().solve(rhs);
  const double before = kinetic_energy(mm, s.q1);
  s.q1 = x.head(n);
  off_[kDissipated] += before - kinetic_energy(mm, s.q1);
  return x[n + mm.constraints[mm.chains[chains_[k]].constraint].row1];
}

// Chain k engages span `span` at s (an impact); true if it then pulls (else it stays slack).
// `zero`: the line of the other span's tension reaching 0 (a handover), left out with the
// engagement's line (the handover counted) if the span pulls and the energy lost is within rtol.
bool Switcher::engage(State& s, size_t k, int span, const char* why, const std::string& zero) {
  const std::vector<int> modes = modes_with(k, span);
  const double e0 = off_[kDissipated], ke = kinetic_energy(m_, s.q1);
  const double P = impact(s, modes, k);
  const double T = tension_in(modes, k, s);
  const double lost = off_[kDissipated] - e0;
  if (!zero.empty() && T >= -tension_tol() && std::abs(lost) <= rel_tension_ * ke + 1e-12) {
    log_.handover(k, 1 - span, s.t);
    spans_[k] = span;
    return true;
  }
  if (!zero.empty()) note(k, zero);
  note(k, "chain '" + chain(k).name + "': the " + kSpanName[span] + " span " + why +
              " at t = " + num(s.t) + " s: perfectly inelastic engagement, impulse " + num(P) +
              " N s, kinetic energy lost " + num(lost) + " J; tension then " + num(T) + " N" +
              (T >= -tension_tol() ? "" : " (< 0: it does not hold, the chain stays slack)"));
  if (T < -tension_tol()) return false;
  spans_[k] = span;
  return true;
}

void Switcher::start(State& s) {
  for (size_t k = 0; k < chains_.size(); ++k) {
    const ChainLoad& c = chain(k);
    const Lengths L = lengths(m_, c, s.q0, s.q1, s.t);
    for (int sp : {0, 1})
      if (L.gap[sp] < -span_tol(c, sp))
        fail(k, s.t,
             std::string("the ") + kSpanName[sp] + " span is longer than its rest length by " +
                 num(-L.gap[sp]) + " m in the initial state");
    spans_[k] = -1;
    if (L.gap[0] <= span_tol(c, 0) && tension_in(modes_with(k, 0), k, s) >= -tension_tol()) {
      spans_[k] = 0;
    } else if (L.gap[1] <= span_tol(c, 1)) {
      State t = s;
      const std::vector<int> modes = modes_with(k, 1);
      impact(t, modes, k);
      if (tension_in(modes, k, t) >= -tension_tol()) spans_[k] = 1, s = t;
    }
    if (spans_[k] < 0) slack_since_ = s.t;
    note(k, "chain '" + c.name + "': " +
                (spans_[k] < 0 ? std::string("slack")
                               : std::string(kSpanName[spans_[k]]) + " span taut") +
                " at t = " + num(s.t) + " s (start)");
  }
}

// The event at the end of a leg: which chain, and its new mode.
void Switcher::switch_at(State& s) {
  Mode md(chain_mode_model(m_, spans_), inner_);
  const VectorXd r = md.reactions(s.t, s.q0, s.q1);
  if (has_quasi_steady(m_)) hold_still(m_, s.t);  // the held values jump with the mode
  size_t which = 0;
  double worst = 1e300;
  int cause = 0;  // 0 the taut span's tension, 1 the other span's length, 2 a slack span's length
  for (size_t k = 0; k < chains_.size(); ++k) {
    const ChainLoad& c = chain(k);
    const Lengths L = lengths(m_, c, s.q0, s.q1, s.t);
    const int sp = spans_[k];
    auto consider = [&](double g, int why) {
      if (g < worst) worst = g, which = k, cause = why;
    };
    if (sp >= 0) {
      consider(tension_cond(r[md.tension[k]]), 0);
      if (watch_[k]) consider(length_cond(c, L, 1 - sp), 1);
    } else {
      consider(std::min(length_cond(c, L, 0), length_cond(c, L, 1)), 2);
    }
  }
  const ChainLoad& c = chain(which);
  const int sp = spans_[which];
  switched_ = true;
  if (s.t - last_switch_ <= 1e-12 * std::max(1.0, std::abs(s.t))) {
    if (++same_instant_ > kChatter)
      fail(which, s.t,
           "the span switching chatters (" + std::to_string(same_instant_) +
               " switches at one instant): the mechanism cannot be handled by fidelity " +
               chain_fidelity_name(c) + "; use fidelity unilateral");
  } else {
    same_instant_ = 0;
  }
  last_switch_ = s.t;
  if (++switches_ > kMaxSwitches)
    fail(which, s.t,
         "more than " + std::to_string(kMaxSwitches) +
             " span switches: the switching chatters; use fidelity unilateral");
  if (cause == 1) both_taut(which, s.t);
  if (cause == 0) {
    const std::string zero = "chain '" + c.name + "': the " + kSpanName[sp] +
                             " span's tension reaches 0 at t = " + num(s.t) + " s";
    if (c.held[sp]) {  // quasi-steady: at rest + T / k, T < 0 past a jump of the loads
      const double stretch = release_span(c, sp, rest(c, sp)), e0 = off_[kDissipated];
      const double P = impact(s, spans_, which);  // onto the row at rest, like an engagement
      if (std::abs(stretch) > span_tol(c, sp))    // else the tension reached 0 at rest: no release
        note(which, "chain '" + c.name + "' (quasi_steady): the " + kSpanName[sp] +
                        " span released from " + num(stretch) +
                        " m beyond its rest length (tension " + num(r[md.tension[which]]) +
                        " N) to it at t = " + num(s.t) + " s: impulse " + num(P) +
                        " N s, kinetic energy lost " + num(off_[kDissipated] - e0) + " J" +
                        (stretch < 0 ? short_span_note(stretch) : std::string()));
    }
    spans_[which] = -1;
    const Lengths L = lengths(m_, c, s.q0, s.q1, s.t);
    const bool near = L.gap[1 - sp] <= 10 * span_tol(c, 1 - sp);
    if (near && engage(s, which, 1 - sp, "takes over", zero)) return;
    if (!near) note(which, zero);
    note(which, "chain '" + c.name + "': slack from t = " + num(s.t) + " s");
    slack_since_ = s.t;
    return;
  }
  const Lengths L = lengths(m_, c, s.q0, s.q1, s.t);
  const int span = L.gap[0] <= L.gap[1] ? 0 : 1;
  note(which,
       "chain '" + c.name + "': slack interval " + num(slack_since_) + " to " + num(s.t) + " s");
  engage(s, which, span, "reaches its rest length");
}

// A switch at the last output time (no leg follows): its sample again, in the new mode.
void Switcher::rewrite_last(const State& s) {
  Mode md(chain_mode_model(m_, spans_), inner_);
  const VectorXd& r = md.reactions(s.t, s.q0, s.q1);
  const Eigen::Index k = o_.samples - 1;
  const std::vector<std::string> labels = md.model.reaction_labels();
  out_.q0.row(k) = s.q0.transpose();
  out_.q1.row(k) = s.q1.transpose();
  out_.a1.row(k) = md.data.a.transpose();
  out_.efforts.row(k) = md.data.u.transpose();
  for (Eigen::Index j = 0; j < out_.reactions.cols(); ++j) {
    const auto at = std::find(labels.begin(), labels.end(), out_.reaction_labels[j]);
    out_.reactions(k, j) = at == labels.end() ? 0.0 : r[at - labels.begin()];
  }
  out_.kinetic[k] = kinetic_energy(m_, s.q1);
  out_.dissipated[k] = off_[kDissipated];
}

Trajectory Switcher::run(const State& initial) {
  const int N = o_.samples;
  out_ = switching_trajectory(m_, N);
  State s = initial;
  s.t = o_.t0;
  start(s);
  const double h = (o_.t1 - o_.t0) / (N - 1);
  while (filled_ < N) {
    Mode md(chain_mode_model(m_, spans_), inner_);
    start_segment(s);
    if (!(event(md, s.t, s.q0, s.q1) > 0)) {  // the mode does not hold from its start
      switch_at(s);
      continue;
    }
    // a leg to the next output time, or over the rest of the grid from an output time
    auto near = [&](int k) {
      return k >= 0 && std::abs(s.t - grid(k)) <=
                           std::max(1e-9 * h, 1e3 * kTimeResolution * std::max(1.0, std::abs(s.t)));
    };
    Trajectory r;
    if (near(filled_)) {
      s.t = grid(filled_);
      r = leg(md, s, o_.t1, N - filled_);
    } else if (near(filled_ - 1)) {
      s.t = grid(filled_ - 1);
      // a switch at this output time: its sample again, in the new mode (the old mode's tension
      // there is the one past a step of the loads: the half-bike's -27.8 N at its brake step)
      if (switched_) --filled_;
      r = leg(md, s, o_.t1, N - filled_ + (switched_ ? 0 : 1));
    } else {
      r = leg(md, s, grid(filled_), 2);
    }
    check_both_taut(md.model, r);
    append_leg(out_, filled_, r, o_, off_);
    switched_ = false;
    const Eigen::Index e = r.time.size() - 1;
    s.t = r.time[e];
    s.q0 = r.q0.row(e).transpose();
    s.q1 = r.q1.row(e).transpose();
    if (r.stats.stopped_by_event) switch_at(s);
  }
  if (switched_) rewrite_last(s);
  std::vector<std::string> names;
  for (size_t k = 0; k < chains_.size(); ++k) names.push_back(chain(k).name);
  for (const std::string& w : log_.summary(names)) out_.stats.warnings.push_back(w);
  return std::move(out_);
}

}  // namespace

bool switches_chains(const Model& m) {
  return std::any_of(m.chains.begin(), m.chains.end(), [](const ChainLoad& c) {
    return c.fidelity == ChainFidelity::inextensible && !c.mode_fixed;
  });
}

Trajectory forward_chain_switching(const Model& m, const State& initial, const ForwardOptions& o) {
  for (const ChainLoad& c : m.chains)
    if (c.fidelity == ChainFidelity::inextensible &&
        (o.integrator == Integrator::cvode_adams || o.integrator == Integrator::baumgarte))
      throw Error("chain '" + c.name + "' (" + chain_fidelity_name(c) + "): the integrator " +
                      to_string(o.integrator) +
                      " does not project on the constraints, and the span's length must be held "
                      "there: use " +
                      (c.held[0] ? "" : "cvode_bdf, ") + "dopri5, erk6, erk8 or rk4",
                  c.name);
  if (o.stop_when)
    throw Error("forward dynamics of '" + m.name +
                    "': a stop condition (stop_when) with inextensible or quasi_steady "
                    "chains is not supported (the span switching uses it)",
                m.name);
  // quasi-steady elements: their held lengths carry over the legs, reset when the run ends
  const QuasiSteadyRun held(m, true);
  return Switcher(m, o).run(initial);
}

}  // namespace mo2d::detail
