// Inverse cross-check: Box2D's motors follow mo2d's exact motion; the motor efforts and joint
// reactions of every step are compared with mo2d's inverse dynamics.
//
// Which instant a Box2D step represents. Step n runs from t_n to t_n + h: v += h (g + F/m), then
// impulses make the joint velocities satisfy the motor targets and J(x_n) v = 0, then x += h v.
// The motor target is the mean rate (s(t_n + h) - s(t_n)) / h, so the positions follow the exact
// path without an O(h) drift and the velocity after step n is that of t_n + h/2. The velocities
// start at the exact state of t0 - h/2, so the impulse of step n is M (v(t_n + h/2) -
// v(t_n - h/2)) - h f(x_n, t_n): the central difference of the momentum at t_n, with the
// Jacobian and the loads of x_n, t_n. Hence the default sample_offset = 0 (compared at t_n); the
// convergence study (bench/crosscheck_study.cpp) measures the offsets 0, 1/2 and 1.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "box2d_world.hpp"
#include "crosscheck_budget.hpp"
#include "dynamics/friction.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

using crosscheck_detail::Box2DWorld;
using crosscheck_detail::JointMap;
using detail::friction_rate;

std::string num6(double v) {  // 6 significant digits, for messages
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

int label_index(const std::vector<std::string>& labels, const std::string& label) {
  for (size_t k = 0; k < labels.size(); ++k)
    if (labels[k] == label) return static_cast<int>(k);
  return -1;
}

// Per-channel error of scalar series (efforts) or of 2D vectors (reaction forces).
ChannelError channel_error(const std::string& label, const Eigen::VectorXd& time,
                           const Eigen::MatrixXd& ref, const Eigen::MatrixXd& box,
                           const std::vector<char>& excluded) {
  ChannelError e;
  e.label = label;
  double sum = 0;
  for (Eigen::Index k = 0; k < ref.rows(); ++k) {
    if (excluded[k]) continue;
    e.peak = std::fmax(e.peak, ref.row(k).norm());
    const double d = (box.row(k) - ref.row(k)).norm();
    sum += d * d;
    if (d > e.max) {
      e.max = d;
      e.max_time = time[k];
    }
  }
  const auto kept = static_cast<Eigen::Index>(std::count(excluded.begin(), excluded.end(), 0));
  const double n = static_cast<double>(std::max<Eigen::Index>(kept, 1));
  const double peak = e.peak > 0 ? e.peak : 1.0;
  e.rms = std::sqrt(sum / n) / peak;
  e.max /= peak;
  return e;
}

void judge(CrosscheckReport& r, const CrosscheckOptions& o) {
  auto check = [&](const std::vector<ChannelError>& chans, double rms_tol, double max_tol,
                   const char* what) {
    for (const ChannelError& c : chans) {
      if (c.rms > rms_tol)
        r.failures.push_back(std::string(what) + " '" + c.label + "': RMS error " +
                             std::to_string(c.rms) + " of peak > " + std::to_string(rms_tol));
      if (c.max > max_tol)
        r.failures.push_back(std::string(what) + " '" + c.label + "': max error " +
                             std::to_string(c.max) + " of peak > " + std::to_string(max_tol) +
                             " at t = " + std::to_string(c.max_time));
    }
  };
  check(r.efforts, o.effort_rms_tolerance, o.effort_max_tolerance, "effort");
  check(r.reactions, o.reaction_rms_tolerance, o.reaction_max_tolerance, "reaction");
  r.agree = r.failures.empty();
}

// Coulomb friction jumps where its joint's rate changes sign: a step whose interval holds such a
// reversal of the exact motion has no one value to compare (Box2D's motor idiom flips within
// the step, mo2d's sign(v(t_n)) at the next): it is left out of the statistics, and noted.
class ReversalWatch {
 public:
  ReversalWatch(const Model& m, const Eigen::VectorXd& q1) : m_(m), rate_(m.frictions.size()) {
    for (size_t f = 0; f < m.frictions.size(); ++f) rate_[f] = friction_rate(m.frictions[f], q1);
  }
  // The exact rates at the end of the step: whether a Coulomb friction reverses within it.
  bool step_to(const Eigen::VectorXd& q1) {
    bool reversal = false;
    for (size_t f = 0; f < m_.frictions.size(); ++f) {
      const double next = friction_rate(m_.frictions[f], q1);
      reversal = reversal || (m_.frictions[f].mu != 0 && rate_[f] * next < 0);
      rate_[f] = next;
    }
    return reversal;
  }
  void exclude(double t) { times_ += (times_.empty() ? "" : ", ") + num6(t); }
  void note(CrosscheckReport& r) const {
    if (!times_.empty())
      r.notes.push_back("a joint with Coulomb friction reverses within the steps at t = " + times_ +
                        " s: the friction jumps there, those steps are not compared");
  }

 private:
  const Model& m_;
  std::vector<double> rate_;
  std::string times_;
};

// Box2D starts `settle` steps before t0 (see CrosscheckOptions::settle_steps): velocities of
// t_start - h/2 (into q1_start), positions of t_start (left in sim). Returns settle (0 when the
// motion cannot be solved before t0, noted in r).
int start_state(const Model& simulated, InverseData& sim, double t0, double h,
                const CrosscheckOptions& check, CrosscheckReport& r, Eigen::VectorXd& q1_start) {
  int settle = std::max(check.settle_steps, 0);
  for (;;) {
    const double t_start = t0 - settle * h;
    try {
      sim.has_previous = false;
      inverse_dynamics_sample(simulated, sim, t_start - h / 2);
      q1_start = sim.q1;
      sim.has_previous = false;
      inverse_dynamics_sample(simulated, sim, t_start);
      return settle;
    } catch (const Error& e) {
      if (settle == 0) throw;
      r.notes.push_back("the motion cannot be solved before t0 (" + std::string(e.what()) +
                        "): Box2D starts at t0, its first " + std::to_string(check.skip_steps) +
                        " steps are not compared");
      settle = 0;
    }
  }
}

// Effort labels: the reference's inputs, matched to the simulated inputs by label (their columns
// in the reference; r.effort_labels filled).
std::vector<int> effort_columns(const Model& reference, const Model& simulated,
                                CrosscheckReport& r) {
  const std::vector<std::string> ref_inputs = reference.input_labels();
  std::vector<int> effort_col;
  for (const Input& in : simulated.inputs) {
    r.effort_labels.push_back(in.label);
    const int c = label_index(ref_inputs, in.label);
    if (c < 0)
      throw Error("Box2D cross-check: reference has no input '" + in.label + "'", in.label);
    effort_col.push_back(c);
  }
  return effort_col;
}

// The Fx column in the reference of every Box2D joint (r.reaction_labels filled).
std::vector<int> reaction_columns(const Model& reference, const std::vector<JointMap>& joints,
                                  CrosscheckReport& r) {
  const std::vector<std::string> ref_reactions = reference.reaction_labels();
  std::vector<int> reaction_col;
  for (const JointMap& j : joints) {
    const int c = label_index(ref_reactions, j.name + ".Fx");
    if (c < 0)
      throw Error("Box2D cross-check: reference has no reaction '" + j.name + ".Fx'", j.name);
    reaction_col.push_back(c);
    r.reaction_labels.push_back(j.name + ".Fx");
    r.reaction_labels.push_back(j.name + ".Fy");
  }
  return reaction_col;
}

// The channels' errors (steps marked in `excluded` left out) and the verdict.
void summarize(CrosscheckReport& r, const std::vector<JointMap>& joints,
               const std::vector<char>& excluded, const CrosscheckOptions& check) {
  for (Eigen::Index k = 0; k < r.mo2d_efforts.cols(); ++k) {
    r.efforts.push_back(channel_error(r.effort_labels[k], r.time, r.mo2d_efforts.col(k),
                                      r.box2d_efforts.col(k), excluded));
    r.effort_rms = std::fmax(r.effort_rms, r.efforts.back().rms);
    r.effort_max = std::fmax(r.effort_max, r.efforts.back().max);
  }
  for (size_t k = 0; k < joints.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(2 * k);
    r.reactions.push_back(channel_error(joints[k].name, r.time, r.mo2d_reactions.middleCols(c, 2),
                                        r.box2d_reactions.middleCols(c, 2), excluded));
    r.reaction_rms = std::fmax(r.reaction_rms, r.reactions.back().rms);
    r.reaction_max = std::fmax(r.reaction_max, r.reactions.back().max);
  }
  judge(r, check);
}

}  // namespace

