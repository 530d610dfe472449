// Convergence study of the Box2D cross-check (docs/crosscheck.md): for each example mechanism, the
// inverse cross-check's effort and reaction errors against Box2D's step and iterations, the
// compared instant (offset), and the forward cross-check's divergence against the step.
// A plain program (each row is one run): mo2d_crosscheck_study [quick]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mo2d/crosscheck.hpp"
#include "mo2d/mechanisms.hpp"

namespace {

using namespace mo2d;

struct Case {
  std::string name;
  mechanisms::Example ex;
  double t1;  // horizon of the study (s)
  double inertia_fraction;
};

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"whitworth", mechanisms::whitworth(), 4.0, 0});
  c.push_back({"rrr3", mechanisms::rrr3(), 4.0, 0});
  c.push_back({"slider_crank", mechanisms::slider_crank(), 1.0, 0});
  c.push_back({"fourbar", mechanisms::fourbar(), 1.0, 0});
  c.push_back({"pendulum", mechanisms::pendulum(), 2.0, 1.0 / 12});
  return c;
}

void row(const Case& c, const Model& ref, const Model& sim, double h, int vi, int pi, double offset,
         double feedback) {
  InverseOptions run = c.ex.run;
  run.t1 = run.t0 + c.t1;
  CrosscheckOptions o;
  o.step = h;
  o.velocity_iterations = vi;
  o.position_iterations = pi;
  o.sample_offset = offset;
  o.feedback_time = feedback;
  o.zero_inertia_fraction = c.inertia_fraction;
  o.max_motion_per_step = 0;  // the study goes to coarse steps on purpose
  const CrosscheckReport r = crosscheck_inverse(ref, sim, c.ex.motion, run, o);
  std::printf("| %s | 1/%.0f | %d/%d | %.1f | %g | %.2e | %.2e | %.2e | %.2e | %.1e | %.2f |\n",
              c.name.c_str(), 1 / h, vi, pi, offset, feedback, r.effort_rms, r.effort_max,
              r.reaction_rms, r.reaction_max, r.tracking_error, r.cpu_seconds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "quick") == 0;
  const double steps[] = {240, 500, 1000, 2000, 4000};
  std::printf("## Inverse: error relative to peak (worst channel) against the step\n\n");
  std::printf(
      "| mechanism | h | vel/pos it | offset | feedback s | effort rms | effort max | "
      "reaction rms | reaction max | tracking | CPU s "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases()) {
    const Model ref = build_model(c.ex.system);
    const Model sim = build_model(c.ex.system, {.reduction = Reduction::none});
    for (double f : steps) {
      row(c, ref, sim, 1 / f, 50, 20, 0.0, 0.0);
      if (quick) continue;
      row(c, ref, sim, 1 / f, 8, 3, 0.0, 0.0);
      row(c, ref, sim, 1 / f, 50, 20, 0.0, 0.05);
    }
    if (quick) continue;
    for (double off : {0.5, 1.0}) row(c, ref, sim, 1 / 1000.0, 50, 20, off, 0.0);
    for (double fb : {0.01, 0.2}) row(c, ref, sim, 1 / 2000.0, 50, 20, 0.0, fb);
  }

  std::printf("\n## Forward: passive motion from the same state, max centre-of-mass error\n\n");
  std::printf(
      "| mechanism | horizon s | h | max position error m | relative | max angle error rad "
      "|\n|---|---|---|---|---|---|\n");
  struct F {
    std::string name;
    System s;
    InitialConditions ic;
    double t1;
  };
  std::vector<F> fw;
  {
    mechanisms::PendulumParams p;
    p.theta0 = 0;
    fw.push_back(
        {"pendulum (I = mL^2/12)", mechanisms::pendulum(p).system, {{}, {{"link.w", 0.0}}}, 1.0});
    fw.push_back({"fourbar", mechanisms::fourbar().system, {{}, {{"crank.w", 0.0}}}, 1.0});
    fw.push_back({"fourbar", mechanisms::fourbar().system, {{}, {{"crank.w", 0.0}}}, 0.25});
    fw.push_back({"double_fourbar", mechanisms::double_fourbar(), {{}, {{"crank0.w", -1.0}}}, 1.0});
  }
  for (F& f : fw) {
    Model m = build_model(f.s, {.reduction = Reduction::none});
    for (Body& b : m.bodies)
      if (b.has_omega && b.inertia == 0) b.inertia = b.mass * b.l01 * b.l01 / 12;
    const State s0 = consistent_state(m, f.ic);
    for (double hs : steps) {
      CrosscheckOptions o;
      o.step = 1 / hs;
      o.max_motion_per_step = 0;  // coarse steps on purpose (the forward check refuses them too)
      const ForwardCrosscheck r = crosscheck_forward(m, s0, f.t1, o, 21);
      std::printf("| %s | %g | 1/%.0f | %.2e | %.2e | %.2e |\n", f.name.c_str(), f.t1, hs,
                  r.max_position_error, r.relative_position_error, r.max_angle_error);
      std::fflush(stdout);
    }
  }
  return 0;
}
