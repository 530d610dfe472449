// From a loaded Scene to a Model and run options; errors that need the model are reported at the
// line of the scene that caused them.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "mo2d/expression.hpp"
#include "mo2d/scene.hpp"
#include "model/suggest.hpp"

namespace mo2d {

std::string Location::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

SceneError::SceneError(const Location& where, const std::string& message)
    : Error(where.str() + ": " + message), where_(where), message_(message) {}

ParameterOverride parse_override(std::string_view text) {
  const size_t eq = text.find('=');
  auto trim = [](std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return std::string(s);
  };
  if (eq == std::string_view::npos || trim(text.substr(0, eq)).empty() ||
      trim(text.substr(eq + 1)).empty())
    throw Error("--set " + std::string(text) + ": expected name=value");
  return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
}

namespace {

const Location* element_location(const Scene& s, const std::string& element,
                                 const std::string& message) {
  // an unknown quantity in a law: where the law writes it
  const std::string unknown = "unknown quantity '";
  if (const size_t at = message.find(unknown); at != std::string::npos) {
    const size_t from = at + unknown.size(), to = message.find('\'', from);
    const std::string key = element + "/" + message.substr(from, to - from);
    for (const auto& [name, where] : s.law_labels)
      if (name == key) return &where;
  }
  for (const auto& [name, where] : s.elements)
    if (name == element) return &where;
  // otherwise the first element the message names ("coordinate 'crank.angle': ...")
  for (const auto& [name, where] : s.elements)
    if (message.find("'" + name + "'") != std::string::npos) return &where;
  return nullptr;
}

void check_labels(const Scene& s, const Model& m) {
  const std::vector<std::string> inputs = m.input_labels();
  for (const auto& use : s.labels) {
    const std::vector<std::string>* names = nullptr;
    bool found = false;
    const char* what = "";
    switch (use.kind) {
      case LabelUse::Kind::coordinate:
        found = m.coordinate_index.count(use.label) > 0;
        names = &m.coordinate_labels;
        what = "coordinate";
        break;
      case LabelUse::Kind::rate:
        found = m.rate_index.count(use.label) > 0;
        names = &m.rate_labels;
        what = "quasi-velocity";
        break;
      case LabelUse::Kind::input:
        found = std::find(inputs.begin(), inputs.end(), use.label) != inputs.end();
        names = &inputs;
        what = "input";
        break;
    }
    if (found) continue;
    std::string extra;
    if (use.kind == LabelUse::Kind::coordinate && m.fixed_coordinates.count(use.label))
      extra = " (its node is joined to the ground)";
    throw SceneError(use.where, std::string("unknown ") + what + " '" + use.label + "'" + extra +
                                    did_you_mean(use.label, *names));
  }
}

}  // namespace

Model build_scene_model(const Scene& scene, const BuildOptions& options) {
  Model m;
  try {
    m = build_model(scene.system, options);
    for (const auto& [name, law] : scene.outputs.columns)  // their quantities, before any run
      compile_law(m, law, "outputs.columns." + name, name);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {
    // a label of a constraint expression, refused by the constraint ("constraint 'c': ...")
    const std::string_view what = e.what();
    for (const auto& u : scene.expression_labels)
      if (u.label == e.element() && what.starts_with("constraint '" + u.element + "':"))
        throw SceneError(u.where, e.what());
    const Location* where = element_location(scene, e.element(), e.what());
    throw SceneError(where ? *where : Location{scene.file, 0, 0}, e.what());
  }
  check_labels(scene, m);
  return m;
}

InverseOptions inverse_options(const Scene& scene) {
  InverseOptions o;
  o.t0 = scene.run.t0;
  o.t1 = scene.run.t0 + scene.run.duration;
  o.samples = scene.run.samples > 0 ? scene.run.samples : 501;
  o.position_tolerance = scene.run.tolerance;
  o.max_seconds = scene.run.max_seconds;
  o.max_memory = scene.run.max_memory;
  return o;
}

namespace {

// The controllers' laws into o.efforts; the feed-forward from inverse dynamics is shared by the
// controllers that ask for it (their references prescribe the motion).
void add_controllers(const Scene& scene, const Model& model, ForwardOptions& o) {
  std::vector<Prescribed> references;
  for (const SceneController& c : scene.controllers)
    if (c.feed_forward_inverse) references.push_back({c.control.coordinate, c.control.reference});
  std::vector<std::function<double(double)>> ff;
  if (!references.empty()) {
    try {
      InverseOptions io = inverse_options(scene);
      ff = efforts_from_inverse(model, references, io);
    } catch (const Error& e) {
      throw SceneError(scene.controllers.front().where,
                       std::string("controllers: feed_forward: inverse: ") + e.what());
    }
  }
  for (const SceneController& c : scene.controllers) {
    PdControl pd = c.control;
    for (size_t k = 0; k < model.inputs.size(); ++k)
      if (model.inputs[k].label == c.input) {
        if (c.feed_forward_inverse) pd.feed_forward = ff[k];
        o.efforts[k] = pd_control(pd);
        try {
          (void)compile_law(model, o.efforts[k], "controllers." + c.input, c.input);
        } catch (const Error& e) {
          throw SceneError(c.where, e.what());
        }
      }
  }
}

}  // namespace

std::vector<TrackingError> tracking_errors(const Scene& scene, const Model& model,
                                           const Trajectory& r) {
  std::vector<TrackingError> out;
  for (const SceneController& c : scene.controllers) {
    TrackingError e{c.input, c.control.coordinate};
    // by the model's index: the coordinate may be an alias (a merged node's label)
    const Eigen::VectorXd x = r.q0.col(model.coordinate(c.control.coordinate));
    for (Eigen::Index k = 0; k < r.time.size(); ++k) {
      const double err = x[k] - (c.control.reference ? c.control.reference(Jet(r.time[k])).v : 0);
      if (std::abs(err) > std::abs(e.max_error) || k == 0) {
        e.max_error = err;
        e.t_max = r.time[k];
      }
      e.final_error = err;
    }
    out.push_back(e);
  }
  return out;
}

ForwardOptions forward_options(const Scene& scene, const Model& model) {
  ForwardOptions o;
  o.t0 = scene.run.t0;
  o.t1 = scene.run.t0 + scene.run.duration;
  o.samples = scene.run.samples > 0 ? scene.run.samples : 101;
  o.integrator = scene.run.integrator;
  o.formulation = scene.run.formulation;
  o.linear_algebra = scene.run.linear_algebra;
  o.rtol = scene.run.rtol;
  o.atol = scene.run.atol;
  o.step = scene.run.step;
  // the accuracy asked for; none and no method either: the default accuracy (the method then
  // chosen by forward_dynamics: choose_method)
  o.accuracy = scene.run.accuracy > 0 ? scene.run.accuracy
               : scene.run.method_set ? 0
                                      : kDefaultAccuracy;
  o.error_estimate = scene.run.error_estimate;
  o.max_steps = scene.run.max_steps;
  o.max_seconds = scene.run.max_seconds;
  o.max_memory = scene.run.max_memory;
  o.efforts.resize(model.inputs.size());
  for (const auto& [label, law] : scene.efforts)
    for (size_t k = 0; k < model.inputs.size(); ++k)
      if (model.inputs[k].label == label) {
        o.efforts[k] = law;
        try {  // the quantities it reads, reported at the scene's line
          (void)compile_law(model, law, "efforts." + label, label);
        } catch (const Error& e) {
          const Location* where = element_location(scene, e.element(), e.what());
          throw SceneError(where ? *where : Location{scene.file, 0, 0}, e.what());
        }
      }
  add_controllers(scene, model, o);
  return options_for_accuracy(model, o);
}

namespace {

// An option's refusal at the line of its run key (the library names "t1" for the end time, which
// the scene writes as run.duration) or of the body it names.
template <class Check>
void check_at_scene_lines(const Scene& scene, Check check) {
  try {
    check();
  } catch (const Error& e) {
    const std::string key = e.element() == "t1" ? "duration" : e.element();
    for (const auto& [name, where] : scene.elements)
      if (name == "run." + key) throw SceneError(where, "run." + key + ": " + e.what());
    if (const Location* where = element_location(scene, e.element(), e.what()))
      throw SceneError(*where, e.what());
    throw SceneError(Location{scene.file, 0, 0}, e.what());
  }
}

}  // namespace

void check_scene_options(const Scene& scene, const Model& model, const InverseOptions& options) {
  check_at_scene_lines(scene, [&] { check_inverse_options(model, options); });
}
void check_scene_options(const Scene& scene, const Model& model, const ForwardOptions& options) {
  check_at_scene_lines(scene, [&] { check_forward_options(model, options); });
}

State initial_state(const Scene& scene, const Model& model) {
  try {
    return consistent_state(model, scene.initial, scene.run.t0);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {
    Location where{scene.file, 0, 0};  // at the initial value it names, if any
    for (const auto& use : scene.labels)
      if (use.kind != LabelUse::Kind::input && use.label == e.element()) {
        where = use.where;
        break;
      }
    throw SceneError(where, std::string("initial state: ") + e.what());
  }
}

}  // namespace mo2d
