// The sparse engine (ForwardOptions::linear_algebra, src/forward/sparse_engine.hpp) against the
// dense path: a second implementation of the same equations (other matrices, other
// factorizations, the augmented-Lagrangian iteration where the dense path solves directly), so
// every difference beyond rounding is a bug of one of them. Checked on generated mechanisms
// (tests/metamorphic/generator.hpp: chains, subsystems, prismatic and slot joints, springs,
// extra coordinates), on the N-four-bar, and through the ten singular passages of the double
// four-bar.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "forward/sparse_engine.hpp"
#include "metamorphic/generator.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"

namespace mo2d {
namespace {

ForwardOptions sparse_options(LinearAlgebra la, Integrator i = Integrator::dopri5) {
  ForwardOptions o;
  o.integrator = i;
  o.linear_algebra = la;
  return o;
}

// |x - y|_inf relative to max(|y|_inf, floor)
double sparse_rel_diff(const VectorXd& x, const VectorXd& y, double floor) {
  return (x - y).lpNorm<Eigen::Infinity>() / std::max(y.lpNorm<Eigen::Infinity>(), floor);
}

// A consistent state with velocities: random rates projected on A q1 = b by the dense workspace.
State sparse_moving_state(const Model& m, ForwardData& dense, std::uint64_t seed) {
  meta::Rng rng(seed);
  State s{0, m.q0, VectorXd::Zero(m.n1)};
  for (int k = 0; k < m.n1; ++k) s.q1[k] = rng.uniform(-1, 1) * m.scale / std::max(m.scale, 1e-9);
  dense.project(0, s.q0, s.q1, 1e-13 * m.scale, 1e-13);
  return s;
}

// One evaluation of the accelerations, the multipliers and the reactions: sparse == dense to
// rounding, on 40 generated mechanisms at a moving state.
TEST(Sparse, AccelerationsAndReactionsEqualTheDensePathOnGeneratedMechanisms) {
  meta::GeneratorStats stats;
  double worst_a = 0, worst_r = 0;
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const meta::Mechanism mech = meta::generate(7000 + seed, stats);
    const Model m = build_model(meta::to_system(mech));
    if (m.n1 == 0) continue;
    ForwardData dense(m, sparse_options(LinearAlgebra::dense));
    ForwardData sparse(m, sparse_options(LinearAlgebra::sparse));
    const State s = sparse_moving_state(m, dense, seed);
    // the mass matrix assembled body by body equals the dense one (column by column)
    EXPECT_EQ(MatrixXd(sparse.sparse_engine()->M), dense.M) << mech.family;
    const VectorXd u = VectorXd::Zero(m.n_inputs());
    forward_accelerations(m, dense, 0.1, s.q0, s.q1, u);
    forward_accelerations(m, sparse, 0.1, s.q0, s.q1, u);
    const double scale_a = 9.81 + dense.a.lpNorm<Eigen::Infinity>();
    const double da = sparse_rel_diff(sparse.a, dense.a, scale_a);
    dense.compute_reactions(0.1, s.q0, s.q1);
    sparse.compute_reactions(0.1, s.q0, s.q1);
    const double dr =
        m.n_reactions() ? sparse_rel_diff(sparse.reactions, dense.reactions, 1.0) : 0.0;
    EXPECT_LE(da, 1e-10) << mech.family << " seed " << 7000 + seed;
    EXPECT_LE(dr, 1e-8) << mech.family << " seed " << 7000 + seed;
    worst_a = std::max(worst_a, da);
    worst_r = std::max(worst_r, dr);
    ++checked;
  }
  EXPECT_GE(checked, 30);
  std::printf("sparse vs dense over %d mechanisms: accelerations %.2g, reactions %.2g\n", checked,
              worst_a, worst_r);
}

// Whole runs: every sample of q0, q1, the reactions and the energies agree.
TEST(Sparse, ForwardRunsEqualTheDensePath) {
  meta::GeneratorStats stats;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const meta::Mechanism mech = meta::generate(9100 + seed, stats);
    const Model m = build_model(meta::to_system(mech));
    if (m.n1 == 0) continue;
    for (Integrator i : {Integrator::dopri5, Integrator::rk4}) {
      ForwardOptions o = sparse_options(LinearAlgebra::dense, i);
      o.t1 = 0.3 * mech.t1;
      o.samples = 7;
      o.step = o.t1 / 120;
      o.rtol = o.atol = 1e-10;
      ForwardData start(m, sparse_options(LinearAlgebra::dense));
      const State s0 = sparse_moving_state(m, start, seed);
      Trajectory d, sp;
      try {
        d = forward_dynamics(m, s0, o);
      } catch (const Error&) {
        continue;  // a mechanism the dense run refuses is not a comparison
      }
      o.linear_algebra = LinearAlgebra::sparse;
      sp = forward_dynamics(m, s0, o);
      const double L = std::max(m.scale, 1e-9);
      EXPECT_LE((sp.q0 - d.q0).cwiseAbs().maxCoeff(), 1e-8 * L)
          << mech.family << " " << to_string(i);
      EXPECT_LE((sp.kinetic - d.kinetic).cwiseAbs().maxCoeff(),
                1e-8 * (1 + d.kinetic.cwiseAbs().maxCoeff()))
          << mech.family << " " << to_string(i);
      EXPECT_EQ(sp.stats.warnings.size(), d.stats.warnings.size()) << mech.family;
      EXPECT_EQ(sp.stats.steps, d.stats.steps) << mech.family << " " << to_string(i);
    }
  }
}

