// mo2d command-line tool. For now: `mo2d demo [MECHANISM] [--out DIR]` runs the inverse dynamics
// of a built-in example mechanism (default: whitworth), prints a short table and writes the CSV.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace {

const char* kUsage =
    "usage: mo2d demo [MECHANISM] [--out DIR]\n"
    "  Runs the inverse dynamics of a built-in mechanism and writes DIR/MECHANISM_inverse.csv\n"
    "  MECHANISM: whitworth (default), rrr3, slider_crank, fourbar, pendulum\n"
    "  --out DIR  output folder (default: out)\n";

int demo(const std::string& name, const std::string& out_dir) {
  using namespace mo2d;
  const std::map<std::string, mechanisms::Example (*)()> table = {
      {"whitworth", &mechanisms::whitworth},
      {"rrr3", &mechanisms::rrr3},
      {"slider_crank", [] { return mechanisms::slider_crank(); }},
      {"fourbar", &mechanisms::fourbar},
      {"pendulum", [] { return mechanisms::pendulum(); }}};
  auto it = table.find(name);
  if (it == table.end()) {
    std::cerr << "mo2d: unknown mechanism '" << name << "'\n" << kUsage;
    return 2;
  }
  const mechanisms::Example ex = it->second();
  const Model model = build_model(ex.system);
  const InverseResult r = inverse_dynamics(model, ex.motion, ex.run);

  std::printf("mo2d inverse dynamics: %s\n", model.name.c_str());
  std::printf("  %d bodies, %d coordinates, %d quasi-velocities, %d DOF, %d samples over [%g, %g] s\n",
              static_cast<int>(model.bodies.size()), model.n0, model.n1, model.dof,
              static_cast<int>(r.time.size()), ex.run.t0, ex.run.t1);
  std::printf("  %-24s %14s %10s %14s %10s\n", "input", "max", "at t [s]", "min", "at t [s]");
  for (int k = 0; k < model.n_inputs(); ++k) {
    Eigen::Index imax, imin;
    const double vmax = r.efforts.col(k).maxCoeff(&imax);
    const double vmin = r.efforts.col(k).minCoeff(&imin);
    std::printf("  %-24s %14.6f %10.4f %14.6f %10.4f\n", model.inputs[k].label.c_str(), vmax,
                r.time[imax], vmin, r.time[imin]);
  }
  std::printf("  max constraint residual: position %.2e m, velocity %.2e, acceleration %.2e\n",
              r.residuals.col(0).maxCoeff(), r.residuals.col(1).maxCoeff(),
              r.residuals.col(2).maxCoeff());
  std::printf("  CPU time %.3f ms (%.2f us per sample)\n", 1e3 * r.cpu_seconds,
              1e6 * r.cpu_seconds / static_cast<double>(r.time.size()));
  std::filesystem::create_directories(out_dir);
  const std::string path = out_dir + "/" + name + "_inverse.csv";
  write_inverse_csv(r, path);
  std::printf("  wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string cmd = argc > 1 ? argv[1] : "demo";
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::cout << kUsage;
    return 0;
  }
  if (cmd != "demo") {
    std::cerr << "mo2d: unknown command '" << cmd << "'\n" << kUsage;
    return 2;
  }
  std::string name = "whitworth", out = "out";
  for (int k = 2; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--out" && k + 1 < argc)
      out = argv[++k];
    else if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (!a.empty() && a[0] != '-')
      name = a;
    else {
      std::cerr << "mo2d: unknown option '" << a << "'\n" << kUsage;
      return 2;
    }
  }
  try {
    return demo(name, out);
  } catch (const mo2d::Error& e) {
    std::cerr << "mo2d: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {  // file system and other library errors
    std::cerr << "mo2d: " << e.what() << "\n";
    return 1;
  }
}
