// The pictures of the engine example (mechanisms/engine.yaml, issue 12 item 10):
//   docs/img/engine_indicator.png  the indicator diagram: cylinder pressure against volume over
//                                  the last complete cycle of the run (steady state)
//   docs/img/engine_speed.png      the crank speed from the start to the steady state, with the
//                                  mean speed of the closed-form balance W = 4 pi c <omega>
// One command (builds this program and runs it):
//   cmake --build build --target mo2d_engine_figures -j2
// or by hand: build/render/mo2d_render_engine_figures mechanisms/engine.yaml docs/img
// The pressure is the scene's own gas force at each sample (point_force of the load "gas",
// p = p_atm - F_y / Ap), the volume V = V_c + Ap (r + L - y_piston).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

#include "mo2d/dynamics.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"
#include "mo2d/scene.hpp"

namespace {

using namespace mo2d;

double parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  throw Error("engine figures: the scene has no parameter '" + name + "'", name);
}

const PointLoad& load(const Model& m, const std::string& name) {
  for (const PointLoad& f : m.forces)
    if (f.name == name) return f;
  throw Error("engine figures: the scene has no force '" + name + "'", name);
}

struct Cycle {
  Eigen::Index first = 0, last = 0;  // samples of the last complete cycle
  double work = 0;                   // its indicated work (J), trapezoid of p dV
};

}  // namespace

int main(int argc, char** argv) {
  const std::string scene_path = argc > 1 ? argv[1] : "mechanisms/engine.yaml";
  const std::string dir = argc > 2 ? argv[2] : "docs/img";
  try {
    const Scene scene = load_scene(scene_path);
    const Model model = build_scene_model(scene);
    ForwardOptions run = forward_options(scene, model);
    run.samples = 24001;  // 4 kHz: ~170 samples per revolution for the diagram
    check_scene_options(scene, model, run);
    const Trajectory r = forward_dynamics(model, initial_state(scene, model), run);

    const double Ap = parameter(scene, "Ap"), p_atm = parameter(scene, "p_atm");
    const double rc = parameter(scene, "r"), L = parameter(scene, "L");
    const double Vc = parameter(scene, "V_c"), c = parameter(scene, "c_load");
    const PointLoad& gas = load(model, "gas");
    const int th = model.coordinate("crank.angle"), y = model.coordinate("rod.B.y");
    const int w = model.rate("crank.w");
    const Eigen::Index n = r.time.size();
    std::vector<double> p(n), V(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Vec2 F =
          point_force(model, gas, r.q0.row(k).transpose(), r.q1.row(k).transpose(), r.time[k]);
      p[k] = (p_atm - F.y() / Ap) / 1e5;               // bar
      V[k] = (Vc + Ap * (rc + L - r.q0(k, y))) * 1e6;  // cm^3
    }
    // the last complete cycle: from the last sample before 4 pi k to the first after 4 pi (k+1)
    const double cycle = 4 * std::numbers::pi;
    const double k_end = std::floor(r.q0(n - 1, th) / cycle) - 1;
    Cycle last;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (r.q0(k, th) <= k_end * cycle) last.first = k;
      if (r.q0(k, th) >= (k_end + 1) * cycle) {
        last.last = k;
        break;
      }
    }
    Plot indicator;
    indicator.title = "Engine: indicator diagram (last cycle of the run, steady state)";
    indicator.x.label = "cylinder volume (cm\u00B3)";
    indicator.y.label = "cylinder pressure (bar)";
    Series pv{"p(V)", {}, {}};
    for (Eigen::Index k = last.first; k <= last.last; ++k) {
      pv.x.push_back(V[k]);
      pv.y.push_back(p[k]);
      if (k > last.first)
        last.work += (0.5 * (p[k] + p[k - 1]) * 1e5 - p_atm) * (V[k] - V[k - 1]) * 1e-6;
    }
    indicator.series = {pv};
    indicator.legend = false;
    indicator.width = 720;
    indicator.height = 480;
    indicator.dpi = 110;
    const std::string indicator_path = dir + "/engine_indicator.png";
    write_plot(indicator, indicator_path);

    // crank speed (rpm) and the closed-form mean speed W / (4 pi c) of the steady state
    const double rpm = 60 / (2 * std::numbers::pi);
    const double mean = last.work / (cycle * c);
    Plot speed;
    speed.title = "Engine: crank speed from " +
                  std::to_string(static_cast<int>(std::lround(r.q1(0, w) * rpm))) +
                  " rpm to the steady state";
    speed.x.label = "time (s)";
    speed.y.label = "crank speed (rpm)";
    Series s{"crank speed", {}, {}};
    for (Eigen::Index k = 0; k < n; k += 4) {
      s.x.push_back(r.time[k]);
      s.y.push_back(r.q1(k, w) * rpm);
    }
    Series m{"mean speed from W = 4\u03C0 c \u27E8\u03C9\u27E9",
             {r.time[0], r.time[n - 1]},
             {mean * rpm, mean * rpm}};
    m.dashed = true;
    speed.series = {s, m};
    const auto [lo, hi] = std::minmax_element(s.y.begin(), s.y.end());
    speed.y.range =
        std::pair{100 * std::floor((*lo - 20) / 100), 100 * std::ceil((*hi + 20) / 100)};
    speed.width = 720;
    speed.height = 400;
    speed.dpi = 110;
    const std::string speed_path = dir + "/engine_speed.png";
    write_plot(speed, speed_path);
    std::printf(
        "indicated work %.3f J/cycle; mean speed %.3f rad/s (%.1f rpm)\nwrote %s\nwrote %s\n",
        last.work, mean, mean * rpm, indicator_path.c_str(), speed_path.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_engine_figures: %s\n", e.what());
    return 1;
  }
}
