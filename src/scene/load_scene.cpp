// A scene document -> Scene: parameters (dependency order), tables, the root system, motion,
// initial state, efforts and run settings.
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "load_system.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/table.hpp"
#include "model/suggest.hpp"
#include "reader.hpp"

namespace mo2d {

namespace scene_detail {
namespace {

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
  });
}

bool is_reserved(const std::string& s) {
  return s == "t" || s == "pi" || Expression::is_function(s);
}

// One parameter definition: its text and where it came from (a YAML node or --set). Its move
// assignment may throw (YAML::Node has only a copy assignment, which allocates): harmless here, a
// throw while reading the parameters leaves no scene.
struct Definition {  // NOLINT(bugprone-exception-escape)
  YAML::Node node{};
  std::string text{};
  bool from_command_line = false;
  Expression expr{};
  int state = 0;  // 0 new, 1 being evaluated, 2 done
};

// The tables' names as functions that refuse to be called: parameters are evaluated before the
// tables are read (a table's scale may use them), so a parameter that calls one is an error at its
// line rather than an unknown function.
std::vector<NamedFunction> table_stubs(const YAML::Node& tables) {
  std::vector<NamedFunction> out;
  if (!tables.IsDefined() || !tables.IsMap()) return out;
  for (auto it = tables.begin(); it != tables.end(); ++it) {
    if (!it->first.IsScalar()) continue;
    const std::string name = it->first.Scalar();
    out.push_back({name, [name](Jet) -> Jet {
                     throw Error("table '" + name +
                                 "' is used in a parameter: parameters are constants evaluated "
                                 "before the tables are read; call the table where the value is "
                                 "used");
                   }});
  }
  return out;
}

void read_parameters(Reader& r, const YAML::Node& node, const YAML::Node& tables,
                     std::span<const ParameterOverride> overrides, Scene& scene) {
  std::map<std::string, Definition> defs;
  std::vector<std::string> order;
  for (const auto& [key, value] : r.entries(node, "parameters")) {
    const std::string& name = key.Scalar();
    if (!is_identifier(name) || is_reserved(name))
      r.fail(key, "parameter '" + name +
                      "': a parameter name is a letter or '_' followed by "
                      "letters, digits or '_', and not t, pi or a function name");
    if (!value.IsScalar())
      r.fail(value, "parameter '" + name + "': expected a number or an expression, got " +
                        type_name(value));
    defs[name] = Definition{value, value.Scalar(), false, {}, 0};
    order.push_back(name);
  }
  r.parameter_names = order;
  for (const auto& o : overrides) {
    auto it = defs.find(o.name);
    if (it == defs.end())
      throw SceneError(Location{"--set", 0, 0}, "'" + o.name + "' is not a parameter of " + r.file +
                                                    did_you_mean(o.name, order));
    it->second.text = o.value;
    it->second.from_command_line = true;
  }
  auto fail = [&](const Definition& d, const std::string& name, const std::string& what,
                  int column) {
    if (d.from_command_line)
      throw SceneError(Location{"--set", 0, 0}, name + "=" + d.text + ": " + what);
    if (column > 0)
      r.fail_expression(d.node, ExpressionError(what, column), "parameter '" + name + "'");
    r.fail(d.node, "parameter '" + name + "': " + what);
  };
  const std::vector<NamedFunction> stubs = table_stubs(tables);
  for (auto& [name, d] : defs) {
    try {
      d.expr = Expression::parse(d.text, stubs);
    } catch (const ExpressionError& e) {
      fail(d, name, e.what(), e.column());
    }
  }
  std::vector<std::string> stack;
  std::function<void(const std::string&)> evaluate = [&](const std::string& name) {
    Definition& d = defs[name];
    if (d.state == 2) return;
    if (d.state == 1) {
      std::string cycle;
      auto it = std::find(stack.begin(), stack.end(), name);
      for (; it != stack.end(); ++it) cycle += *it + " -> ";
      fail(defs[name], name, "parameters depend on each other in a cycle: " + cycle + name, 0);
    }
    d.state = 1;
    stack.push_back(name);
    for (const auto& n : d.expr.names())
      if (defs.count(n)) evaluate(n);
    try {
      d.expr.bind(
          [&](const std::string& n) {
            if (n == "t") throw ExpressionError("a parameter is a constant: it may not use t", 0);
            return r.parameter_binding(n);
          },
          order);
    } catch (const ExpressionError& e) {
      fail(d, name, e.what(), e.column());
    }
    double v = 0;
    try {
      v = d.expr.evaluate().v;
    } catch (const Error& e) {  // a table called (table_stubs)
      fail(d, name, e.what(), 0);
    }
    if (!std::isfinite(v)) fail(d, name, "the value is not a finite number", 0);
    r.parameters[name] = v;
    scene.parameters.emplace_back(name, v);
    stack.pop_back();
    d.state = 2;
  };
  for (const auto& name : order) evaluate(name);
}

