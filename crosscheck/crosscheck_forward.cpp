// Forward cross-check: mo2d (CVODE BDF, tight tolerances) and Box2D integrate the same passive
// motion from the same state; centres of mass and angles are compared at instants on Box2D steps.
#include <algorithm>
#include <cmath>

#include "box2d_world.hpp"
#include "crosscheck_budget.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

ForwardCrosscheck crosscheck_forward(const Model& model_in, const State& initial, double t1,
                                     const CrosscheckOptions& check, int samples) {
  using namespace crosscheck_detail;
  std::vector<std::string> notes;
  const Model model = with_inertia_floor(model_in, check.zero_inertia_fraction, notes);
  if (!(check.step > 0) || samples < 2 || !(t1 > initial.t))
    throw Error("Box2D forward cross-check: need step > 0, samples >= 2 and t1 > t0", model.name);
  ForwardCrosscheck r;
  r.mechanism = model.name;
  r.step = check.step;
  const double h = check.step;
  const std::string what = "Box2D forward cross-check of '" + model.name + "'";
  const double stride_wanted =
      std::fmax(1, std::floor((t1 - initial.t) / h / (samples - 1) + 1e-9));
  check_box2d_steps(what, model.name, stride_wanted * (samples - 1), h, check);
  check_result_memory(what, model.name, samples, 3, check);
  const int stride = static_cast<int>(stride_wanted);
  r.steps = stride * (samples - 1);
  detail::RunBudget budget(box2d_budget(what, model.name, initial.t, t1, check));

  ForwardOptions fo;
  fo.t0 = initial.t;
  fo.t1 = initial.t + r.steps * h;
  fo.samples = samples;
  fo.rtol = 1e-10;
  fo.atol = 1e-12;
  // a reference run takes ~1e3 steps per simulated second; a wrong model (the mutation check's
  // acceleration-bias flip) made CVODE grind through millions: fail instead
  fo.max_steps =
      static_cast<int>(check.max_steps > 0 ? std::min<long>(200'000, check.max_steps) : 200'000);
  fo.max_seconds = check.max_seconds;
  fo.max_memory = check.max_memory;
  const Trajectory ref = forward_dynamics(model, initial, fo);

  Box2DWorld w = build_box2d_world(model, initial.q0, initial.q1, check, false);
  r.time = ref.time;
  r.position_error = Eigen::VectorXd::Zero(samples);
  r.angle_error = Eigen::VectorXd::Zero(samples);
  for (int s = 0; s < samples; ++s) {
    if (s > 0)
      for (int n = 0; n < stride; ++n) {
        const int step = (s - 1) * stride + n;
        budget.check(initial.t + step * h, step, h);
        apply_loads(model, w, initial.t + step * h);
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
  }
  r.max_position_error = r.position_error.maxCoeff();
  r.max_angle_error = r.angle_error.maxCoeff();
  r.final_position_error = r.position_error[samples - 1];
  r.final_angle_error = r.angle_error[samples - 1];
  r.relative_position_error = r.max_position_error / model.scale;
  return r;
}

}  // namespace mo2d
