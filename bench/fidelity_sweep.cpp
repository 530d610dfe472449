// Speed against error between fidelities (issue 13, docs/reduction.md "Speed against error
// between fidelities"): for the half-bike (scenario 1) and a chain-driven four-bar, every
// fidelity of the chain at k_chain = 1e4 ... 1e8 N/m and three tolerances: CPU of the solve
// (median of the repetitions) against the error of the slow signals, low-pass filtered, against
// the reference run of the full model (unilateral spans, CVODE BDF, rtol 1e-10) at the same k.
// Writes OUT/fidelity_sweep.csv and OUT/fidelity_sweep.md; the plot: mo2d_fidelity_plot.
//   build/bench/mo2d_fidelity_sweep --out docs/img
//   build/bench/mo2d_fidelity_plot docs/img/fidelity_sweep.csv docs/img/fidelity
// --quick: the four-bar only, k = 1e4 and 1e5, one tolerance, 1 s; checks that the gear pair's
// error falls with k (1/k) and the full model's stays at its tolerance (the ctest).
#include "fidelity_sweep.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace mo2d::sweep;

// `velocities`: the scene's initial velocities for a fidelity with a chain row (inextensible:
// one independent velocity fewer); empty: the scene's own.
Fidelity chain_fidelity(const std::string& name, const std::string& integrator, bool optional,
                        const std::string& velocities = "") {
  Fidelity f{.name = name + " (" + (integrator == "cvode_bdf" ? "BDF" : "DOPRI5") + ")",
             .integrator = integrator,
             .optional = optional};
  if (name != "unilateral") f.edits = {{"loads.chains.chain.fidelity", name}};
  if (!velocities.empty()) f.edits.emplace_back("initial.velocities", velocities);
  return f;
}

// The chain's fidelities of a scene; `rigid_velocities` its initial velocities with the chain's
// row (one fewer). quasi_steady runs with dopri5 only (cvode_bdf is refused with QSS rows).
std::vector<Fidelity> chain_fidelities(const std::string& rigid_velocities) {
  return {chain_fidelity("unilateral", "cvode_bdf", false),
          chain_fidelity("unilateral", "dopri5", false),
          chain_fidelity("bilateral", "cvode_bdf", false),
          chain_fidelity("inextensible", "cvode_bdf", true, rigid_velocities),
          chain_fidelity("inextensible", "dopri5", true, rigid_velocities),
          chain_fidelity("quasi_steady", "dopri5", true, rigid_velocities)};
}

// The thesis's QSS half-bike (tests/data/half_bike_qss.yaml): the chain and the suspension
// quasi-steady, one initial velocity left.
Fidelity qss_half_bike() {
  return {.name = "QSS half-bike (DOPRI5)",
          .edits = {{"loads.chains.chain.fidelity", "quasi_steady"},
                    {"loads.torsional_springs.suspension.reduce", "quasi_steady"},
                    {"initial.velocities", "{shaft.w: 0}"}},
          .integrator = "dopri5",
          .optional = true};
}

// The net chain force T_upper - T_lower: the chain's torque on sprocket b over r_b.
Signal net_tension() {
  return {"chain tension", {{"chain.upper.tension", 1}, {"chain.lower.tension", -1}}};
}

SceneCase half_bike(const std::string& dir) {
  SceneCase s{.name = "half_bike",
              .file = dir + "/half_bike.yaml",
              .parameters = {"scenario=1"},
              .duration = 15,
              .samples = 1501,
              .sigma = 0.1};
  s.signals = {{"wheel speed", {{"wheel.w", 1}}},
               {"swing-arm angle", {{"arm.W.x", 1}, {"arm.W.y", 1}}, true, 0, 0},
               net_tension()};
  s.fidelities = chain_fidelities("{shaft.w: 0, arm.w: 0}");
  s.fidelities.push_back(qss_half_bike());
  return s;
}

// The rigid chain on fixed centres: a gear pair crank.w = (r_m / r_c) motor.w, mesh torque on
// the crank r_c (T_upper - T_lower).
Fidelity gear_pair(const std::string& integrator) {
  return {.name = std::string("gear pair (") + (integrator == "cvode_bdf" ? "BDF" : "DOPRI5") + ")",
          .edits = {{"loads.chains", ""},
                    {"gears.belt", "{body: crank, driver: motor, ratio: r_m / r_c}"},
                    {"initial.velocities", "{motor.w: 0}"}},
          .integrator = integrator,
          .signals = {{"chain tension", {{"belt.torque", 1 / 0.075}}}}};
}