CrosscheckReport crosscheck_inverse(const Model& reference_in, const Model& simulated_in,
                                    std::span<const Prescribed> motion,
                                    const InverseOptions& options, const CrosscheckOptions& check) {
  using namespace crosscheck_detail;
  if (!(check.step > 0) || check.velocity_iterations < 1 || check.position_iterations < 0)
    throw Error("Box2D cross-check: the step must be > 0 and the velocity iterations >= 1",
                simulated_in.name);
  const auto start = std::chrono::steady_clock::now();
  CrosscheckReport r;
  r.mechanism = simulated_in.name;
  r.step = check.step;
  r.velocity_iterations = check.velocity_iterations;
  r.position_iterations = check.position_iterations;
  r.sample_offset = check.sample_offset;
  r.feedback_time = check.feedback_time;
  const Model reference = with_inertia_floor(reference_in, check.zero_inertia_fraction, r.notes);
  const Model simulated = with_inertia_floor(simulated_in, check.zero_inertia_fraction, r.notes);
  if (simulated.n_inputs() != simulated.dof)
    throw Error("Box2D cross-check of '" + simulated.name +
                    "': " + std::to_string(simulated.n_inputs()) + " inputs for " +
                    std::to_string(simulated.dof) +
                    " degrees of freedom (the motors must fix "
                    "the motion)",
                simulated.name);

  const double h = check.step, t0 = options.t0;
  const std::string what = "Box2D cross-check of '" + simulated.name + "'";
  const double steps_wanted = std::floor((options.t1 - t0) / h + 1e-9);
  check_box2d_steps(what, simulated.name, steps_wanted + std::max(check.settle_steps, 0), h, check);
  const int steps = static_cast<int>(steps_wanted);
  InverseData sim(simulated, motion, options), ref(reference, motion, options);

  Eigen::VectorXd q1_start;
  const int settle = start_state(simulated, sim, t0, h, check, r, q1_start);
  const int skip = settle > 0 ? 0 : std::max(check.skip_steps, 0);
  if (steps - skip < check.min_compared_steps)
    throw Error("Box2D cross-check of '" + simulated.name +
                    "': " + std::to_string(std::max(steps - skip, 0)) + " steps of " + num6(h) +
                    " s over [" + num6(t0) + ", " + num6(options.t1) +
                    "] s would be compared, fewer than " +
                    std::to_string(check.min_compared_steps) + ": use a smaller step",
                simulated.name);
  Box2DWorld w = build_box2d_world(simulated, sim.q0, q1_start, check, true);

  std::vector<const JointMap*> motors;
  for (const Input& in : simulated.inputs)
    for (const JointMap& j : w.joints)
      if (j.motor && j.name == in.joint) motors.push_back(&j);
  if (motors.size() != simulated.inputs.size())
    throw Error("Box2D cross-check of '" + simulated.name + "': an input has no motor",
                simulated.name);

  const std::vector<int> effort_col = effort_columns(reference, simulated, r);
  const std::vector<int> reaction_col = reaction_columns(reference, w.joints, r);

  const int n_motor = static_cast<int>(motors.size());
  const int n_joint = static_cast<int>(w.joints.size());
  const int rows = steps - skip;
  check_result_memory(what, simulated.name, rows, 1 + 2 * (n_motor + 2 * n_joint), check);
  r.time.resize(rows);
  r.mo2d_efforts.resize(rows, n_motor);
  r.box2d_efforts.resize(rows, n_motor);
  r.mo2d_reactions.resize(rows, 2 * n_joint);
  r.box2d_reactions.resize(rows, 2 * n_joint);

  // Exact joint coordinates, unwrapped from t0 (Box2D's joint angles start at 0).
  // A slider coordinate is absolute in both engines; an angle is unwrapped from t0.
  std::vector<double> s_now(n_motor), s_exact(n_motor, 0.0);
  for (int k = 0; k < n_motor; ++k) {
    s_now[k] = joint_coordinate(simulated, w, *motors[k], sim.q0);
    if (motors[k]->linear_motor) s_exact[k] = s_now[k];
  }
  std::vector<char> excluded(rows, 0);
  ReversalWatch reversals(simulated, sim.q1);
  const double inv_dt = 1.0 / h;
  detail::RunBudget budget(box2d_budget(what, simulated.name, t0, options.t1, check));
  for (int n = -settle; n < steps; ++n) {
    const double t = t0 + n * h;
    budget.check(t, n + settle, h);
    inverse_dynamics_sample(simulated, sim, t + h);
    for (int k = 0; k < n_motor; ++k) {
      const double s_next = joint_coordinate(simulated, w, *motors[k], sim.q0);
      const double ds = motors[k]->linear_motor ? s_next - s_now[k] : wrap_angle(s_next - s_now[k]);
      const double moved = std::fabs(ds) / (motors[k]->linear_motor ? simulated.scale : 1.0);
      if (check.max_motion_per_step > 0 && moved > check.max_motion_per_step)
        throw Error("Box2D cross-check of '" + simulated.name + "': the step " + num6(h) +
                        " s is too coarse for this motion: joint '" + motors[k]->name + "' moves " +
                        num6(moved) +
                        (motors[k]->linear_motor ? " of the mechanism's size" : " rad") +
                        " in the step at t = " + num6(t) + " s, more than the " +
                        num6(check.max_motion_per_step) +
                        " the tolerances hold for (docs/crosscheck.md): use a step <= " +
                        num6(h * check.max_motion_per_step / moved) + " s",
                    motors[k]->name, t);
      double speed = ds / h;
      if (check.feedback_time > 0)
        speed += (s_exact[k] - box2d_joint_coordinate(*motors[k])) / check.feedback_time;
      set_motor_speed(*motors[k], speed);
      s_now[k] = s_next;
      s_exact[k] += ds;
    }
    const bool reversal = reversals.step_to(sim.q1);
    apply_loads(simulated, w, t, h);
    w.world->Step(static_cast<float>(h), check.velocity_iterations, check.position_iterations);
    for (int k = 0; k < n_motor; ++k) {
      const double err = box2d_joint_coordinate(*motors[k]) - s_exact[k];
      r.tracking_error = std::fmax(r.tracking_error, std::fabs(err));
    }
    if (n < skip) continue;
    const int row = n - skip;
    if (reversal) {
      excluded[row] = 1;
      reversals.exclude(t);
    }
    const double tc = t + check.sample_offset * h;
    inverse_dynamics_sample(reference, ref, tc);
    r.time[row] = tc;
    for (int k = 0; k < n_motor; ++k) {
      r.mo2d_efforts(row, k) = ref.u[effort_col[k]];
      r.box2d_efforts(row, k) = motor_effort(*motors[k], inv_dt);
    }
    for (int k = 0; k < n_joint; ++k) {
      const Vec2 F = reaction_force(w.joints[k], inv_dt);
      r.mo2d_reactions(row, 2 * k) = ref.reactions[reaction_col[k]];
      r.mo2d_reactions(row, 2 * k + 1) = ref.reactions[reaction_col[k] + 1];
      r.box2d_reactions(row, 2 * k) = F.x();
      r.box2d_reactions(row, 2 * k + 1) = F.y();
    }
  }
  reversals.note(r);
  r.steps = steps;
  r.settle_steps = settle;
  r.compared_steps = rows;
  summarize(r, w.joints, excluded, check);
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

CrosscheckReport crosscheck_inverse(const System& system, std::span<const Prescribed> motion,
                                    const InverseOptions& options, const CrosscheckOptions& check) {
  const Model reference = build_model(system);
  const Model simulated = build_model(system, {.reduction = Reduction::none});
  return crosscheck_inverse(reference, simulated, motion, options, check);
}

}  // namespace mo2d
