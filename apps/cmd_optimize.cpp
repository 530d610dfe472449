// mo2d optimize SCENE --minimize EXPR --vary NAME=LO:HI... [--subject-to EXPR]... [--starts N]
// [--max-evals N] [--xtol X] [--seed S] [--measures] [--set name=value]... [--out DIR]
// [run settings]: the parameters within bounds that minimize an expression of a run's summary
// values (mo2d/optimize.hpp, docs/design.md "Optimization"). Prints every improvement; writes
// DIR/NAME_optimized.yaml (the scene with the best values) and DIR/NAME_optimize.json (both or
// neither).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "mo2d/optimize.hpp"
#include "mo2d/output.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

struct OptimizeFlags {
  SceneOptions scene{};
  std::string minimize{};
  std::vector<std::string> vary{}, subject_to{};
  int starts = 1, max_evals = 200;
  double xtol = 1e-6;
  std::uint64_t seed = 1;
};

#ifdef MO2D_HAVE_NLOPT
using json = nlohmann::ordered_json;

std::string assignments(const std::vector<std::string>& names, const std::vector<double>& x) {
  std::string s;
  char buf[64];
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%s%s = %.10g", k ? ", " : "", names[k].c_str(), x[k]);
    s += buf;
  }
  return s;
}

json values(const std::vector<std::string>& names, const std::vector<double>& x) {
  json j = json::object();
  for (std::size_t k = 0; k < names.size(); ++k) j[names[k]] = x[k];
  return j;
}

std::string summary_json(const OptimizeFlags& f, const OptimizeOptions& o, const Scene& s,
                         const OptimizeResult& r, const std::string& scene_path) {
  json vary = json::object();
  for (std::size_t k = 0; k < o.vary.size(); ++k)
    vary[o.vary[k].name] = {{"lo", o.vary[k].lo}, {"hi", o.vary[k].hi}, {"best", r.x[k]}};
  json constraints = json::array();
  for (std::size_t k = 0; k < o.subject_to.size(); ++k)
    constraints.push_back({{"expression", o.subject_to[k]}, {"value", r.constraints[k]}});
  json starts = json::array();
  for (const OptimizeStart& st : r.starts)
    starts.push_back({{"x0", values(r.names, st.x0)},
                      {"x", values(r.names, st.x)},
                      {"objective", st.value},
                      {"violation", st.violation},
                      {"evaluations", st.evaluations},
                      {"status", st.status}});
  json params = json::object();
  for (const auto& [name, value] : r.parameters) params[name] = value;
  json set = json::object(), run = json::object();
  for (const ParameterOverride& p : o.set) set[p.name] = p.value;
  for (const RunOverride& v : o.run) run[v.key] = v.value;
  json j = {
      {"mo2d_version", MO2D_VERSION},
      {"scene", s.file},
      {"name", s.name},
      {"method", r.method},
      {"objective", {{"expression", o.minimize}, {"value", r.value}}},
      {"constraints", constraints},
      {"vary", vary},
      {"feasible", r.feasible},
      {"stop", r.stop},
      {"evaluations", r.evaluations},
      {"settings",
       {{"starts", f.starts}, {"max_evals", f.max_evals}, {"xtol", f.xtol}, {"seed", f.seed}}},
      {"starts", starts},
      {"parameters", params},
      {"overrides", {{"set", set}, {"run", run}}},
      {"optimized_scene", scene_path},
      {"warnings", r.warnings},
      {"wall_seconds", r.wall_seconds},
      {"cpu_seconds", r.cpu_seconds}};
  return j.dump(2) + "\n";
}

