// The accuracy contract (issue 30, item 2), measured: scenes x accuracies 1e-2 ... 1e-9 (1e-10 is
// refused: below kMinAccuracy), each run's error at its output times against a reference computed
// at much tighter settings, its a-posteriori estimate (src/forward/error_estimate.cpp), whether
// it met the accuracy or warned, and the CPU of the run and of the estimate. Prints a Markdown
// table (docs/performance.md, "Issue 30"). Build Release:
//   cmake --build build --target mo2d_accuracy_table -j2 && build/bench/mo2d_accuracy_table [SCENE]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

struct Case {
  std::string name;
  Model model;
  State start;
  ForwardOptions base, reference;
  std::string reference_text;
};

double error_of(const Model& m, const Trajectory& r, const Trajectory& ref) {
  const VectorXd d = column_scaling(m).head(m.n0);
  double worst = 0;
  for (Eigen::Index k = 0; k < std::min(r.time.size(), ref.time.size()); ++k)
    for (int j = 0; j < m.n0; ++j)
      worst = std::max(worst, std::abs(r.q0(k, j) - ref.q0(k, j)) / d[j] / m.scale);
  return worst;
}

Case pendulum(double duration) {
  Model m = build_model(
      mechanisms::pendulum({.L = 1, .m = 1, .g = 9.81, .theta0 = -std::numbers::pi / 2 - 2.0})
          .system);
  State s = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  ForwardOptions base{.t0 = 0, .t1 = duration, .samples = 101};
  ForwardOptions ref = base;
  ref.integrator = Integrator::erk8;
  ref.rtol = ref.atol = 1e-14;
  char name[64];
  std::snprintf(name, sizeof name, "pendulum 2 rad, %g s", duration);
  return {name, m, s, base, ref, "erk8 1e-14"};
}

Case double_fourbar() {
  Model m = build_model(mechanisms::double_fourbar());
  State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  ForwardOptions base{.t0 = 0, .t1 = 10, .samples = 101};
  ForwardOptions ref = base;
  ref.integrator = Integrator::rk4;
  ref.step = 5e-5;
  return {"double four-bar, 10 s", m, s, base, ref, "rk4 h = 5e-5"};
}

Case scene_case(const std::string& path, const std::string& name, double duration, int samples,
                Integrator ri, double rtol) {
  const Scene sc = load_scene(path);
  Model m = build_scene_model(sc);
  ForwardOptions base = forward_options(sc, m);
  base.t1 = base.t0 + duration;
  base.samples = samples;
  ForwardOptions ref = base;
  ref.accuracy = 0;
  ref.integrator = ri;
  ref.rtol = rtol;
  ref.atol = rtol / 100;
  char text[64];
  std::snprintf(text, sizeof text, "%s %g", to_string(ri), rtol);
  char n[96];
  std::snprintf(n, sizeof n, "%s, %g s", name.c_str(), duration);
  return {n, m, initial_state(sc, m), base, ref, text};
}

}  // namespace

int main(int argc, char** argv) {  // argv[1]: only the scenes whose name contains it
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const std::string mech = MO2D_MECHANISMS_DIR, data = MO2D_TEST_DATA_DIR;
  Case cases[] = {
      pendulum(10),
      pendulum(100),
      double_fourbar(),
      scene_case(data + "/stiff_chain7.yaml", "stiff_chain7", 1, 1001, Integrator::cvode_bdf,
                 1e-13),
      scene_case(mech + "/rack_pinion.yaml", "rack_pinion", 5, 101, Integrator::erk8, 1e-14),
      scene_case(mech + "/sprung_double_pendulum.yaml", "sprung_double_pendulum", 2, 101,
                 Integrator::erk8, 1e-14),
  };
  std::printf(
      "| scene | reference | accuracy | method | error | estimated | verdict | CPU run ms | CPU "
      "estimate ms |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    if (argc > 1 && c.name.find(argv[1]) == std::string::npos) continue;
    Trajectory ref;
    try {
      ref = forward_dynamics(c.model, c.start, c.reference);
    } catch (const std::exception& e) {
      std::printf("| %s | %s: failed: %s |\n", c.name.c_str(), c.reference_text.c_str(), e.what());
      continue;
    }
    for (double a : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
      ForwardOptions o = c.base;
      o.accuracy = a;
      try {
        const Trajectory r = forward_dynamics(c.model, c.start, o);
        const double e = error_of(c.model, r, ref);
        const bool warned = r.stats.estimated_error > a;
        const char* verdict = e <= a ? (warned ? "met (warned)" : "met")
                                     : (warned ? "not met, warned" : "NOT MET, NO WARNING");
        std::printf("| %s | %s | %g | %s | %.1e | %.1e | %s | %.1f | %.1f |\n", c.name.c_str(),
                    c.reference_text.c_str(), a, r.stats.integrator.c_str(), e,
                    r.stats.estimated_error, verdict, 1e3 * r.stats.cpu_seconds,
                    1e3 * r.stats.estimate_cpu_seconds);
      } catch (const std::exception& e) {
        std::string what = e.what();
        if (what.size() > 60) what = what.substr(0, 60) + "...";
        std::printf("| %s | %s | %g | refused: %s | | | refused | | |\n", c.name.c_str(),
                    c.reference_text.c_str(), a, what.c_str());
      }
    }
  }
}