void read_motion(const Reader& r, const YAML::Node& node, Scene& scene) {
  for (const auto& [key, value] : r.entries(node, "motion")) {
    const std::string label = key.Scalar();
    auto e = r.time_function(value, "motion." + label);
    scene.motion.push_back({label, [e](Jet t) { return e->evaluate({}, t); }});
    scene.labels.push_back({label, LabelUse::Kind::coordinate, r.at(key)});
  }
}

void read_initial(const Reader& r, const YAML::Node& node, Scene& scene) {
  if (!node.IsDefined() || node.IsNull()) return;
  r.check_keys(node, {"positions", "velocities"}, "initial");
  for (const auto& [key, value] : r.entries(node["positions"], "initial.positions")) {
    scene.initial.positions.emplace_back(key.Scalar(),
                                         r.number(value, "initial.positions." + key.Scalar()));
    scene.labels.push_back({key.Scalar(), LabelUse::Kind::coordinate, r.at(key)});
  }
  for (const auto& [key, value] : r.entries(node["velocities"], "initial.velocities")) {
    scene.initial.velocities.emplace_back(key.Scalar(),
                                          r.number(value, "initial.velocities." + key.Scalar()));
    scene.labels.push_back({key.Scalar(), LabelUse::Kind::rate, r.at(key)});
  }
}

void read_efforts(const Reader& r, const YAML::Node& node, Scene& scene) {
  for (const auto& [key, value] : r.entries(node, "efforts")) {
    scene.efforts.emplace_back(key.Scalar(), state_law(r, value, "efforts." + key.Scalar(),
                                                       key.Scalar(), &scene.law_labels));
    scene.labels.push_back({key.Scalar(), LabelUse::Kind::input, r.at(key)});
  }
}

// controllers: {input: {coordinate, reference, kp, kd, feed_forward: inverse | expression of t}}
void read_controllers(const Reader& r, const YAML::Node& node, Scene& scene) {
  for (const auto& [key, value] : r.entries(node, "controllers")) {
    const std::string what = "controllers." + key.Scalar();
    r.check_keys(value, {"coordinate", "rate", "reference", "kp", "kd", "feed_forward"}, what);
    SceneController c;
    c.input = key.Scalar();
    c.where = r.at(key);
    const YAML::Node coordinate = r.required(value, "coordinate", what);
    c.control.coordinate = r.string(coordinate, what + ".coordinate");
    scene.labels.push_back({c.control.coordinate, LabelUse::Kind::coordinate, r.at(coordinate)});
    if (value["rate"].IsDefined()) {
      c.control.rate = r.string(value["rate"], what + ".rate");
      scene.labels.push_back({c.control.rate, LabelUse::Kind::rate, r.at(value["rate"])});
    }
    auto ref = r.time_function(r.required(value, "reference", what), what + ".reference");
    c.control.reference = [ref](Jet t) { return ref->evaluate({}, t); };
    c.control.kp = r.number_or(value, "kp", 0.0, what);
    c.control.kd = r.number_or(value, "kd", 0.0, what);
    for (const char* gain : {"kp", "kd"})
      if (value[gain].IsDefined() && r.number(value[gain], what + "." + gain) < 0)
        r.fail(value[gain], what + "." + gain + ": must be >= 0");
    if (const YAML::Node ff = value["feed_forward"]; ff.IsDefined()) {
      if (ff.IsScalar() && ff.Scalar() == "inverse") {
        c.feed_forward_inverse = true;
      } else {
        auto e = r.time_function(ff, what + ".feed_forward");
        c.control.feed_forward = [e](double t) { return e->evaluate({}, Jet(t)).v; };
      }
    }
    for (const auto& [label, law] : scene.efforts)
      if (label == c.input)
        r.fail(key, what + ": input '" + c.input +
                        "' has an effort too (give its open-loop part as feed_forward)");
    scene.labels.push_back({c.input, LabelUse::Kind::input, r.at(key)});
    scene.controllers.push_back(std::move(c));
  }
}

