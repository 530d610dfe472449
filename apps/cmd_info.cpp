// mo2d info SCENE: what the scene defines (bodies, variables, constraints, inputs, DOF) and
// whether its initial configuration is consistent and non-singular; with --fidelity, each
// compliant element's frequency against the run's time scales (mo2d/fidelity.hpp).
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "command.hpp"
#include "mo2d/fidelity.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/mo2d.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

// Above this condition number of the velocity constraint Jacobian the configuration is reported
// as near-singular: with double precision, velocities would lose more than 8 of 16 digits.
constexpr double kNearSingular = 1e8;

// The time scales of the scene's run (the fixed step only for the fixed-step integrators).
RunTimeScale run_time_scale(const Scene& scene) {
  const RunSettings& r = scene.run;
  const int samples = r.samples > 0 ? r.samples : (r.solve == Solve::inverse ? 501 : 101);
  const bool fixed = r.solve == Solve::forward &&
                     (r.integrator == Integrator::rk4 || r.integrator == Integrator::baumgarte);
  return {r.duration, r.duration / std::max(1, samples - 1), fixed ? r.step : 0.0};
}

void print_fidelity(const Scene& scene, const Model& m) {
  const RunTimeScale scale = run_time_scale(scene);
  const State s = scene.run.solve == Solve::forward
                      ? initial_state(scene, m)
                      : State{scene.run.t0, m.q0, Eigen::VectorXd::Zero(m.n1)};
  std::cout << describe_fidelity(fidelity_report(m, s.q0, s.q1, s.t, scale), scale);
}

int info(const SceneOptions& o, bool fidelity) {
  const Scene scene = load_scene_with_overrides(o);
  const Model m = build_model_of(scene);
  check_memory("the conditioning of '" + m.name + "' (SVD of the velocity constraint Jacobian)",
               conditioning_memory_bytes(m), scene.run.max_memory, model_sizes(m), "max_memory");
  std::printf("scene %s\n", scene.file.c_str());
  std::cout << describe(m);
  std::printf("parameters:");
  for (const auto& [name, value] : scene.parameters) std::printf(" %s=%g", name.c_str(), value);
  std::printf("\nbodies:\n");
  for (const auto& b : m.bodies)
    std::printf("  %-24s mass %-10g inertia %-10g nodes %d%s\n", b.name.c_str(), b.mass, b.inertia,
                static_cast<int>(b.nodes.size()), b.has_omega ? "" : " (no rotation)");
  std::printf("constraints:\n");
  for (const auto& c : m.constraints)
    if (c.nrow0 + c.nrow1 > 0)
      std::printf("  %-24s %-16s %d position rows, %d velocity rows\n", c.name.c_str(),
                  constraint_kind_name(c.kind()), c.nrow0, c.nrow1);

  // consistency and conditioning of the initial configuration
  VectorXd psi(m.m0);
  position_residual(m, m.q0, scene.run.t0, psi);
  const double residual = m.m0 > 0 ? psi.cwiseAbs().maxCoeff() : 0.0;
  const Conditioning c = velocity_conditioning(m, m.q0, scene.run.t0);
  const bool full_rank = c.rank == c.rows;
  std::printf(
      "initial configuration: |psi| = %.2e m (%s), rank A = %d of %d rows, "
      "condition %.3g -> %s\n",
      residual, residual <= 1e-9 * m.scale ? "consistent" : "NOT consistent", c.rank, c.rows,
      c.condition,
      !full_rank                    ? "SINGULAR"
      : c.condition > kNearSingular ? "near-singular"
                                    : "non-singular");
  if (scene.run.solve == Solve::inverse) {
    std::printf("run: inverse dynamics, %d prescribed coordinate(s) for %d DOF",
                static_cast<int>(scene.motion.size()), m.dof);
    for (const auto& p : scene.motion) std::printf(" %s", p.coordinate.c_str());
    std::printf("\n");
  } else {
    const State s = initial_state(scene, m);
    std::printf(
        "run: forward dynamics, initial state consistent (t0 = %g s, kinetic energy %.6g J)\n", s.t,
        kinetic_energy(m, s.q1));
  }
  if (fidelity) print_fidelity(scene, m);
  return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* sub = app.add_subcommand(
      "info",
      "Describe a scene: bodies, variables, constraints, inputs, DOF, initial configuration");
  add_scene_options(sub, *o, false);
  auto fidelity = std::make_shared<bool>(false);
  sub->add_flag("--fidelity", *fidelity,
                "Each compliant element's own frequency against the run's time scales, which to "
                "reduce, and the reduced ones with their fidelity (docs/reduction.md)");
  return {sub, [o, fidelity] { return info(*o, *fidelity); }};
}

}  // namespace mo2d::cli