SceneCase chain_fourbar(const std::string& dir) {
  SceneCase s{.name = "chain_fourbar",
              .file = dir + "/chain_fourbar.yaml",
              .duration = 3,
              .samples = 601,
              .sigma = 0.04};
  s.signals = {{"crank speed", {{"crank.w", 1}}},
               {"rocker angle", {{"coupler.B.x", 1}, {"coupler.B.y", 1}}, true, 0.4, 0},
               net_tension()};
  s.fidelities = chain_fidelities("{motor.w: 0}");
  s.fidelities.push_back(gear_pair("cvode_bdf"));
  s.fidelities.push_back(gear_pair("dopri5"));
  return s;
}

struct Row {
  std::string scene, fidelity, integrator;
  double k, rtol;
  RunResult r;
  std::vector<double> err;  // per signal, then their max
};

struct Settings {
  std::vector<double> ks{1e4, 1e5, 1e6, 1e7, 1e8};
  std::vector<double> rtols{1e-4, 1e-6, 1e-8};
  int repetitions = 3;
};

Row make_row(const SceneCase& sc, const std::string& name, const Fidelity& f, const RunSpec& spec,
             const RunResult& ref) {
  Row row{sc.name, name, f.integrator, spec.k, spec.rtol, run_case(sc, f, spec), {}};
  if (row.r.status == Status::ok && ref.status == Status::ok) {
    const auto margin = filter_margin(sc.duration / (sc.samples - 1), sc.sigma);
    double worst = 0;
    for (std::size_t i = 0; i < sc.signals.size(); ++i)
      worst =
          std::max(worst, row.err.emplace_back(relative_error(row.r.slow[i], ref.slow[i], margin)));
    row.err.push_back(worst);
  }
  std::printf("  %-22s rtol %.0e: %s", name.c_str(), spec.rtol, to_string(row.r.status));
  if (!row.err.empty())
    std::printf(", CPU %.4f s, %ld steps, error %.2e", row.r.cpu_median, row.r.steps,
                row.err.back());
  std::printf("\n");
  return row;
}

// The reference at k: the full model (the scene's first fidelity) at rtol 1e-10; its check, the
// same at rtol 1e-9 (a row "reference check": the reference's own error is below it).
std::vector<Row> sweep_scene(const SceneCase& sc, const Settings& set) {
  std::vector<Row> rows;
  for (double k : set.ks) {
    RunSpec ref_spec{.k = k,
                     .rtol = 1e-10,
                     .atol = 1e-12,
                     .integrator = "cvode_bdf",
                     .repetitions = 1,
                     .max_steps = 2000000,
                     .max_seconds = 120};
    const RunResult ref = run_case(sc, sc.fidelities.front(), ref_spec);
    std::printf("%s k = %.0e reference: %s, CPU %.3f s\n", sc.name.c_str(), k,
                to_string(ref.status), ref.cpu_median);
    if (ref.status != Status::ok) std::printf("    (%s)\n", ref.message.c_str());
    ref_spec.rtol = 1e-9;
    ref_spec.atol = 1e-11;
    rows.push_back(make_row(sc, "reference check", sc.fidelities.front(), ref_spec, ref));
    for (const Fidelity& f : sc.fidelities)
      for (double rtol : set.rtols) {
        const RunSpec spec{.k = k,
                           .rtol = rtol,
                           .atol = 1e-2 * rtol,
                           .integrator = f.integrator,
                           .repetitions = set.repetitions};
        rows.push_back(make_row(sc, f.name, f, spec, ref));
        const Status st = rows.back().r.status;
        if ((st == Status::not_available && rtol == set.rtols.front()) || st == Status::failed ||
            st == Status::budget_exceeded)
          std::printf("    (%s)\n", rows.back().r.message.c_str());
      }
  }
  return rows;
}

const char* kCsvHeader =
    "scene,fidelity,integrator,k_chain,rtol,status,cpu_median_s,cpu_min_s,steps,"
    "err_speed,err_angle,err_tension,err_max";

void write_csv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream out(path);
  out << kCsvHeader << "\n";
  for (const Row& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%s,%.0e,%.0e,%s,%.6g,%.6g,%ld", r.scene.c_str(),
                  r.fidelity.c_str(), r.integrator.c_str(), r.k, r.rtol, to_string(r.r.status),
                  r.r.cpu_median, r.r.cpu_min, r.r.steps);
    out << line;
    for (std::size_t i = 0; i < 4; ++i) {
      std::snprintf(line, sizeof line, ",%.4e", i < r.err.size() ? r.err[i] : NAN);
      out << line;
    }
    out << "\n";
  }
  std::printf("wrote %s\n", path.c_str());
}

std::string cell(const Row& r) {
  char b[96];
  if (r.r.status != Status::ok || r.err.empty()) return to_string(r.r.status);
  const double ms = 1e3 * r.r.cpu_median;
  std::snprintf(b, sizeof b, ms >= 100 ? "%.0f ms, %.1e" : "%.3g ms, %.1e", ms, r.err.back());
  return b;
}

