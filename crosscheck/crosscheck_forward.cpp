// Forward cross-check: mo2d (CVODE BDF, tight tolerances) and Box2D integrate the same passive
// motion from the same state; centres of mass and angles are compared at instants on Box2D steps.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "box2d_branch.hpp"
#include "box2d_world.hpp"
#include "crosscheck_budget.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

std::string num4(double v) {  // 4 significant digits, for messages
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

// The fastest rotation per Box2D step h along mo2d's trajectory: the largest |omega| h of a
// rotating body (rad). (Translation is not limited: a body falling freely is integrated alike.)
struct Motion {
  double per_step = 0, t = 0;
  std::string what;
};
Motion fastest_motion(const Model& m, const Trajectory& tr, double h) {
  Motion out;
  for (Eigen::Index s = 0; s < tr.q1.rows(); ++s)
    for (const Body& b : m.bodies) {
      if (b.omega.var >= 0) {
        const double turn = std::fabs(tr.q1(s, b.omega.var)) * h;
        if (turn > out.per_step) out = {turn, tr.time[s], "body '" + b.name + "'"};
      }
    }
  return out;
}

}  // namespace

ForwardCrosscheck crosscheck_forward(const Model& model, const State& initial, double t1,
                                     const CrosscheckOptions& check, int samples,
                                     const EffortLaws& efforts) {
  return crosscheck_forward(model, model, initial, t1, check, samples, efforts);
}

ForwardCrosscheck crosscheck_forward(const Model& reference_in, const Model& model_in,
                                     const State& initial, double t1,
                                     const CrosscheckOptions& check, int samples,
                                     const EffortLaws& efforts) {
  using namespace crosscheck_detail;
  std::vector<std::string> notes, reference_notes;
  const Model model = with_inertia_floor(model_in, check.zero_inertia_fraction, notes);
  const Model reference =
      with_inertia_floor(reference_in, check.zero_inertia_fraction, reference_notes);
  if (reference.n0 != model.n0 || reference.bodies.size() != model.bodies.size())
    throw Error(
        "Box2D forward cross-check: the reference model must have the simulated model's "
        "variables",
        model.name);
  if (!(check.step > 0) || samples < 2 || !(t1 > initial.t))
    throw Error("Box2D forward cross-check: need step > 0, samples >= 2 and t1 > t0", model.name);
  ForwardCrosscheck r;
  r.notes = notes;
  r.mechanism = model.name;
  const std::string what = "Box2D forward cross-check of '" + model.name + "'";
  check_result_memory(what, model.name, samples, 3, check);
  // the translation first: a refusal names the element before any run
  Box2DWorld w = build_box2d_world(model, initial.q0, initial.q1, check, false);
  w.regularized_friction = true;  // as mo2d integrates joint friction
  for (size_t k = 0; k < efforts.size() && k < model.inputs.size(); ++k)
    w.efforts.push_back(efforts[k] ? compile_law(model, efforts[k],
                                                 "effort '" + model.inputs[k].label + "'",
                                                 model.inputs[k].label)
                                   : CompiledLaw{});
  ForwardOptions fo;
  fo.t0 = initial.t;
  fo.samples = samples;
  fo.rtol = 1e-10;
  fo.atol = 1e-12;
  // a reference run takes ~1e3 steps per simulated second; a wrong model (the mutation check's
  // acceleration-bias flip) made CVODE grind through millions: fail instead
  fo.max_steps =
      static_cast<int>(check.max_steps > 0 ? std::min<long>(200'000, check.max_steps) : 200'000);
  fo.max_seconds = check.max_seconds;
  fo.max_memory = check.max_memory;
  fo.efforts = efforts;
  double h = check.step;
  int stride = 1;
  Trajectory ref;
  for (int halvings = 0;; ++halvings) {
    const double stride_wanted =
        std::fmax(1, std::floor((t1 - initial.t) / h / (samples - 1) + 1e-9));
    check_box2d_steps(what, model.name, stride_wanted * (samples - 1), h, check);
    stride = static_cast<int>(stride_wanted);
    r.steps = stride * (samples - 1);
    fo.t1 = initial.t + r.steps * h;
    ref = forward_dynamics(reference, initial, fo);
    const Motion fastest = fastest_motion(reference, ref, h);
    if (!(check.max_motion_per_step > 0) || fastest.per_step <= check.max_motion_per_step) break;
    const double wanted = h * check.max_motion_per_step / fastest.per_step;
    if (!check.refine_step || halvings >= 8)
      throw Error(
          what + ": the step " + num4(h) + " s is too coarse for this motion: " + fastest.what +
              " turns " + num4(fastest.per_step) + " rad in a step at t = " + num4(fastest.t) +
              " s, more than the " + num4(check.max_motion_per_step) +
              " the tolerances hold for (docs/crosscheck.md): use a step <= " + num4(wanted) + " s",
          model.name, fastest.t);
    const double coarse = h;
    while (h > wanted) h /= 2;
    r.notes.push_back("Box2D step refined from " + num4(coarse) + " to " + num4(h) +
                      " s: " + fastest.what + " turned " + num4(fastest.per_step) +
                      " rad per step at t = " + num4(fastest.t) + " s");
  }
  r.step = h;
  detail::RunBudget budget(box2d_budget(what, model.name, initial.t, t1, check));

  BranchWatch branch(model, w, initial.q0);
  r.time = ref.time;
  r.position_error = Eigen::VectorXd::Zero(samples);
  r.angle_error = Eigen::VectorXd::Zero(samples);
  r.energy_difference = Eigen::VectorXd::Zero(samples);
  r.mo2d_energy_error = energy_balance_error(ref);
  r.kinetic_peak = ref.kinetic.size() ? ref.kinetic.maxCoeff() : 0.0;
  for (int s = 0; s < samples; ++s) {
    if (s > 0)
      for (int n = 0; n < stride; ++n) {
        const int step = (s - 1) * stride + n;
        budget.check(initial.t + step * h, step, h);
        apply_loads(model, w, initial.t + step * h, h);
        w.world->Step(static_cast<float>(h), check.velocity_iterations, check.position_iterations);
      }
    const Eigen::VectorXd q0 = ref.q0.row(s).transpose();
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      const b2Vec2 c = w.bodies[b].body->GetPosition();
      const double dp = (Vec2(c.x, c.y) - com_position(model.bodies[b], q0)).norm();
      r.position_error[s] = std::fmax(r.position_error[s], dp);
      if (w.bodies[b].oriented) {
        const double da = wrap_angle(w.bodies[b].body->GetAngle() -
                                     box2d_angle(model, w, static_cast<int>(b), q0));
        r.angle_error[s] = std::fmax(r.angle_error[s], std::fabs(da));
      }
    }
    branch.sample(model, w, q0, ref.time[s]);
    read_box2d_state(model, w, 0.0);  // h = 0: no coordinate integrated twice
    r.energy_difference[s] = kinetic_energy(model, w.q1) + potential_energy(model, w.q0) -
                             ref.kinetic[s] - ref.potential[s];
  }
  r.branch_switch = branch.report(model);
  r.max_position_error = r.position_error.maxCoeff();
  r.max_angle_error = r.angle_error.maxCoeff();
  r.final_position_error = r.position_error[samples - 1];
  r.final_angle_error = r.angle_error[samples - 1];
  r.relative_position_error = r.max_position_error / model.scale;
  return r;
}

