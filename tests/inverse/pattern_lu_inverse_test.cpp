// Inverse dynamics with the fixed-pattern LUs of K and of the Newton Jacobian (the default,
// src/linalg/pattern_lu.hpp) against the same samples with both LUs forced onto the dense
// partial-pivoting path they replaced (PatternLU with dense_below = infinity is SmallLU): the
// shipped inverse scenes, the reference examples and generated mechanisms
// (tests/metamorphic/generator.hpp) agree to 1e-12 relative in positions, velocities,
// accelerations, efforts and reactions, and most samples did take the sparse path.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "linalg/pattern_lu.hpp"
#include "metamorphic/generator.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/scene.hpp"

namespace pattern_lu_inverse_test {

using namespace mo2d;

// Largest difference and largest value of one result over a run.
struct Gap {
  double diff = 0, size = 0;
  void add(const VectorXd& a, const VectorXd& b) {
    if (a.size() == 0) return;
    diff = std::max(diff, (a - b).lpNorm<Eigen::Infinity>());
    size = std::max(size, b.lpNorm<Eigen::Infinity>());
  }
  double relative() const { return size > 0 ? diff / size : diff; }
};

struct Outcome {
  double worst = 0;
  std::string what;
  long sparse = 0, calls = 0;  // factorizations of K (and of J) that took the pattern
};

Outcome compare(const Model& m, std::span<const Prescribed> p, const InverseOptions& o) {
  InverseData a(m, p, o), b(m, p, o);
  b.lu_K = std::make_unique<detail::PatternLU>(m.n1, INFINITY);
  b.lu_pos = std::make_unique<detail::PatternLU>(static_cast<int>(b.J.cols()), INFINITY);
  Gap q0, q1, a1, u, reactions;
  const int N = o.samples;
  for (int k = 0; k < N; ++k) {
    const double t = N == 1 ? o.t0 : o.t0 + (o.t1 - o.t0) * k / (N - 1);
    inverse_dynamics_sample(m, a, t);
    inverse_dynamics_sample(m, b, t);
    q0.add(a.q0, b.q0), q1.add(a.q1, b.q1), a1.add(a.a1, b.a1);
    u.add(a.u, b.u), reactions.add(a.reactions, b.reactions);
  }
  Outcome r;
  for (const auto& [gap, name] :
       {std::pair{q0, "q0"}, {q1, "q1"}, {a1, "a1"}, {u, "efforts"}, {reactions, "reactions"}})
    if (gap.relative() > r.worst) r.worst = gap.relative(), r.what = name;
  for (const auto* lu : {a.lu_K.get(), a.lu_pos.get()}) {
    r.sparse += lu->refactorizations;
    r.calls += lu->refactorizations + lu->dense_factorizations;
  }
  EXPECT_EQ(b.lu_K->refactorizations + b.lu_pos->refactorizations, 0);
  return r;
}

constexpr double kAgree = 1e-12;

TEST(PatternLUInverse, ShippedScenesAgreeWithDense) {
  int scenes = 0;
  for (const char* name :
       {"cam_table", "crank_press", "fourbar", "pendulum", "rrr3", "slider_crank",
        "slider_crank_friction", "watt_sixbar_lengths", "whitworth"}) {
    const Scene s = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml");
    if (s.motion.empty()) continue;
    const Model m = build_scene_model(s);
    const Outcome r = compare(m, s.motion, inverse_options(s));
    EXPECT_LT(r.worst, kAgree) << name << ": " << r.what;
    EXPECT_GT(r.sparse, r.calls / 2) << name << ": " << r.sparse << " of " << r.calls;
    ++scenes;
  }
  EXPECT_GE(scenes, 8);
}

TEST(PatternLUInverse, ExamplesAgreeWithDense) {
  for (const auto& ex : {mechanisms::whitworth(), mechanisms::rrr3(), mechanisms::slider_crank(),
                         mechanisms::fourbar()}) {
    const Model m = build_model(ex.system);
    const Outcome r = compare(m, ex.motion, ex.run);
    EXPECT_LT(r.worst, kAgree) << m.name << ": " << r.what;
    EXPECT_GT(r.sparse, r.calls * 9 / 10) << m.name << ": " << r.sparse << " of " << r.calls;
  }
}

TEST(PatternLUInverse, GeneratedMechanismsAgreeWithDense) {
  meta::GeneratorStats stats;
  long sparse = 0, calls = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const meta::Mechanism mech = meta::generate(seed, stats);
    const Model m = build_model(meta::to_system(mech));
    const auto p = meta::prescribed(mech);
    const Outcome r = compare(m, p, {.t0 = 0, .t1 = mech.t1, .samples = 41});
    EXPECT_LT(r.worst, kAgree) << "seed " << seed << " (" << mech.family << "): " << r.what;
    sparse += r.sparse, calls += r.calls;
  }
  EXPECT_GT(sparse, calls / 2) << sparse << " of " << calls;
}

}  // namespace pattern_lu_inverse_test
