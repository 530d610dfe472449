// mo2d beside MuJoCo and Box2D on the same mechanisms, measured in one run (performance issue,
// docs/performance.md "Peers"). A plain program printing Markdown tables, not a Google Benchmark:
// each row is one timed run of its own. Built only where MuJoCo is found (libmujoco-dev):
//   cmake --build build --target mo2d_peers_bench && taskset -c 0 build/bench/mo2d_peers_bench
// Options: --long adds the MuJoCo runs of 1.6 million steps (about 5 s each); --max-n N caps the
// chain sizes of the second table (default 400; the dense path is not run past N = 400; 0: no
// second table); --csv FILE writes the second table's costs (seconds) for the plot
// docs/img/n_scaling.png (bench/scaling_plot.cpp); --engine mo2d|mujoco runs only that engine's
// rows of the first table (for alternating runs of the two); --self-test checks the harness' read
// of MuJoCo's crank tip against closed-form kinematics of its joint angle (ctest
// bench.peers_harness).
//
// 1. IFToMM double four-bar, 10 s: error of the first crank tip at t = 10 s against the exact
//    reference of shared/notes/peers.md (1-DOF parallelogram reduction, 40-digit arithmetic),
//    against process CPU time of the run (model construction excluded).
// 2. IFToMM N-four-bar (N + 1 cranks pivoted at x = 0 .. N, N couplers, 1 kg / 1 m uniform bars,
//    gravity, crank tips at 1 m/s): CPU per step at h = 2e-3 (mo2d rk4: 4 evaluations and one
//    projection; MuJoCo Euler: one mj_step; Box2D: one b2World::Step, 8 velocity and 3 position
//    iterations), and the model construction time.
//
// MuJoCo's model: the same bars in the x-z plane, hinges about y, each coupler a child of its
// left crank, the right end closed on the next crank's tip by a `connect` equality; contacts off;
// the equality made as stiff as is stable at the step (solref time constant 2 h, critical
// damping, solimp 0.9999): MuJoCo's constraints are soft, so this is its most accurate setting.
// Table 1 adds the rest of the tuned settings of shared/peers/README.md (solver Newton, tolerance
// 1e-12, 1000 iterations, dense Jacobian) and runs MuJoCo's three integrators (Euler, RK4,
// implicit); table 2 keeps MuJoCo's default solver settings (cost per step, Euler).
// Measured: a time constant below 2 h (refsafe off) leaves the branch at every step tried here;
// solimp 0.99999 or 0.999999 changes the errors by less than 1 %; 0.9 multiplies them by 3-30.
//
// The crank tip is read after mj_kinematics of the final state: right after mj_step, site_xpos
// still holds the kinematics computed at the start of the step (the position at t - h), which
// alone adds about |v| h to the error (the "error 1.6 h" of earlier versions of this table).
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "box2d_world.hpp"
#include "eval_cost.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/mo2d.hpp"
#include "n_fourbar.hpp"

