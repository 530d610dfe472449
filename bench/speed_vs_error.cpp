// Speed against error on the IFToMM double four-bar (forward-dynamics issue): every integrator over
// a range of steps / tolerances; error of the first crank tip at t = 10 s against the reference of
// shared/notes/peers.md (1-DOF parallelogram reduction in 40-digit arithmetic). Prints a Markdown
// table. Build Release: cmake --build build-bench --target mo2d_speed_vs_error
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

int main() {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const Model m = build_model(mechanisms::double_fourbar());
  const State st = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const double rx = 0.328458111541, ry = 0.944518538179;
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  std::printf(
      "| integrator | setting | B0(10 s) | error vs reference | steps | evaluations | CPU ms | max "
      "residual | max energy error (J) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  auto row = [&](ForwardOptions o, const std::string& setting) {
    o.t0 = 0;
    o.t1 = 10;
    o.samples = 11;
    try {
      const Trajectory r = forward_dynamics(m, st, o);
      const int k = static_cast<int>(r.time.size()) - 1;
      const VectorXd E = r.kinetic + r.potential;
      std::printf("| %s | %s | (%.9f, %.9f) | %.2e | %ld | %ld | %.1f | %.1e | %.1e |\n",
                  to_string(options_for_accuracy(m, o).integrator), setting.c_str(), r.q0(k, ix),
                  r.q0(k, iy), std::hypot(r.q0(k, ix) - rx, r.q0(k, iy) - ry), r.stats.steps,
                  r.stats.rhs_evaluations, 1e3 * r.stats.cpu_seconds, r.residuals.maxCoeff(),
                  (E.array() - E[0]).abs().maxCoeff());
    } catch (const std::exception& e) {
      std::printf("| %s | %s | failed: %s | | | | | | |\n", to_string(o.integrator),
                  setting.c_str(), e.what());
    }
  };
  auto g = [](const char* prefix, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%g", prefix, v);
    return std::string(buf);
  };
  for (double h : {4e-3, 2e-3, 1e-3, 1e-4})
    row({.integrator = Integrator::rk4, .step = h}, g("h = ", h));
  for (double tol : {1e-7, 1e-8, 3e-9, 1e-9})
    row({.integrator = Integrator::dopri5, .rtol = tol, .atol = tol}, g("tol ", tol));
  for (Integrator i : {Integrator::erk6, Integrator::erk8})
    for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12})
      row({.integrator = i, .rtol = tol, .atol = tol}, g("tol ", tol));
  for (double tol : {1e-6, 1e-8, 1e-10})
    row({.integrator = Integrator::cvode_bdf, .rtol = tol, .atol = tol}, g("tol ", tol));
  for (double a : {1e-3, 1e-5, 1e-6, 1e-8, 1e-9}) row({.accuracy = a}, g("accuracy ", a));
  row({.integrator = Integrator::cvode_adams, .rtol = 1e-8, .atol = 1e-8},
      "tol 1e-8, no projection");
  row({.integrator = Integrator::baumgarte, .step = 1e-3}, "h = 1e-3, alpha 20/s");
  return 0;
}
