// One run of the fidelity sweep (bench/fidelity_sweep.hpp): the scene's YAML edited for the
// fidelity, loaded with the stiffness and run settings as overrides, built once, run
// `repetitions` times (CPU of the solve), its slow signals filtered.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "fidelity_sweep.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::sweep {

const char* to_string(Status s) {
  switch (s) {
    case Status::ok:
      return "ok";
    case Status::budget_exceeded:
      return "budget exceeded";
    case Status::not_available:
      return "not available in this build";
    case Status::failed:
      return "failed";
  }
  return "?";
}

namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> keys;
  std::istringstream in(path);
  for (std::string key; std::getline(in, key, '.');) keys.push_back(key);
  return keys;
}

// The map at keys[0..n-2] below `root` (created for a set, required for an erase).
void apply_edit(const YAML::Node& root, const Edit& e) {
  const std::vector<std::string> keys = split_path(e.path);
  YAML::Node node = root;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (!node[keys[i]].IsDefined() && e.value.empty())
      throw Error("fidelity edit: no key '" + e.path + "' in the scene");
    node.reset(node[keys[i]]);
  }
  if (e.value.empty()) {
    if (!node.remove(keys.back())) throw Error("fidelity edit: no key '" + e.path + "' to erase");
  } else {
    node[keys.back()] = YAML::Load(e.value);
  }
}

// Column `label` of a run, whichever block holds it.
Eigen::VectorXd column(const Trajectory& r, const std::string& label) {
  auto find = [&](const std::vector<std::string>& labels) {
    return static_cast<int>(std::find(labels.begin(), labels.end(), label) - labels.begin());
  };
  if (int i = find(r.coordinate_labels); i < static_cast<int>(r.coordinate_labels.size()))
    return r.q0.col(i);
  if (int i = find(r.rate_labels); i < static_cast<int>(r.rate_labels.size())) return r.q1.col(i);
  if (int i = find(r.reaction_labels); i < static_cast<int>(r.reaction_labels.size()))
    return r.reactions.col(i);
  if (int i = find(r.input_labels); i < static_cast<int>(r.input_labels.size()))
    return r.efforts.col(i);
  if (int i = find(r.output_labels); i < static_cast<int>(r.output_labels.size()))
    return r.outputs.col(i);
  throw Error("the run has no column '" + label + "'");
}

Eigen::VectorXd signal_values(const Trajectory& r, const Signal& s) {
  if (s.angle) {
    const Eigen::VectorXd x = column(r, s.terms.at(0).column), y = column(r, s.terms.at(1).column);
    Eigen::VectorXd a(x.size());
    // measured from the axis nearest the first sample's direction (the same for every run of a
    // scene), so that a start on atan2's cut (an arm along -x: y = +0 in one run, -4e-12 in
    // another) cannot put two runs' unwrapped angles 2 pi apart
    const double ux = x.size() == 0 ? 1.0 : x[0] - s.x0, uy = x.size() == 0 ? 0.0 : y[0] - s.y0;
    const double axis = std::abs(ux) >= std::abs(uy) ? (ux >= 0 ? 0.0 : std::numbers::pi)
                                                     : (uy >= 0 ? 0.5 : -0.5) * std::numbers::pi;
    const double ca = std::cos(axis), sa = std::sin(axis);
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double dx = x[i] - s.x0, dy = y[i] - s.y0;
      a[i] = axis + std::atan2(ca * dy - sa * dx, ca * dx + sa * dy);
      if (i > 0)
        a[i] -= 2 * std::numbers::pi * std::round((a[i] - a[i - 1]) / (2 * std::numbers::pi));
    }
    return a;
  }
  Eigen::VectorXd v = Eigen::VectorXd::Zero(r.time.size());
  for (const Term& t : s.terms) v += t.factor * column(r, t.column);
  return v;
}

const Signal& signal_for(const SceneCase& scene, const Fidelity& f, std::size_t i) {
  for (const Signal& s : f.signals)
    if (s.name == scene.signals[i].name) return s;
  return scene.signals[i];
}