std::string box2d_cause(const ForwardCrosscheck& r, double position_tolerance,
                        double angle_tolerance) {
  if (!r.branch_switch.empty()) return r.branch_switch;
  const double scale = r.position_error.size() && r.relative_position_error > 0
                           ? r.max_position_error / r.relative_position_error
                           : 1.0;
  for (Eigen::Index s = 0; s < r.time.size(); ++s) {
    if (r.position_error[s] <= position_tolerance * scale && r.angle_error[s] <= angle_tolerance)
      continue;
    const double dE = std::fabs(r.energy_difference[s]);
    if (!(dE > 10 * r.mo2d_energy_error && dE > 1e-4 * r.kinetic_peak)) return "";
    char b[640];
    std::snprintf(b, sizeof b,
                  "at t = %.4g s, where the error first exceeds the tolerance, Box2D's "
                  "mechanical energy (mo2d's energy functions of Box2D's state) differs from "
                  "mo2d's by %.3g J (%.2g of the kinetic energy peak, %.3g J), while mo2d's "
                  "energy balance holds to %.3g J: Box2D's first-order float32 step has drifted "
                  "(a smaller --step shrinks the drift in proportion if so), and the motion "
                  "amplifies it",
                  r.time[s], r.energy_difference[s], dE / r.kinetic_peak, r.kinetic_peak,
                  r.mo2d_energy_error);
    return b;
  }
  return "";
}

}  // namespace mo2d
