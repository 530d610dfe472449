// Forward reactions to the digits of the state (issue 30, item 3): at a state that inverse dynamics
// solved exactly (positions by Newton to rounding, velocities and accelerations by one LU), the
// forward workspace under the same efforts gives the same accelerations and reactions, in every
// formulation and on both linear-algebra paths, to 12 digits of the largest reaction. Inverse
// dynamics computes its reactions another way (the transpose of its square K = [A; E] solved by
// LU), so this is a second formulation checking the first.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

struct Variant {
  Formulation formulation;
  LinearAlgebra linear_algebra;
  const char* name;
};

constexpr Variant kVariants[] = {
    {Formulation::augmented_lagrangian, LinearAlgebra::dense, "augmented_lagrangian dense"},
    {Formulation::augmented_lagrangian, LinearAlgebra::sparse, "augmented_lagrangian sparse"},
    {Formulation::lagrange, LinearAlgebra::dense, "lagrange dense"},
    {Formulation::null_space, LinearAlgebra::dense, "null_space dense"},
};

// The largest difference of the forward reactions from the inverse ones at `samples` samples spread
// over the scene's inverse run, relative to the largest |reaction| of each sample; also the largest
// relative difference of the accelerations (reported).
double worst_reaction_error(const std::string& scene_file, const Variant& v, int samples,
                            double* worst_a) {
  const Scene s = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/" + scene_file);
  const Model m = build_scene_model(s);
  const Trajectory inv = inverse_dynamics(m, s.motion, inverse_options(s));
  ForwardOptions o;
  o.integrator = Integrator::rk4;  // the sparse path runs with the explicit integrators
  o.formulation = v.formulation;
  o.linear_algebra = v.linear_algebra;
  o.efforts = efforts_from_inverse(m, s.motion, inverse_options(s));
  ForwardData d(m, o);
  double worst = 0;
  *worst_a = 0;
  const int N = static_cast<int>(inv.time.size());
  for (int j = 0; j < samples; ++j) {
    const int k = j * (N - 1) / (samples - 1);
    const double t = inv.time[k];
    const VectorXd q0 = inv.q0.row(k).transpose(), q1 = inv.q1.row(k).transpose();
    d.accelerations(t, q0, q1, false);
    const VectorXd a_inv = inv.a1.row(k).transpose();
    *worst_a = std::max(*worst_a, (d.a - a_inv).lpNorm<Eigen::Infinity>() /
                                      std::max(1.0, a_inv.lpNorm<Eigen::Infinity>()));
    d.compute_reactions(t, q0, q1);
    const VectorXd r_inv = inv.reactions.row(k).transpose();
    const double scale = std::max(1e-300, r_inv.lpNorm<Eigen::Infinity>());
    worst = std::max(worst, (d.reactions - r_inv).lpNorm<Eigen::Infinity>() / scale);
  }
  return worst;
}

// Before (the regularized normal equations alone): 2.3e-12 (Whitworth) and 1.5e-12 (Watt six-bar)
// in every formulation, 2e-13 to 4e-13 on the others; now below 6e-14 (Whitworth) and 1e-15.
TEST(ReactionDigits, ForwardReactionsEqualInverseDynamicsAtExactStates) {
  const char* scenes[] = {"fourbar.yaml",
                          "slider_crank.yaml",
                          "whitworth.yaml",
                          "rrr3.yaml",
                          "crank_press.yaml",
                          "watt_sixbar_lengths.yaml",
                          "slider_crank_friction.yaml"};
  for (const char* scene : scenes)
    for (const Variant& v : kVariants) {
      double da = 0;
      const double dr = worst_reaction_error(scene, v, 7, &da);
      std::printf("%-20s %-28s reactions %.2g accelerations %.2g\n", scene, v.name, dr, da);
      EXPECT_LE(dr, 1e-12) << scene << ", " << v.name;
    }
}

// The cost of the reactions of one recorded sample (ForwardData::compute_reactions), printed in
// ns per call (5 rounds of 4000 calls): docs/performance.md, "Issue 30, item 3" (run with
// --gtest_also_run_disabled_tests --gtest_filter='ReactionDigits.DISABLED_*'; MO2D_COST_CASE =
// "SCENE dense|sparse" runs one case, for callgrind).
TEST(ReactionDigits, DISABLED_CostPerRecordedSample) {
  for (const char* scene : {"double_fourbar.yaml", "engine.yaml", "gear_train.yaml"})
    for (const LinearAlgebra la : {LinearAlgebra::dense, LinearAlgebra::sparse}) {
      const char* only = std::getenv("MO2D_COST_CASE");  // e.g. "engine.yaml sparse"
      if (only && std::string(only) != std::string(scene) + " " + to_string(la)) continue;
      const Scene s = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/" + scene);
      const Model m = build_scene_model(s);
      const State x = initial_state(s, m);
      ForwardOptions o;
      o.integrator = Integrator::rk4;
      o.linear_algebra = la;
      ForwardData d(m, o);
      d.accelerations(0.0, x.q0, x.q1, false);
      constexpr int kCalls = 4000;
      double best = INFINITY;
      for (int round = 0; round < 5; ++round) {
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < kCalls; ++k) d.compute_reactions(0.0, x.q0, x.q1);
        const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - start;
        best = std::min(best, dt.count() / kCalls);
      }
      std::printf("%-22s %-6s n1 %3d m1 %3d: %.0f ns per compute_reactions\n", scene, to_string(la),
                  m.n1, m.m1, 1e9 * best);
    }
}

}  // namespace
}  // namespace mo2d