Scene load(const SceneCase& sc, const Fidelity& f, const RunSpec& spec) {
  std::vector<ParameterOverride> params;
  for (const std::string& p : sc.parameters) params.push_back(parse_override(p));
  char k[32];
  std::snprintf(k, sizeof k, "k_chain=%.17g", spec.k);
  params.push_back(parse_override(k));
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  const std::vector<RunOverride> run = {{"duration", num(sc.duration)},
                                        {"samples", std::to_string(sc.samples)},
                                        {"integrator", spec.integrator},
                                        {"rtol", num(spec.rtol)},
                                        {"atol", num(spec.atol)},
                                        {"max_steps", std::to_string(spec.max_steps)},
                                        {"max_seconds", num(spec.max_seconds)}};
  // an edited scene's locations are lines of the emitted text, not of the file
  const std::string name = f.edits.empty() ? sc.file : sc.file + " (edited for " + f.name + ")";
  return parse_scene(edited_scene(sc.file, f.edits), name, params, run);
}

}  // namespace

std::string edited_scene(const std::string& file, const std::vector<Edit>& edits) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read " + file);
  std::stringstream text;
  text << in.rdbuf();
  if (edits.empty()) return text.str();
  YAML::Node root = YAML::Load(text.str());
  for (const Edit& e : edits) apply_edit(root, e);
  YAML::Emitter out;
  out << root;
  return out.c_str();
}

RunResult run_case(const SceneCase& sc, const Fidelity& f, const RunSpec& spec) {
  RunResult res;
  Scene scene;
  Model model;
  try {
    scene = load(sc, f, spec);
    model = build_scene_model(scene);
  } catch (const Error& e) {
    if (!f.optional) throw;
    return {.status = Status::not_available, .message = e.what()};
  }
  const ForwardOptions options = forward_options(scene, model);
  check_scene_options(scene, model, options);
  const State start = initial_state(scene, model);
  std::vector<double> cpu;
  Trajectory r;
  try {
    for (int i = 0; i < spec.repetitions; ++i) {
      r = forward_dynamics(model, start, options);
      cpu.push_back(r.stats.cpu_seconds);
    }
  } catch (const Error& e) {
    const std::string m = e.what();
    res.status =
        m.find("budget of") != std::string::npos ? Status::budget_exceeded : Status::failed;
    res.message = m;
    return res;
  }
  add_output_columns(model, r, scene.outputs);
  std::sort(cpu.begin(), cpu.end());
  res.cpu_median = cpu[cpu.size() / 2];
  res.cpu_min = cpu.front();
  res.steps = r.stats.steps;
  const double dt = sc.duration / (sc.samples - 1);
  for (std::size_t i = 0; i < sc.signals.size(); ++i)
    res.slow.push_back(gaussian_filter(signal_values(r, signal_for(sc, f, i)), dt, sc.sigma));
  return res;
}

Eigen::VectorXd gaussian_filter(const Eigen::VectorXd& x, double dt, double sigma) {
  const Eigen::Index n = x.size(), w = filter_margin(dt, sigma);
  Eigen::VectorXd kernel(2 * w + 1);
  for (Eigen::Index j = -w; j <= w; ++j)
    kernel[j + w] = std::exp(-0.5 * std::pow(static_cast<double>(j) * dt / sigma, 2));
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, i - w), hi = std::min(n - 1, i + w);
    const auto k = kernel.segment(lo - i + w, hi - lo + 1);
    y[i] = k.dot(x.segment(lo, hi - lo + 1)) / k.sum();
  }
  return y;
}

Eigen::Index filter_margin(double dt, double sigma) {
  return static_cast<Eigen::Index>(std::ceil(4 * sigma / dt));
}

double relative_error(const Eigen::VectorXd& x, const Eigen::VectorXd& ref, Eigen::Index margin) {
  const Eigen::Index n = ref.size() - 2 * margin;
  if (n < 2) throw Error("fidelity sweep: the run is shorter than the filter's kernel");
  const auto r = ref.segment(margin, n);
  const double range = r.maxCoeff() - r.minCoeff();
  return (x.segment(margin, n) - r).cwiseAbs().maxCoeff() / (range > 0 ? range : 1.0);
}

}  // namespace mo2d::sweep