// Through the ten singular passages of the IFToMM double four-bar (forward_test.cpp's reference,
// the parallelogram reduction in 40 digits): the sparse path stays on the branch as the dense
// one does, with the same step-over of singular instants.
TEST(Sparse, DoubleFourBarStaysOnThePhysicalBranch) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  for (Integrator i : {Integrator::rk4, Integrator::dopri5}) {
    ForwardOptions o = sparse_options(LinearAlgebra::sparse, i);
    o.t1 = 10;
    o.samples = 41;
    o.step = 4e-3;
    o.rtol = o.atol = 1e-9;
    const Trajectory r = forward_dynamics(m, s, o);
    const int k = static_cast<int>(r.time.size()) - 1;
    const double e = std::hypot(r.q0(k, ix) - 0.328458111541, r.q0(k, iy) - 0.944518538179);
    // the dense path's bounds in forward_test.cpp (rk4 4e-3: 3.3e-7; dopri5: ~370 rtol)
    EXPECT_LE(e, i == Integrator::rk4 ? 1e-6 : 1e-6) << to_string(i);
    EXPECT_TRUE(r.stats.sparse);
    const bool reported = std::any_of(
        r.stats.warnings.begin(), r.stats.warnings.end(),
        [](const std::string& w) { return w.find("near-singular") != std::string::npos; });
    EXPECT_TRUE(reported) << to_string(i);
  }
}

TEST(Sparse, AutomaticChoosesByIntegratorAndSize) {
  const Model small = build_model(mechanisms::double_fourbar());
  EXPECT_FALSE(uses_sparse(small, sparse_options(LinearAlgebra::automatic)));
  EXPECT_TRUE(uses_sparse(small, sparse_options(LinearAlgebra::sparse)));
  ForwardOptions bdf = sparse_options(LinearAlgebra::sparse, Integrator::cvode_bdf);
  try {
    (void)uses_sparse(small, bdf);
    ADD_FAILURE() << "sparse with cvode_bdf accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "linear_algebra");
    EXPECT_NE(std::string(e.what()).find("cvode_bdf"), std::string::npos) << e.what();
  }
  ForwardOptions lagrange = sparse_options(LinearAlgebra::sparse);
  lagrange.formulation = Formulation::lagrange;
  EXPECT_THROW((void)uses_sparse(small, lagrange), Error);
}

}  // namespace
}  // namespace mo2d
