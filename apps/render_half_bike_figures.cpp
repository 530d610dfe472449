// The pictures of the half-bike (mechanisms/half_bike.yaml, issue 13 item 4):
//   docs/img/half_bike_filmstrip.png  scenario 1 (engine ramp, coast, brake) at four instants:
//                                     the chain's spans coloured by tension, slack spans dashed
//   docs/img/half_bike_speed.png      scenario 1: the wheel's speed relative to the arm against
//                                     the drive ratio times the shaft's speed
//   docs/img/half_bike_tension.png    scenario 1: the tension of both spans
//   docs/img/half_bike_extension.png  scenario 2 (triangular engine and load torques): the
//                                     pulling span's extension at k = 1e4, 1e5, 1e6 N/m
// One command (builds this program and runs it):
//   cmake --build build --target mo2d_half_bike_figures -j2
// or by hand: build/render/mo2d_render_half_bike_figures mechanisms/half_bike.yaml docs/img
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "mo2d/mo2d.hpp"
#include "mo2d/output_columns.hpp"
#include "mo2d/render.hpp"
#include "mo2d/scene.hpp"

namespace {

using namespace mo2d;

struct Run {
  Scene scene;
  Model model;
  Trajectory r;
};

Run run(const std::string& path, const std::vector<ParameterOverride>& set,
        const std::vector<RunOverride>& settings) {
  Run b{load_scene(path, set, settings), {}, {}};
  b.model = build_scene_model(b.scene);
  const ForwardOptions o = forward_options(b.scene, b.model);
  check_scene_options(b.scene, b.model, o);
  b.r = forward_dynamics(b.model, initial_state(b.scene, b.model), o);
  add_output_columns(b.model, b.r, b.scene.outputs);
  return b;
}

double parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  throw Error("half-bike figures: the scene has no parameter '" + name + "'", name);
}

Series column(const Trajectory& r, const std::string& label, int col, bool output, double scale) {
  Series s{label, {}, {}};
  for (Eigen::Index k = 0; k < r.time.size(); ++k) {
    s.x.push_back(r.time[k]);
    s.y.push_back(scale * (output ? r.outputs(k, col) : r.q1(k, col)));
  }
  return s;
}

Plot time_plot(const std::string& title, const std::string& y) {
  Plot p;
  p.title = title;
  p.x.label = "time (s)";
  p.y.label = y;
  p.width = 720;
  p.height = 360;
  p.dpi = 110;
  return p;
}

void scenario1(const std::string& path, const std::string& dir) {
  const Run b = run(path, {}, {{"duration", "15"}, {"samples", "1501"}});
  const Trajectory& r = b.r;
  const Motion m = motion_of(r);
  FilmstripOptions film;
  film.samples = {250, 490, 800, 1060};  // traction, engine at its peak, coasting, braking
  film.columns = 2;
  film.tile.width = 420;
  film.tile.height = 230;
  film.tile.dpi = 100;
  write_filmstrip(b.model, m, film, dir + "/half_bike_filmstrip.png");

  const double rho = parameter(b.scene, "r_ds") / parameter(b.scene, "r_ws");
  Series wheel = column(r, "wheel relative to the arm", r.rate_column("wheel.w"), false, 1);
  const Series arm = column(r, "", r.rate_column("arm.w"), false, 1);
  for (size_t k = 0; k < wheel.y.size(); ++k) wheel.y[k] -= arm.y[k];
  Series ratio = column(r, "(r_ds / r_ws) \u00D7 shaft", r.rate_column("shaft.w"), false, rho);
  ratio.dashed = true;
  Plot speed =
      time_plot("Half-bike, scenario 1: wheel speed against the drive ratio", "speed (rad/s)");
  speed.series = {wheel, ratio};
  write_plot(speed, dir + "/half_bike_speed.png");

  Plot tension = time_plot("Half-bike, scenario 1: chain tension (k = 1e5 N/m)", "tension (N)");
  tension.series = {column(r, "upper span", r.output("chain.upper.tension"), true, 1),
                    column(r, "lower span", r.output("chain.lower.tension"), true, 1)};
  write_plot(tension, dir + "/half_bike_tension.png");
  std::printf("scenario 1: energy balance error %.3e J\n", energy_balance_error(r));
}

void scenario2(const std::string& path, const std::string& dir) {
  Plot ext = time_plot("Half-bike, scenario 2: lower span extension (log scale; slack: gaps)",
                       "extension (m)");
  ext.y.log = true;
  for (const char* k : {"1e4", "1e5", "1e6"}) {
    const Run b = run(path, {{"scenario", "2"}, {"k_chain", k}}, {{"duration", "20"}});
    const double rest = parameter(b.scene, "L0") + parameter(b.scene, "slack") / 2;
    Series s =
        column(b.r, std::string("k = ") + k + " N/m", b.r.output("chain.lower.length"), true, 1);
    for (double& y : s.y) y -= rest;
    ext.series.push_back(s);
    std::printf("scenario 2, k = %s N/m: energy balance error %.3e J\n", k,
                energy_balance_error(b.r));
  }
  write_plot(ext, dir + "/half_bike_extension.png");
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "mechanisms/half_bike.yaml";
  const std::string dir = argc > 2 ? argv[2] : "docs/img";
  try {
    scenario1(path, dir);
    scenario2(path, dir);
    std::printf("wrote %s/half_bike_{filmstrip,speed,tension,extension}.png\n", dir.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_half_bike_figures: %s\n", e.what());
    return 1;
  }
}