template <class E>
E choice(const Reader& r, const YAML::Node& node, const std::string& what,
         const std::vector<std::pair<std::string, E>>& options) {
  const std::string s = r.string(node, what);
  std::vector<std::string> names;
  for (const auto& [n, v] : options) {
    if (n == s) return v;
    names.push_back(n);
  }
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  r.fail(node, what + ": unknown value '" + s + "'" + did_you_mean(s, names) +
                   "; expected one of: " + list);
}

// tables: {name: {file, x, y, interpolation, extrapolate, scale_x, scale_y}}, each a function of
// one argument in the expressions read after it (every expression but the parameters').
void read_tables(Reader& r, const YAML::Node& node) {
  const std::filesystem::path dir = std::filesystem::path(r.file).parent_path();
  for (const auto& [key, value] : r.entries(node, "tables")) {
    const std::string name = key.Scalar();
    const std::string what = "table '" + name + "'";
    if (!is_identifier(name) || is_reserved(name))
      r.fail(key, what +
                      ": a table name is a letter or '_' followed by letters, digits or '_', and "
                      "not t, pi or a function name");
    if (r.parameters.count(name)) r.fail(key, what + ": a parameter has the same name");
    r.check_keys(value, {"file", "x", "y", "interpolation", "extrapolate", "scale_x", "scale_y"},
                 what);
    const YAML::Node file = r.required(value, "file", what);
    std::filesystem::path path = r.string(file, what + ".file");
    if (path.is_relative()) path = dir / path;
    CsvColumns columns;
    if (value["x"].IsDefined()) columns.x = r.string(value["x"], what + ".x");
    if (value["y"].IsDefined()) columns.y = r.string(value["y"], what + ".y");
    columns.scale_x = r.number_or(value, "scale_x", 1.0, what);
    if (!(columns.scale_x > 0))
      r.fail(value["scale_x"], what + ".scale_x: must be > 0 (x must keep increasing)");
    columns.scale_y = r.number_or(value, "scale_y", 1.0, what);
    TableOptions options;
    if (value["interpolation"].IsDefined())
      options.interpolation = choice<Interpolation>(
          r, value["interpolation"], what + ".interpolation",
          {{"cubic", Interpolation::cubic}, {"linear", Interpolation::linear}});
    if (value["extrapolate"].IsDefined())
      options.extrapolation = choice<Extrapolation>(r, value["extrapolate"], what + ".extrapolate",
                                                    {{"error", Extrapolation::error},
                                                     {"clamp", Extrapolation::clamp},
                                                     {"periodic", Extrapolation::periodic}});
    std::shared_ptr<const LookupTable> table;
    try {
      table = std::make_shared<const LookupTable>(
          read_table_csv(path.string(), name, columns, options));
    } catch (const Error& e) {  // "cam.csv:7: table 'cam': x must increase ..."
      r.fail(file, e.what());
    }
    r.functions.push_back({name, [table](Jet x) { return (*table)(x); }});
    r.tables.emplace_back(name, table);
  }
}

