// The sparse kinematic set-up of large models (src/kinematics/sparse_kinematics.hpp: rank checks,
// assembly, initial velocities, conditioning) against the dense path, a second implementation
// (column-pivoted QR, complete orthogonal decomposition, LU, SVD): every difference beyond
// rounding is a bug of one of them. The sparse functions are called directly on small generated
// mechanisms (tests/metamorphic/generator.hpp), and through the public API on the N-four-bar
// (bench/n_fourbar.hpp) above the size where build_model, consistent_state and
// velocity_conditioning switch to them (kSparseKinematics).
#include "kinematics/sparse_kinematics.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../bench/n_fourbar.hpp"
#include "error_support.hpp"
#include "kinematics/solve_positions.hpp"
#include "metamorphic/generator.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/mo2d.hpp"

namespace mo2d {
namespace {

using detail::SparseRowsK;

// The dimensionless velocity rows of m at q0, sparse.
SparseRowsK dimensionless_A(const Model& m, const VectorXd& q0) {
  SparseRowsK A;
  VectorXd b(m.m1);
  detail::sparse_velocity_jacobian(m, q0, 0.0, A, b);
  detail::make_dimensionless(A, column_scaling(m));
  return A;
}

// Extreme singular values and rank: the sparse Gram-matrix iterations against the dense SVD, on
// 40 generated mechanisms (full rank: no dependent rows either way).
TEST(SparseKinematics, SingularValuesEqualTheDenseSvdOnGeneratedMechanisms) {
  meta::GeneratorStats stats;
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const meta::Mechanism mech = meta::generate(9100 + seed, stats);
    const Model m = build_model(meta::to_system(mech));
    if (m.m1 == 0) continue;
    MatrixXd A(m.m1, m.n1);
    VectorXd b(m.m1);
    velocity_jacobian(m, m.q0, 0.0, A, b);
    const Conditioning dense = conditioning(A, column_scaling(m));
    const SparseRowsK B = dimensionless_A(m, m.q0);
    const detail::SparseSingular sparse = detail::sparse_extreme_singular_values(B, 1e-10);
    EXPECT_EQ(sparse.rank, dense.rank) << mech.family;
    EXPECT_NEAR(sparse.sigma_max, dense.sigma_max, 1e-9 * dense.sigma_max) << mech.family;
    EXPECT_NEAR(sparse.sigma_min, dense.sigma_min, 1e-7 * dense.sigma_min) << mech.family;
    EXPECT_TRUE(detail::sparse_dependent_rows(B, 1e-10).empty()) << mech.family;
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

// Above kSparseKinematics the public velocity_conditioning takes the sparse path: the same rank,
// sigmas and condition number as the dense SVD of the same Jacobian (N = 60: n1 + m1 = 485).
TEST(SparseKinematics, LargeModelConditioningEqualsTheDenseSvd) {
  const Model m = build_model(bench::n_fourbar(60));
  ASSERT_TRUE(detail::sparse_kinematics(m));
  const Conditioning sparse = velocity_conditioning(m, m.q0);
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  velocity_jacobian(m, m.q0, 0.0, A, b);
  const Conditioning dense = conditioning(A, column_scaling(m));
  EXPECT_EQ(sparse.rank, dense.rank);
  EXPECT_EQ(sparse.rows, dense.rows);
  EXPECT_NEAR(sparse.condition, dense.condition, 1e-7 * dense.condition);
}

// The minimum-norm step: J dx = psi with dx in the row space of J (dense: the complete orthogonal
// decomposition's solve), on the position rows of generated mechanisms with a random right side.
TEST(SparseKinematics, MinimumNormStepEqualsTheDenseOne) {
  meta::GeneratorStats stats;
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const meta::Mechanism mech = meta::generate(9300 + seed, stats);
    const Model m = build_model(meta::to_system(mech));
    if (m.m0 == 0) continue;
    VectorXd psi(m.m0);
    MatrixXd J(m.m0, m.n0);
    position_jacobian(m, m.q0, 0.0, psi, J);
    const VectorXd rhs = VectorXd::LinSpaced(m.m0, -1, 1);
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(J);
    cod.setThreshold(1e-12);
    const VectorXd dense = cod.solve(rhs);
    SparseRowsK Js;
    detail::sparse_position_jacobian(m, m.q0, 0.0, nullptr, m.n0, psi, Js);
    VectorXd sparse;
    ASSERT_TRUE(detail::sparse_minimum_norm_step(Js, rhs, 1e-12, sparse)) << mech.family;
    EXPECT_LE((sparse - dense).lpNorm<Eigen::Infinity>(),
              1e-9 * std::max(1.0, dense.lpNorm<Eigen::Infinity>()))
        << mech.family;
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// build_model on a large chain (the description: counts, labels and DOF do not depend on the
// path), and assembly from displaced positions: the sparse Newton returns the configuration the
// dense one (solve_positions with assemble's options) finds, the same minimum-norm steps.
TEST(SparseKinematics, LargeChainAssemblesAsTheDensePath) {
  const Model m = build_model(bench::n_fourbar(100));
  ASSERT_TRUE(detail::sparse_kinematics(m));
  EXPECT_EQ(m.dof, 1);
  EXPECT_NE(describe(m).find("1 DOF"), std::string::npos);
  VectorXd guess = m.q0;
  for (int k = 0; k < m.n0; ++k) guess[k] += 0.01 * std::sin(3.0 * k);
  const std::vector<int> fixed = {0};  // the first coordinate held
  const VectorXd sparse = assemble(m, guess, 0.0, fixed);
  VectorXd psi(m.m0);
  position_residual(m, sparse, 0.0, psi);
  EXPECT_LE(psi.lpNorm<Eigen::Infinity>(), 1e-12 * m.scale);
  EXPECT_EQ(sparse[fixed[0]], guess[fixed[0]]);
  // the dense Newton of assemble.cpp
  std::vector<int> colmap(m.n0);
  int nfree = 0;
  for (int k = 0; k < m.n0; ++k) colmap[k] = k == fixed[0] ? -1 : nfree++;
  VectorXd dx(nfree), q_trial(m.n0), dense = guess;
  MatrixXd J(m.m0, nfree);
  detail::NewtonBuffers w{.psi = psi, .J = J, .dx = dx, .q_trial = &q_trial};
  const detail::NewtonOptions o{.tolerance = 1e-12 * m.scale,
                                .max_iterations = 100,
                                .test_last = false,
                                .step = detail::NewtonStep::minimum_norm,
                                .rank_threshold = 1e-12,
                                .line_search = detail::LineSearch::armijo,
                                .min_alpha = 1e-8,
                                .non_finite = detail::NonFinite::reject};
  ASSERT_EQ(detail::solve_positions(m, o, w, 0.0, colmap, dense).status,
            detail::NewtonStatus::converged);
  EXPECT_LE((sparse - dense).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_GE((sparse - guess).lpNorm<Eigen::Infinity>(), 1e-3);  // it moved
}

// consistent_state: the initial velocities by KLU equal the dense LU's (N = 100), and the
// velocities satisfy A q1 = b.
TEST(SparseKinematics, LargeChainInitialVelocities) {
  const Model m = build_model(bench::n_fourbar(100));
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  velocity_jacobian(m, s.q0, 0.0, A, b);
  EXPECT_LE((A * s.q1 - b).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_DOUBLE_EQ(s.q1[m.rate("crank0.w")], -1.0);
  // the parallelogram chain: every crank turns as the first
  for (int k = 1; k <= 100; ++k)
    EXPECT_NEAR(s.q1[m.rate("crank" + std::to_string(k) + ".w")], -1.0, 1e-12) << k;
}

// The rank checks on the sparse path: a redundant fifth bar in one loop of a 100-loop chain is
// refused naming a constraint of that loop, as the dense path does on the parallelogram
// (Errors.ParallelogramWithAFifthBarIsRedundant); two revolutes on the same nodes likewise.
TEST(SparseKinematics, LargeChainWithARedundantBarIsRefused) {
  System s = bench::n_fourbar(100);
  s.add_ground_node("M50", {50.5, 0});
  s.add_body({.name = "bar5",
              .nodes = {{"O", {50.5, 0}}, {"M", {50.5, 1}}},
              .mass = 1,
              .inertia = 0.1,
              .com = CenterOfMass::between("O", "M", 0.5)});
  s.add_revolute({.name = "bar5_pivot", .node_a = "ground.M50", .node_b = "bar5.O"});
  // a second coupler of loop 51 (redundant in a parallelogram), with a node at its middle for
  // the fifth bar (redundant too)
  for (Reduction r : {Reduction::flat, Reduction::none}) {
    SCOPED_TRACE(r == Reduction::flat ? "Reduction::flat" : "Reduction::none");
    System c = s;
    c.add_body({.name = "bar5_link",
                .nodes = {{"A", {50, 1}}, {"B", {51, 1}}, {"M", {50.5, 1}}},
                .mass = 1,
                .inertia = 0.1,
                .com = CenterOfMass::between("A", "B", 0.5)});
    c.add_revolute({.name = "bar5_link_left", .node_a = "crank50.B", .node_b = "bar5_link.A"});
    c.add_revolute({.name = "bar5_link_right", .node_a = "crank51.B", .node_b = "bar5_link.B"});
    c.add_revolute({.name = "bar5_pin", .node_a = "bar5_link.M", .node_b = "bar5.M"});
    Error e("");
    EXPECT_TRUE(test::ThrowsError(test::building(c, {.reduction = r}), {"redundant"}, &e));
    EXPECT_TRUE(test::NamesOneOf(e, {"crank50", "crank51", "coupler51", "bar5"}));
  }
}

}  // namespace
}  // namespace mo2d