namespace {

using namespace mo2d;
using mo2d::bench::n_fourbar;

constexpr double kRefX = 0.328458111541, kRefY = 0.944518538179;  // B0(10 s), peers.md

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// ---- the mechanism in mo2d
// -----------------------------------------------------------------------
State start_state(const Model& m) {
  return consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
}

// ---- the mechanism in MuJoCo
// ----------------------------------------------------------------------
// MuJoCo's settings: table 1 uses the tuned ones of shared/peers/README.md (solver, tolerance,
// iterations, dense Jacobian) with each integrator; table 2 the default solver, Euler.
struct MjSettings {
  const char* integrator = "Euler";  // Euler, RK4 or implicit (MuJoCo 2.2's names)
  bool tuned = false;
};

std::string mjcf(int n, double h, MjSettings s = {}) {
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco model='fourbar_chain'>\n"
    << "  <option timestep='" << h << "' integrator='" << s.integrator << "' gravity='0 0 -9.81'"
    << " jacobian='" << (n > 10 ? "sparse" : "dense") << "'"
    << (s.tuned ? " solver='Newton' tolerance='1e-12' iterations='1000'" : "") << ">\n"
    << "    <flag contact='disable'/>\n  </option>\n"
    << "  <default><equality solref='" << 2 * h << " 1' solimp='0.9999 0.9999 0.001 0.5 2'/>"
    << "</default>\n"
    << "  <size njmax='" << 3 * n + 16 << "'/>\n"  // the equality rows: 3 per connect
    << "  <worldbody>\n";
  const char* rod =
      "pos='0 0 0.5' mass='1' diaginertia='0.0833333333333333 0.0833333333333333 1e-9'";
  for (int k = 0; k <= n; ++k) {
    x << "    <body name='crank" << k << "' pos='" << k << " 0 0'>\n"
      << "      <joint type='hinge' axis='0 1 0'/>\n"
      << "      <inertial " << rod << "/>\n"
      << "      <site name='tip" << k << "' pos='0 0 1'/>\n";
    if (k < n)
      x << "      <body name='coupler" << k + 1 << "' pos='0 0 1'>\n"
        << "        <joint type='hinge' axis='0 1 0'/>\n"
        << "        <inertial pos='0.5 0 0' mass='1' diaginertia='1e-9 0.0833333333333333 "
           "0.0833333333333333'/>\n"
        << "      </body>\n";
    x << "    </body>\n";
  }
  x << "  </worldbody>\n  <equality>\n";
  for (int k = 0; k < n; ++k)
    x << "    <connect body1='coupler" << k + 1 << "' body2='crank" << k + 1
      << "' anchor='1 0 0'/>\n";
  x << "  </equality>\n</mujoco>\n";
  return x.str();
}

struct MjRun {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  int tip0 = -1;
  MjRun(int n, double h, MjSettings s = {}) {
    const std::filesystem::path p = std::filesystem::temp_directory_path() /
                                    ("mo2d_peers_" + std::to_string(::getpid()) + ".xml");
    std::ofstream(p) << mjcf(n, h, s);
    char err[1000] = "";
    model = mj_loadXML(p.c_str(), nullptr, err, sizeof err);
    std::filesystem::remove(p);
    if (!model) throw std::runtime_error(std::string("MuJoCo: ") + err);
    data = mj_makeData(model);
    // crank tips at 1 m/s in +x: crank rates +1 about y; couplers stay horizontal (relative -1)
    for (int k = 0; k < model->nv; ++k)
      data->qvel[k] = (model->jnt_bodyid[k] % 2 == 1) ? 1.0 : -1.0;
    tip0 = mj_name2id(model, mjOBJ_SITE, "tip0");
    mj_forward(model, data);
  }
  // The harness' read of the first crank tip (x, z: mo2d's x, y) at the state reached: the
  // kinematics of that state first (mj_step leaves site_xpos at the start of its step).
  std::array<double, 2> tip() const {
    mj_kinematics(model, data);
    const double* p = data->site_xpos + 3 * tip0;
    return {p[0], p[2]};
  }
  ~MjRun() {
    mj_deleteData(data);
    mj_deleteModel(model);
  }
  MjRun(const MjRun&) = delete;
  MjRun& operator=(const MjRun&) = delete;
};

// ---- table 1: double four-bar, error against CPU time
// --------------------------------------------
enum class Engines { all, mo2d, mujoco };

void speed_vs_error(bool long_runs, Engines engines) {
  std::printf("\n### Double four-bar, 10 s: error of B0(10 s) against CPU time\n\n");
  std::printf("| engine | setting | error | steps | CPU ms |\n|---|---|---|---|---|\n");
  const Model m = build_model(n_fourbar(2));
  const State st = start_state(m);
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  auto mo2d_row = [&](ForwardOptions o, const char* setting) {
    o.t0 = 0;
    o.t1 = 10;
    o.samples = 2;
    const Trajectory r = forward_dynamics(m, st, o);
    const double e = std::hypot(r.q0(1, ix) - kRefX, r.q0(1, iy) - kRefY);
    std::printf("| mo2d %s | %s | %.2e | %ld | %.2f |\n",
                to_string(options_for_accuracy(m, o).integrator), setting, e, r.stats.steps,
                1e3 * r.stats.cpu_seconds);
  };
  if (engines != Engines::mujoco) {
    mo2d_row({.integrator = Integrator::dopri5, .rtol = 3e-6, .atol = 3e-6}, "tol 3e-6");
    mo2d_row({.integrator = Integrator::dopri5, .rtol = 1e-7, .atol = 1e-7}, "tol 1e-7");
    mo2d_row({.integrator = Integrator::dopri5, .rtol = 1e-9, .atol = 1e-9}, "tol 1e-9");
    mo2d_row({.integrator = Integrator::rk4, .step = 2e-3}, "h 2e-3");
    mo2d_row({.integrator = Integrator::cvode_bdf, .rtol = 1e-8, .atol = 1e-8}, "tol 1e-8");
    // the high-order methods, and what run.accuracy picks (src/forward/accuracy.cpp)
    mo2d_row({.integrator = Integrator::erk6, .rtol = 1e-5, .atol = 1e-5}, "tol 1e-5");
    mo2d_row({.integrator = Integrator::erk8, .rtol = 1e-5, .atol = 1e-5}, "tol 1e-5");
    // the cheapest runs of issue 33 at 1e-3, 1e-6 and 1e-10 (scripts/instructions.sh counts them)
    mo2d_row({.integrator = Integrator::erk6, .rtol = 3e-6, .atol = 3e-6}, "tol 3e-6");
    mo2d_row({.integrator = Integrator::erk8, .rtol = 3e-9, .atol = 3e-9}, "tol 3e-9");
    mo2d_row({.integrator = Integrator::rk4, .step = 8e-4}, "h 8e-4");
    mo2d_row({.accuracy = 1e-3}, "accuracy 1e-3");
    mo2d_row({.accuracy = 1e-6}, "accuracy 1e-6");
    mo2d_row({.accuracy = 1e-5}, "accuracy 1e-5");
    mo2d_row({.accuracy = 1e-9}, "accuracy 1e-9");
  }
  if (engines == Engines::mo2d) return;
  for (const char* integ : {"Euler", "RK4", "implicit"}) {
    // steps over the 10 s (h = 10 / steps): dense enough to find the cheapest run under 1e-3,
    // and to show that the error is not monotone in h (the implicit integrator's changes sign)
    for (long steps : {1000L, 1250L, 1500L, 1600L, 2000L, 3200L, 5000L, 10000L, 16000L, 32000L,
                       50000L, 100000L, 160000L, 1600000L}) {
      if (steps > 200000 && !long_runs) continue;
      const double h = 10.0 / static_cast<double>(steps);
      MjRun r(2, h, {.integrator = integ, .tuned = true});
      const double c0 = cpu_seconds();
      for (long k = 0; k < steps; ++k) mj_step(r.model, r.data);
      const double cpu = cpu_seconds() - c0;
      const std::array<double, 2> tip = r.tip();
      const double e = std::hypot(tip[0] - kRefX, tip[1] - kRefY);
      std::printf("| MuJoCo %d.%d.%d %s, tuned | h %.4g | %.2e | %ld | %.2f |\n",
                  mj_version() / 100, mj_version() / 10 % 10, mj_version() % 10, integ, h, e, steps,
                  1e3 * cpu);
    }
  }
}

// ---- the harness checked: its read of the crank tip against closed-form kinematics
// -----------------------------------------------------------------------
// The first crank turns about y at the origin, its tip at (0, 0, 1) in its body: at the joint
// angle q the tip is (sin q, cos q) in (x, z). After k steps the harness' read (MjRun::tip) must
// be that position of the state reached (t = k h), to rounding, for every integrator: a read of
// the kinematics of t - h is off by about |v| h (here ~5e-3).
int self_test() {
  int failed = 0, passed = 0;
  for (const char* integ : {"Euler", "RK4", "implicit"}) {
    const double h = 6.25e-3;
    MjRun r(2, h, {.integrator = integ, .tuned = true});
    const int crank0 = mj_name2id(r.model, mjOBJ_BODY, "crank0");
    const int qadr = r.model->jnt_qposadr[r.model->body_jntadr[crank0]];
    for (int k = 0; k < 160; ++k) mj_step(r.model, r.data);  // to t = 1 s
    const double q = r.data->qpos[qadr];
    const std::array<double, 2> tip = r.tip();
    const double dx = tip[0] - std::sin(q), dz = tip[1] - std::cos(q);
    const double dt = r.data->time - 160 * h;
    // the harness' error against the one of the closed-form position
    const double de = std::hypot(tip[0] - kRefX, tip[1] - kRefY) -
                      std::hypot(std::sin(q) - kRefX, std::cos(q) - kRefY);
    const bool ok = std::hypot(dx, dz) < 1e-12 && std::abs(dt) < 1e-12 && std::abs(de) < 1e-12;
    std::printf("%s %s: read (%.15f, %.15f), closed form (%.15f, %.15f) at t = %.6f\n",
                ok ? "ok  " : "FAIL", integ, tip[0], tip[1], std::sin(q), std::cos(q),
                r.data->time);
    ok ? ++passed : ++failed;
  }
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}

// ---- table 2: N-four-bar, cost per step
// ----------------------------------------------------------
double mo2d_step_cost(const Model& m, const State& st, int steps, LinearAlgebra la) {
  ForwardOptions o{.integrator = Integrator::rk4, .step = 2e-3};
  o.linear_algebra = la;
  o.t0 = 0;
  o.t1 = steps * 2e-3;
  o.samples = 2;
  const Trajectory r = forward_dynamics(m, st, o);
  return r.stats.cpu_seconds / static_cast<double>(r.stats.steps);
}

double mujoco_step_cost(int n, int steps) {
  MjRun r(n, 2e-3);
  const double c0 = cpu_seconds();
  for (int k = 0; k < steps; ++k) mj_step(r.model, r.data);
  return (cpu_seconds() - c0) / steps;
}

double box2d_step_cost(const Model& m, const State& st, int steps) {
  CrosscheckOptions o;
  crosscheck_detail::Box2DWorld w = crosscheck_detail::build_box2d_world(m, st.q0, st.q1, o, false);
  const double c0 = cpu_seconds();
  for (int k = 0; k < steps; ++k) w.world->Step(2e-3f, 8, 3);
  return (cpu_seconds() - c0) / steps;
}

template <class F>
double timed(F&& f) {
  const double c0 = cpu_seconds();
  f();
  return cpu_seconds() - c0;
}

struct ScaleRow {
  int n = 0;
  double dense = NAN, sparse = NAN, mj = NAN, b2 = NAN, eval_sparse = NAN, eval_dense = NAN;
};

void write_csv(const std::string& path, const std::vector<ScaleRow>& rows) {
  std::ofstream f(path);
  f << "N,mo2d_eval_sparse_s,mo2d_eval_dense_s,mo2d_rk4_step_sparse_s,mo2d_rk4_step_dense_s,"
       "mujoco_step_s,box2d_step_s\n";
  f.precision(6);
  for (const ScaleRow& r : rows)
    f << r.n << ',' << r.eval_sparse << ',' << r.eval_dense << ',' << r.sparse << ',' << r.dense
      << ',' << r.mj << ',' << r.b2 << '\n';
  if (!f) throw std::runtime_error("cannot write " + path);
}

void step_costs(int max_n, const std::string& csv) {
  std::printf(
      "\n### N-four-bar: CPU per step (h = 2e-3), per evaluation and model construction\n\n");
  std::printf(
      "| N | mo2d rk4 step, dense | mo2d rk4 step, sparse | MuJoCo step | Box2D step | mo2d sparse "
      "/ MuJoCo | mo2d eval, sparse | mo2d eval, dense | mo2d build | MuJoCo load "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<ScaleRow> rows;
  for (int n : {2, 5, 10, 20, 40, 100, 400, 1000}) {
    if (n > max_n) break;
    ScaleRow row{.n = n};
    Model m;
    const double build = timed([&] { m = build_model(n_fourbar(n)); });
    const State st = start_state(m);
    // budget: the dense step grows as N^3 (about 74 ms at N = 100): one step past N = 100
    const int steps = n <= 10 ? 200 : n <= 100 ? 5 : 1;
    if (n <= 400) row.dense = mo2d_step_cost(m, st, steps, LinearAlgebra::dense);
    row.sparse = mo2d_step_cost(m, st, n <= 100 ? 200 : 20, LinearAlgebra::sparse);
    row.eval_sparse = mo2d::bench::eval_cost(m, st, LinearAlgebra::sparse);
    if (n <= 400) row.eval_dense = mo2d::bench::eval_cost(m, st, LinearAlgebra::dense);
    row.mj = mujoco_step_cost(n, n <= 100 ? 2000 : 200);
    const double load = timed([&] { MjRun r(n, 2e-3); });
    Model mb = build_model(n_fourbar(n), {.reduction = Reduction::none});
    row.b2 = box2d_step_cost(mb, start_state(mb), n <= 100 ? 2000 : 200);
    auto us = [](double t) {
      char b[32] = "not run";
      if (std::isfinite(t)) std::snprintf(b, sizeof b, "%.3g µs", 1e6 * t);
      return std::string(b);
    };
    std::printf("| %d | %s | %s | %s | %s | %.3g | %s | %s | %.3g ms | %.3g ms |\n", n,
                us(row.dense).c_str(), us(row.sparse).c_str(), us(row.mj).c_str(),
                us(row.b2).c_str(), row.sparse / row.mj, us(row.eval_sparse).c_str(),
                us(row.eval_dense).c_str(), 1e3 * build, 1e3 * load);
    rows.push_back(row);
  }
  if (!csv.empty()) write_csv(csv, rows);
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  bool long_runs = false;
  int max_n = 400;
  std::string csv;
  Engines engines = Engines::all;
  bool self_check = false;
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--long") == 0)
      long_runs = true;
    else if (std::strcmp(argv[k], "--max-n") == 0 && k + 1 < argc)
      max_n = std::atoi(argv[++k]);
    else if (std::strcmp(argv[k], "--csv") == 0 && k + 1 < argc)
      csv = argv[++k];
    else if (std::strcmp(argv[k], "--engine") == 0 && k + 1 < argc &&
             (std::strcmp(argv[k + 1], "mo2d") == 0 || std::strcmp(argv[k + 1], "mujoco") == 0))
      engines = std::strcmp(argv[++k], "mo2d") == 0 ? Engines::mo2d : Engines::mujoco;
    else if (std::strcmp(argv[k], "--self-test") == 0)
      self_check = true;
    else {
      std::fprintf(stderr,
                   "usage: mo2d_peers_bench [--long] [--max-n N] [--csv FILE] "
                   "[--engine mo2d|mujoco] [--self-test]\n");
      return 2;
    }
  }
  try {
    if (self_check) return self_test();
    speed_vs_error(long_runs, engines);
    if (max_n > 0) step_costs(max_n, csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mo2d_peers_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