void table_head(std::ofstream& out, const std::string& scene, const Settings& set) {
  out << "\n**" << scene << "** (CPU of the solve, median; error of the slow signals)\n\n";
  out << "| fidelity | rtol |";
  for (double k : set.ks) out << " k = 1e" << std::lround(std::log10(k)) << " N/m |";
  out << "\n|---|---|";
  for (std::size_t j = 0; j < set.ks.size(); ++j) out << "---|";
  out << "\n";
}

// One table per scene: a row per fidelity and tolerance, a column per k ("CPU, error"); the
// fidelities not available in this build listed below it.
void write_markdown(const std::vector<Row>& rows, const Settings& set, const std::string& path) {
  std::ofstream out(path);
  std::string scene, missing;
  auto flush_missing = [&] {
    if (!missing.empty()) out << "\nNot available in this build: " << missing << ".\n";
    missing.clear();
  };
  for (const Row& r : rows) {
    if (r.k != set.ks.front()) continue;
    if (r.scene != scene) {
      flush_missing();
      table_head(out, scene = r.scene, set);
    }
    if (r.r.status == Status::not_available) {
      if (r.rtol == set.rtols.front()) missing += (missing.empty() ? "" : ", ") + r.fidelity;
      continue;
    }
    char t[16];
    std::snprintf(t, sizeof t, "%.0e", r.rtol);
    out << "| " << r.fidelity << " | " << t << " |";
    for (const Row& q : rows)
      if (q.scene == r.scene && q.fidelity == r.fidelity && q.rtol == r.rtol)
        out << " " << cell(q) << " |";
    out << "\n";
  }
  flush_missing();
  std::printf("wrote %s\n", path.c_str());
}

// The ctest's checks on the quick sweep (the four-bar at k = 1e4 and 1e5): the CSV's header, the
// gear pair's error falling with k (the rigid chain is the k -> infinity limit: error ~ 1/k) and
// the full model at rtol 1e-6 near its reference.
int check_quick(const std::vector<Row>& rows, const std::string& csv) {
  int failures = 0;
  auto expect = [&](bool ok, const std::string& what) {
    std::printf("check: %s: %s\n", what.c_str(), ok ? "ok" : "FAILED");
    failures += ok ? 0 : 1;
  };
  std::ifstream in(csv);
  std::string head;
  std::getline(in, head);
  expect(head == kCsvHeader, "CSV columns " + head);
  auto err = [&](const std::string& fidelity, double k) -> double {
    for (const Row& r : rows)
      if (r.fidelity == fidelity && r.k == k && !r.err.empty()) return r.err.back();
    return NAN;
  };
  const double g4 = err("gear pair (BDF)", 1e4), g5 = err("gear pair (BDF)", 1e5);
  std::printf("gear pair error: %.3e at k = 1e4, %.3e at k = 1e5\n", g4, g5);
  expect(g5 < 0.3 * g4, "the gear pair's error falls with k like 1/k");
  const double u4 = err("unilateral (BDF)", 1e4), u5 = err("unilateral (BDF)", 1e5);
  std::printf("full model error (rtol 1e-6): %.3e at k = 1e4, %.3e at k = 1e5\n", u4, u5);
  expect(u4 < 0.1 * g4 && u5 < 0.1 * g5, "the full model nearer its reference than the gear pair");
  return failures;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  std::string out = ".", mechanisms = MO2D_MECHANISMS_DIR;
  bool quick = false;
  Settings set;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      quick = true;
    else if (a == "--out" && i + 1 < argc)
      out = argv[++i];
    else if (a == "--mechanisms" && i + 1 < argc)
      mechanisms = argv[++i];
    else if (a == "--repetitions" && i + 1 < argc)
      set.repetitions = std::stoi(argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: mo2d_fidelity_sweep [--quick] [--out DIR] [--mechanisms DIR] "
                   "[--repetitions N]\n");
      return 2;
    }
  }
  try {
    std::vector<SceneCase> scenes = {half_bike(mechanisms), chain_fourbar(mechanisms)};
    if (quick) {
      scenes = {chain_fourbar(mechanisms)};
      scenes[0].duration = 1;
      scenes[0].samples = 201;
      set = {.ks = {1e4, 1e5}, .rtols = {1e-6}, .repetitions = 1};
    }
    std::vector<Row> rows;
    for (const SceneCase& sc : scenes)
      for (Row& r : sweep_scene(sc, set)) rows.push_back(std::move(r));
    const std::string csv = out + "/fidelity_sweep.csv";
    write_csv(rows, csv);
    write_markdown(rows, set, out + "/fidelity_sweep.md");
    if (quick) return check_quick(rows, csv) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mo2d_fidelity_sweep: %s\n", e.what());
    return 1;
  }
  return 0;
}
