// The N-scaling figure of docs/performance.md ("Scaling"): cost per evaluation against N on the
// IFToMM N-four-bar, log-log, from the CSV that mo2d_peers_bench --csv writes (measured numbers;
// docs/img/n_scaling.csv is the committed run):
//   taskset -c 1 build/bench/mo2d_peers_bench --max-n 1000 --csv docs/img/n_scaling.csv
//   build/bench/mo2d_scaling_plot docs/img/n_scaling.csv docs/img/n_scaling.png
// mo2d: one forward_accelerations (sparse and dense linear algebra); MuJoCo: one mj_step (Euler:
// one mj_forward); Box2D: one b2World::Step (8 velocity, 3 position iterations).
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mo2d/render.hpp"

namespace {

using namespace mo2d;

std::vector<std::vector<double>> read_csv(const std::string& path, std::vector<std::string>& head) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::string line, cell;
  std::getline(f, line);
  std::istringstream h(line);
  while (std::getline(h, cell, ',')) head.push_back(cell);
  std::vector<std::vector<double>> cols(head.size());
  while (std::getline(f, line)) {
    std::istringstream r(line);
    for (std::size_t k = 0; k < head.size() && std::getline(r, cell, ','); ++k)
      cols[k].push_back(cell == "nan" ? NAN : std::stod(cell));
  }
  return cols;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: mo2d_scaling_plot COSTS.csv OUT.png\n");
    return 2;
  }
  try {
    std::vector<std::string> head;
    const auto cols = read_csv(argv[1], head);
    auto col = [&](const std::string& name) {
      for (std::size_t k = 0; k < head.size(); ++k)
        if (head[k] == name) {
          std::vector<double> us = cols[k];
          for (double& v : us) v *= 1e6;
          return us;
        }
      throw std::runtime_error(std::string(argv[1]) + ": no column " + name);
    };
    Plot p;
    p.title = "IFToMM N-four-bar: CPU per evaluation (one core)";
    p.x = {"N (four-bar loops)", true, {}};
    p.y = {"CPU per evaluation (µs)", true, {}};
    const std::vector<double> n = cols.at(0);
    p.series.push_back({"mo2d, sparse (forward_accelerations)", n, col("mo2d_eval_sparse_s")});
    p.series.push_back({"mo2d, dense", n, col("mo2d_eval_dense_s")});
    p.series.push_back({"MuJoCo 2.2.2 (mj_step, Euler)", n, col("mujoco_step_s")});
    p.series.push_back({"Box2D 2.4.1 (Step, 8+3 iterations)", n, col("box2d_step_s")});
    for (Series& s : p.series) s.markers = true;
    write_plot(p, argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mo2d_scaling_plot: %s\n", e.what());
    return 1;
  }
  return 0;
}