void read_run(const Reader& r, const YAML::Node& node, RunSettings& run,
              std::vector<std::pair<std::string, Location>>& elements) {
  if (!node.IsDefined() || node.IsNull()) return;
  r.check_keys(
      node,
      {"solve",       "t0",         "duration",       "samples",  "tolerance",      "integrator",
       "formulation", "rtol",       "atol",           "step",     "outputs",        "max_steps",
       "max_seconds", "max_memory", "linear_algebra", "accuracy", "error_estimate", "max_events",
       "zeno_time",   "zeno_speed", "baumgarte_rate"},
      "run");
  // where each run key is written: errors found when the run's options are checked against the
  // model (check_scene_options) are reported there
  for (const auto& [key, value] : r.entries(node, "run"))
    elements.emplace_back("run." + key.Scalar(), r.at(value));
  if (node["solve"].IsDefined())
    run.solve = choice<Solve>(r, node["solve"], "run.solve",
                              {{"inverse", Solve::inverse}, {"forward", Solve::forward}});
  run.t0 = r.number_or(node, "t0", run.t0, "run");
  run.duration = r.number_or(node, "duration", run.duration, "run");
  if (!(run.duration > 0)) r.fail(node["duration"], "run.duration: must be > 0 s");
  if (node["samples"].IsDefined()) {
    run.samples = r.integer(node["samples"], "run.samples");
    if (run.samples < 2) r.fail(node["samples"], "run.samples: must be >= 2");
  }
  auto positive = [&](const char* key, double& v) {
    v = r.number_or(node, key, v, "run");
    if (!(v > 0)) r.fail(node[key], std::string("run.") + key + ": must be > 0");
  };
  positive("tolerance", run.tolerance);
  positive("rtol", run.rtol);
  positive("atol", run.atol);
  positive("step", run.step);
  {  // the time grid, with the duration as written (t0 + duration may round it away)
    const double n = run.samples > 0 ? run.samples : 101;  // the smaller default: wider spacing
    const double spacing = run.duration / (n - 1);
    const double tmax = std::max(std::abs(run.t0), std::abs(run.t0 + run.duration));
    if (!std::isfinite(run.t0 + run.duration))
      r.fail(node[node["duration"].IsDefined() ? "duration" : "t0"],
             "run: t0 + duration is not finite");
    if (!(spacing >= kTimeResolution * tmax)) {
      std::ostringstream m;
      m << "run.t0: t0 = " << run.t0 << " s: samples " << spacing
        << " s apart are not resolved by double precision there (doubles are "
        << std::nextafter(tmax, INFINITY) - tmax << " s apart near t = " << tmax
        << " s; the spacing must be at least " << kTimeResolution * tmax
        << " s): use a t0 closer to 0, or fewer samples";
      r.fail(node[node["t0"].IsDefined() ? "t0" : "duration"], m.str());
    }
  }
  positive("max_seconds", run.max_seconds);
  positive("max_memory", run.max_memory);
  if (node["max_steps"].IsDefined()) {
    run.max_steps = r.integer(node["max_steps"], "run.max_steps");
    if (run.max_steps < 1) r.fail(node["max_steps"], "run.max_steps: must be >= 1");
  }
  if (node["integrator"].IsDefined())
    run.integrator = choice<Integrator>(r, node["integrator"], "run.integrator",
                                        {{"cvode_bdf", Integrator::cvode_bdf},
                                         {"cvode_adams", Integrator::cvode_adams},
                                         {"rk4", Integrator::rk4},
                                         {"dopri5", Integrator::dopri5},
                                         {"erk6", Integrator::erk6},
                                         {"erk8", Integrator::erk8},
                                         {"baumgarte", Integrator::baumgarte}});
  if (node["formulation"].IsDefined())
    run.formulation =
        choice<Formulation>(r, node["formulation"], "run.formulation",
                            {{"augmented_lagrangian", Formulation::augmented_lagrangian},
                             {"lagrange", Formulation::lagrange},
                             {"null_space", Formulation::null_space}});
  if (node["linear_algebra"].IsDefined())
    run.linear_algebra = choice<LinearAlgebra>(r, node["linear_algebra"], "run.linear_algebra",
                                               {{"automatic", LinearAlgebra::automatic},
                                                {"dense", LinearAlgebra::dense},
                                                {"sparse", LinearAlgebra::sparse}});
  if (node["error_estimate"].IsDefined())
    run.error_estimate = choice<ErrorEstimate>(r, node["error_estimate"], "run.error_estimate",
                                               {{"automatic", ErrorEstimate::automatic},
                                                {"on", ErrorEstimate::on},
                                                {"off", ErrorEstimate::off}});
  read_accuracy(r, node, run);
  if (node["outputs"].IsDefined()) {
    run.csv = run.json = false;
    for (const auto& o : node["outputs"].IsSequence() ? node["outputs"] : YAML::Node()) {
      const std::string s = r.string(o, "run.outputs");
      if (s == "csv")
        run.csv = true;
      else if (s == "json")
        run.json = true;
      else
        r.fail(o, "run.outputs: unknown output '" + s + "'; expected csv or json");
    }
    if (!node["outputs"].IsSequence())
      r.fail(node["outputs"], "run.outputs: expected a list such as [csv, json]");
  }
}

