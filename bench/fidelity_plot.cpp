// The speed-against-error figures of docs/reduction.md ("Speed against error between
// fidelities"): CPU of the solve against the error of the slow signals, log-log, one colour per
// fidelity, one line per (fidelity, k) through its tolerances, from the CSV mo2d_fidelity_sweep
// writes; per scene PREFIX_SCENE.png, and PREFIX_SCENE_cost.png: CPU against k at rtol 1e-6:
//   build/bench/mo2d_fidelity_plot docs/img/fidelity_sweep.csv docs/img/fidelity
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mo2d/render.hpp"

namespace {

using namespace mo2d;

using Record = std::map<std::string, std::string>;

std::vector<Record> read_csv(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::string line, cell;
  std::getline(f, line);
  std::vector<std::string> head;
  std::istringstream h(line);
  while (std::getline(h, cell, ',')) head.push_back(cell);
  std::vector<Record> rows;
  while (std::getline(f, line)) {
    std::istringstream r(line);
    Record rec;
    for (std::size_t k = 0; k < head.size() && std::getline(r, cell, ','); ++k) rec[head[k]] = cell;
    rows.push_back(rec);
  }
  return rows;
}

double num(const Record& r, const std::string& key) {
  const auto it = r.find(key);
  if (it == r.end()) throw std::runtime_error("the CSV has no column " + key);
  return it->second == "nan" ? NAN : std::stod(it->second);
}

// One series per (fidelity, k) in the order of the CSV, coloured by fidelity, the fidelity
// labelled once; explicit integrators dashed.
Plot scene_plot(const std::vector<Record>& rows, const std::string& scene) {
  Plot p;
  p.title = scene + ": CPU of the solve against the error of the slow signals";
  p.x = {"error of the slow signals (relative to their range)", true, {}};
  p.y = {"CPU of the solve (s)", true, {}};
  p.width = 900;
  p.height = 560;
  std::map<std::string, std::size_t> colour;
  std::string last;
  for (const Record& r : rows) {
    if (r.at("scene") != scene || r.at("status") != "ok" || r.at("fidelity") == "reference check")
      continue;
    const std::string& f = r.at("fidelity");
    const std::string key = f + "@" + r.at("k_chain");
    if (key != last) {
      const bool first = !colour.count(f);
      if (first) colour.emplace(f, colour.size());
      Series s{.label = first ? f : "",
               .colour = okabe_ito()[colour.at(f) % okabe_ito().size()],
               .dashed = r.at("integrator") != "cvode_bdf",
               .markers = true};
      p.series.push_back(s);
      last = key;
    }
    p.series.back().x.push_back(num(r, "err_max"));
    p.series.back().y.push_back(num(r, "cpu_median_s"));
  }
  return p;
}

// CPU against k at one tolerance, one line per fidelity: a model without k (the gear pair, the
// inextensible chain) is flat.
Plot cost_plot(const std::vector<Record>& rows, const std::string& scene, const std::string& rtol) {
  Plot p;
  p.title = scene + ": CPU of the solve against the chain's stiffness (rtol " + rtol + ")";
  p.x = {"chain stiffness k (N/m)", true, {}};
  p.y = {"CPU of the solve (s)", true, {}};
  p.width = 900;
  p.height = 500;
  std::map<std::string, std::size_t> index;
  for (const Record& r : rows) {
    if (r.at("scene") != scene || r.at("rtol") != rtol || r.at("fidelity") == "reference check" ||
        r.at("status") == "not available in this build")
      continue;
    const std::string& f = r.at("fidelity");
    if (!index.count(f)) {
      index.emplace(f, p.series.size());
      p.series.push_back(
          {.label = f, .dashed = r.at("integrator") != "cvode_bdf", .markers = true});
    }
    Series& s = p.series[index.at(f)];
    s.x.push_back(num(r, "k_chain"));
    s.y.push_back(r.at("status") == "ok" ? num(r, "cpu_median_s") : NAN);
  }
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: mo2d_fidelity_plot SWEEP.csv OUT_PREFIX\n");
    return 2;
  }
  try {
    const std::vector<Record> rows = read_csv(argv[1]);
    std::vector<std::string> scenes;
    for (const Record& r : rows)
      if (scenes.empty() || scenes.back() != r.at("scene")) scenes.push_back(r.at("scene"));
    for (const std::string& s : scenes) {
      const std::string out = std::string(argv[2]) + "_" + s + ".png";
      write_plot(scene_plot(rows, s), out);
      const std::string cost = std::string(argv[2]) + "_" + s + "_cost.png";
      write_plot(cost_plot(rows, s, "1e-06"), cost);
      std::printf("wrote %s\nwrote %s\n", out.c_str(), cost.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mo2d_fidelity_plot: %s\n", e.what());
    return 1;
  }
  return 0;
}