int optimize(const OptimizeFlags& f) {
  OptimizeOptions o;
  o.scene = f.scene.scene;
  o.minimize = f.minimize;
  o.subject_to = f.subject_to;
  o.run = f.scene.run;
  o.measures = f.scene.measures;
  o.starts = f.starts;
  o.max_evals = f.max_evals;
  o.xtol = f.xtol;
  o.seed = f.seed;
  for (const auto& s : f.scene.set) o.set.push_back(parse_override(s));
  const Scene scene = load_scene_with_overrides(f.scene);  // the scene's errors first
  try {
    for (const auto& v : f.vary) o.vary.push_back(parse_design_variable(v));
  } catch (const OptimizeInputError& e) {
    throw UsageError(e.what());
  }
  std::vector<std::string> names;
  for (const DesignVariable& v : o.vary) names.push_back(v.name);
  std::printf(
      "mo2d optimize: %s, %s over %s (%d start%s, at most %d evaluations each)\n",
      scene.name.c_str(), o.subject_to.empty() ? "BOBYQA" : "COBYLA",
      [&] {
        std::string s;
        for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
        return s;
      }()
          .c_str(),
      o.starts, o.starts == 1 ? "" : "s", o.max_evals);
  std::printf("  minimize %s\n", o.minimize.c_str());
  for (const auto& c : o.subject_to) std::printf("  subject to %s\n", c.c_str());
  o.progress = [&names](const OptimizeProgress& p) {
    if (!p.improved) return;
    std::printf("  eval %4d  start %d  objective %-16.10g%s  %s\n", p.evaluation, p.start + 1,
                p.value, p.feasible ? "" : " (infeasible)", assignments(names, p.x).c_str());
    std::fflush(stdout);
  };
  OptimizeResult r;
  try {
    r = optimize_scene(o);
  } catch (const OptimizeInputError& e) {
    throw UsageError(e.what());
  }
  for (const auto& w : r.warnings) std::fprintf(stderr, "mo2d: warning: optimize: %s\n", w.c_str());
  std::printf("  best design (%s; %d evaluations, %zu start%s, %.3g s CPU): %s\n", r.stop.c_str(),
              r.evaluations, r.starts.size(), r.starts.size() == 1 ? "" : "s", r.cpu_seconds,
              assignments(names, r.x).c_str());
  std::printf("  objective %.12g\n", r.value);
  for (std::size_t k = 0; k < o.subject_to.size(); ++k)
    std::printf("  constraint %zu: %s: %.6g (%s)\n", k + 1, o.subject_to[k].c_str(),
                r.constraints[k], r.constraints[k] <= 0 ? "holds" : "within tolerance or violated");
  const std::string yaml_path = output_path(f.scene, scene, "optimized.yaml");
  std::string header = "# mo2d optimize: the best design found for " + scene.file + " (" +
                       assignments(names, r.x) + "): minimize " + o.minimize;
  for (const auto& c : o.subject_to) header += " subject to " + c;
  char buf[64];
  std::snprintf(buf, sizeof buf, " = %.12g (%s)\n", r.value, r.stop.c_str());
  OutputSet out;
  out.add(yaml_path, header + buf + r.scene_text);
  out.add(output_path(f.scene, scene, "optimize.json"), summary_json(f, o, scene, r, yaml_path));
  out.commit();
  for (const auto& path : out.paths()) std::printf("  wrote %s\n", path.c_str());
  return 0;
}
#else
int optimize(const OptimizeFlags&) {
  throw Error(
      "optimize: this mo2d was built without NLopt (install libnlopt-dev and configure again, "
      "docs/design.md)");
}
#endif

}  // namespace

Command add_optimize_command(CLI::App& app) {
  auto f = std::make_shared<OptimizeFlags>();
  CLI::App* sub = app.add_subcommand(
      "optimize",
      "Parameters within bounds that minimize an expression of a run's summary values (NLopt; "
      "docs/design.md)");
  add_scene_options(sub, f->scene, true, RunFlags::all);
  sub->add_option("--minimize", f->minimize,
                  "objective: an expression of the parameters and the run's summary values "
                  "(peak.COL, rms.COL, max.COL, min.COL, mean.COL, peak_to_peak.COL, "
                  "flywheel.INPUT, ...)")
      ->required();
  sub->add_option("--vary", f->vary, "a parameter to vary within bounds: NAME=LO:HI; repeatable")
      ->required()
      ->allow_extra_args(false);
  sub->add_option("--subject-to", f->subject_to,
                  "a constraint: G <= H, G >= H, or G (meaning G <= 0); repeatable (COBYLA)")
      ->allow_extra_args(false);
  sub->add_option("--starts", f->starts,
                  "starts: the scene's values, then seeded random points in the bounds")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  sub->add_option("--max-evals", f->max_evals, "evaluations (runs) per start")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  sub->add_option("--xtol", f->xtol,
                  "stop a start when its step is below XTOL times each parameter's range")
      ->check(finite_positive())
      ->capture_default_str();
  sub->add_option("--seed", f->seed, "seed of the random starts (std::mt19937_64)")
      ->capture_default_str();
  sub->add_flag("--measures", f->scene.measures,
                "add the frame's shaking force and moment and the bearing loads to the run's "
                "columns (frame.shaking.F, J.load, ...)");
  return {sub, [f] { return optimize(*f); }};
}

}  // namespace mo2d::cli