// A run setting from the command line, read by read_run on top of the scene's: its errors (and
// those check_scene_options finds later for that key) are reported at "--KEY".
void apply_run_override(const Reader& r, const RunOverride& o, Scene& scene) {
  const std::string flag = run_override_flag(o.key);
  const std::vector<std::string> keys(std::begin(kRunOverrideKeys), std::end(kRunOverrideKeys));
  if (std::find(keys.begin(), keys.end(), o.key) == keys.end())
    throw SceneError(
        Location{flag, 0, 0},
        "'" + o.key + "' is not a run setting a run can override" + did_you_mean(o.key, keys));
  Reader at_flag = r;
  at_flag.file = flag;
  at_flag.source = {};
  YAML::Node node(YAML::NodeType::Map);
  node[o.key] = o.value;
  std::erase_if(scene.elements, [&](const auto& e) { return e.first == "run." + o.key; });
  read_run(at_flag, node, scene.run, scene.elements);
}

}  // namespace
}  // namespace scene_detail

std::string run_override_flag(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

Scene parse_scene(std::string_view yaml, const std::string& file_name,
                  std::span<const ParameterOverride> overrides,
                  std::span<const RunOverride> run_overrides) {
  using namespace scene_detail;
  Reader r;
  r.file = file_name;
  r.source = yaml;
  Scene scene;
  scene.file = file_name;
  try {
    const YAML::Node doc = YAML::Load(std::string(yaml));
    if (!doc.IsMap())
      throw SceneError(Location{file_name, 1, 1},
                       std::string("a scene is a map of keys (name, bodies, joints, ...), got ") +
                           type_name(doc));
    r.check_keys(doc, {"name",          "parameters",  "tables",    "ground", "bodies",
                       "joints",        "coordinates", "gears",     "racks",  "constraints",
                       "loads",         "subsystems",  "instances", "motion", "initial",
                       "efforts",       "controllers", "run",       "points", "outputs",
                       "transmissions", "design",      "contacts"},
                 "scene");
    scene.name = doc["name"].IsDefined() ? r.string(doc["name"], "name") : "scene";
    read_parameters(r, doc["parameters"], doc["tables"], overrides, scene);
    read_tables(r, doc["tables"]);
    scene.system = System(scene.name);
    Subsystems library;
    if (doc["subsystems"].IsDefined()) {
      r.entries(doc["subsystems"], "subsystems");  // a map of named blocks
      library.definitions.reset(doc["subsystems"]);
    }
    SystemInfo info = read_system(r, doc, scene.system, true, library);
    read_motion(r, doc["motion"], scene);
    read_initial(r, doc["initial"], scene);
    read_efforts(r, doc["efforts"], scene);
    read_controllers(r, doc["controllers"], scene);
    read_outputs(r, doc["outputs"], info, scene);
    read_design(r, doc["design"], info, scene);
    read_contacts(r, doc["contacts"], info, scene);
    scene.elements = std::move(info.elements);
    scene.law_labels.insert(scene.law_labels.end(), info.law_labels.begin(), info.law_labels.end());
    scene.expression_labels = std::move(info.labels);
    read_run(r, doc["run"], scene.run, scene.elements);
    read_contact_run(r, doc["run"], scene);
    check_accuracy_overrides(run_overrides, scene.run.accuracy > 0);
    for (const RunOverride& o : run_overrides) apply_run_override(r, o, scene);
  } catch (const YAML::DeepRecursion& e) {  // yaml-cpp's depth guard (its message: "bad file")
    throw SceneError(Location{file_name, e.mark.line + 1, e.mark.column + 1},
                     "YAML: nested too deeply (" + std::to_string(e.depth()) + " levels)");
  } catch (const YAML::Exception& e) {  // syntax errors (and any misuse of a node)
    Location l{file_name, e.mark.is_null() ? 0 : e.mark.line + 1,
               e.mark.is_null() ? 0 : e.mark.column + 1};
    throw SceneError(l, "YAML: " + e.msg);
  }
  return scene;
}

Scene load_scene(const std::string& path, std::span<const ParameterOverride> overrides,
                 std::span<const RunOverride> run_overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(Location{path, 0, 0}, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path, overrides, run_overrides);
}

}  // namespace mo2d
