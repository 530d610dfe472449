// Regenerates the README figures of the Whitworth quick-return mechanism:
//   docs/img/whitworth_filmstrip.png  one crank revolution (4 s), a frame every 0.5 s
//   docs/img/whitworth_torque.png     the crank torque over two revolutions
// One command (builds this program and runs it on docs/img):
//   cmake --build build --target mo2d_readme_figures -j2
// or by hand: build/render/mo2d_render_readme_figures docs/img
#include <cstdio>
#include <exception>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "docs/img";
  try {
    using namespace mo2d;
    const mechanisms::Example ex = mechanisms::whitworth();
    const Model model = build_model(ex.system);
    const Trajectory r = inverse_dynamics(model, ex.motion, ex.run);

    // One revolution of the crank (pi/2 rad/s: 4 s), sampled every 10 ms; a frame every 0.5 s
    // from 0.15 s, so that one frame falls on the torque's trough (2.65 s).
    InverseOptions rev_run = ex.run;
    rev_run.t1 = 4;
    rev_run.samples = 401;
    const Motion rev = motion_of(inverse_dynamics(model, ex.motion, rev_run));

    FilmstripOptions film;
    film.samples = {15, 65, 115, 165, 215, 265, 315, 365};  // t = 0.15 s + 0.5 s k
    film.columns = 4;
    film.tile.width = 250;
    film.tile.height = 250;
    film.tile.dpi = 100;
    film.tile.traces = {"rod.com"};
    const std::string strip = dir + "/whitworth_filmstrip.png";
    write_filmstrip(model, rev, film, strip);

    Plot torque = efforts_plot(r);
    torque.series[0].label = "crank torque (crank_pivot)";
    torque.title = "Whitworth mechanism: crank torque at \u03C9 = \u03C0/2 rad/s";
    torque.x.range = std::pair{0.0, 8.0};
    torque.y.range = std::pair{-1.25, 1.25};
    torque.legend = false;
    torque.width = 720;
    torque.height = 330;
    torque.dpi = 110;
    const std::string plot = dir + "/whitworth_torque.png";
    write_plot(torque, plot);
    std::printf("wrote %s\nwrote %s\n", strip.c_str(), plot.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_readme_figures: %s\n", e.what());
    return 1;
  }
}
