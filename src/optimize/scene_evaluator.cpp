// One evaluation of an optimization: the scene run at a design (scene_evaluator.hpp).
#include "optimize/scene_evaluator.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "model/suggest.hpp"

namespace mo2d::optimize_detail {

namespace {

std::string number_text(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(Location{path, 0, 0}, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The run the scene asks for (run.solve), every run setting as mo2d inverse / forward use it,
// its wall-time budget at most `seconds`; the output and design columns added.
struct SceneRun {
  Model model;
  Trajectory r;
  DesignRequest request;
};
SceneRun run_scene(const Scene& s, bool measures, double seconds) {
  // the runs below are the plain inverse and forward ones, and the summaries re-integrate between
  // samples: a scene with contacts would be optimized without them
  refuse_contacts(s, "mo2d optimize");
  BuildOptions b;
  b.max_memory = s.run.max_memory;
  SceneRun out{build_scene_model(s, b), {}, scene_design_request(s, measures)};
  const Model& model = out.model;
  Trajectory& r = out.r;
  if (s.run.solve == Solve::inverse) {
    check_inverse_motion(s, model);
    InverseOptions run = inverse_options(s);
    run.max_seconds = std::min(run.max_seconds, seconds);
    check_scene_options(s, model, run);
    r = inverse_dynamics(model, s.motion, run);
  } else {
    ForwardOptions run = forward_options(s, model);
    run.max_seconds = std::min(run.max_seconds, seconds);
    check_scene_options(s, model, run);
    r = forward_dynamics(model, initial_state(s, model), run);
  }
  add_output_columns(model, r, s.outputs);
  if (!out.request.empty()) add_design_columns(model, r, out.request);
  return out;
}

}  // namespace

SceneEvaluator::SceneEvaluator(const OptimizeOptions& o) : o_(o) {
  if (o.vary.empty()) throw OptimizeInputError("optimize: nothing to vary (--vary NAME=LO:HI)");
  if (o.minimize.empty()) throw OptimizeInputError("optimize: no objective (--minimize EXPR)");
  text_ = read_text(o.scene);
  const Scene plain = parse_scene(text_, o.scene);  // the names of its parameters
  std::vector<std::string> names;
  for (const auto& p : plain.parameters) names.push_back(p.first);
  for (std::size_t k = 0; k < o.vary.size(); ++k) {
    const DesignVariable& v = o.vary[k];
    if (std::find(names.begin(), names.end(), v.name) == names.end())
      throw OptimizeInputError("--vary " + v.name + ": '" + v.name + "' is not a parameter of " +
                               o.scene + did_you_mean(v.name, names));
    if (!(std::isfinite(v.lo) && std::isfinite(v.hi) && v.lo < v.hi))
      throw OptimizeInputError("--vary " + v.name +
                               ": the bounds must be finite with LO < HI, got " +
                               number_text(v.lo) + ":" + number_text(v.hi));
    for (std::size_t j = 0; j < k; ++j)
      if (o.vary[j].name == v.name)
        throw OptimizeInputError("--vary " + v.name + ": the parameter is varied twice");
    for (const ParameterOverride& s : o.set)
      if (s.name == v.name)
        throw OptimizeInputError("--vary " + v.name + ": the parameter is also fixed by --set");
  }
  scene_ = parse_scene(text_, o.scene, o.set, o.run);
  criteria_.push_back(parse_criterion(o.minimize, "objective", false));
  for (std::size_t k = 0; k < o.subject_to.size(); ++k)
    criteria_.push_back(
        parse_criterion(o.subject_to[k], "constraint " + std::to_string(k + 1), true));
}

std::vector<ParameterOverride> SceneEvaluator::overrides(std::span<const double> x) const {
  std::vector<ParameterOverride> out = o_.set;
  for (std::size_t k = 0; k < o_.vary.size(); ++k)
    out.push_back({o_.vary[k].name, number_text(x[k])});
  return out;
}

Scene SceneEvaluator::scene_at(std::span<const double> x) const {
  return parse_scene(text_, o_.scene, overrides(x), o_.run);
}

std::string SceneEvaluator::text_at(std::span<const double> x) const {
  const Scene s = scene_at(x);
  std::vector<std::pair<std::string, double>> values;
  for (const auto& parameter : s.parameters) {
    const std::string& name = parameter.first;
    const bool varied = std::any_of(o_.vary.begin(), o_.vary.end(),
                                    [&](const DesignVariable& v) { return v.name == name; });
    const bool fixed = std::any_of(o_.set.begin(), o_.set.end(),
                                   [&](const ParameterOverride& p) { return p.name == name; });
    if (varied || fixed) values.push_back(parameter);
  }
  return set_parameter_values(text_, o_.scene, values);
}

std::string SceneEvaluator::describe(std::span<const double> x) const {
  std::string s;
  for (std::size_t k = 0; k < o_.vary.size(); ++k)
    s += (k ? ", " : "") + o_.vary[k].name + " = " + number_text(x[k]);
  return s;
}

void SceneEvaluator::bind(const Scene& s, const Trajectory& r) {
  std::vector<std::string> candidates;  // for "did you mean"
  for (const auto& p : s.parameters) candidates.push_back(p.first);
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  for (const std::string& l : labels)
    for (const char* stat : {"peak.", "rms.", "max.", "min.", "mean.", "peak_to_peak."})
      candidates.push_back(stat + l);
  for (const std::string& l : r.input_labels)
    for (const char* stat : {"energy_fluctuation.", "flywheel."}) candidates.push_back(stat + l);
  auto resolve = [&](const Criterion& c, Expression& e, int offset) {
    try {
      e.bind(
          [&](const std::string& name) {
            Source src;
            for (std::size_t k = 0; k < s.parameters.size(); ++k)
              if (s.parameters[k].first == name) src.parameter = static_cast<int>(k);
            if (src.parameter < 0) {
              const std::optional<RunValue> v = parse_run_value(name);
              if (!v) return Binding{};
              const bool known = needs_design_summary(*v)
                                     ? std::find(r.input_labels.begin(), r.input_labels.end(),
                                                 v->column) != r.input_labels.end()
                                     : column_samples(r, v->column).has_value();
              if (!known) {
                std::string why = "'" + name + "': the run has no " +
                                  (needs_design_summary(*v) ? "input '" : "column '") + v->column +
                                  "'" + did_you_mean(name, candidates);
                if (v->column.starts_with("frame.") || v->column.ends_with(".load") ||
                    v->column.ends_with(".load_angle"))
                  why += " (the frame's and bearings' columns need --measures or a design: block)";
                throw ExpressionError(why, e.column(name));
              }
              src.value = *v;
              needs_summary_ = needs_summary_ || needs_design_summary(*v);
            }
            sources_.push_back(src);
            return Binding{Binding::Kind::variable, 0, static_cast<int>(sources_.size() - 1)};
          },
          candidates);
    } catch (const ExpressionError& x) {
      fail_criterion(c, x.column() + offset,
                     std::string(x.what()) +
                         " (a name is a parameter or peak|max|min|mean|rms|peak_to_peak.COLUMN, "
                         "energy_fluctuation|flywheel.INPUT)");
    }
  };
  for (Criterion& c : criteria_) {
    resolve(c, c.lhs, 0);
    if (c.has_rhs) resolve(c, c.rhs, c.rhs_offset);
  }
  values_.assign(sources_.size(), Jet{});
  bound_ = true;
}

SceneEvaluator::Values SceneEvaluator::evaluate(std::span<const double> x, double seconds) {
  Scene s;
  SceneRun run;
  DesignSummary summary;
  const Trajectory& r = run.r;
  try {
    s = scene_at(x);
    run = run_scene(s, o_.measures, seconds);
    if (!bound_) bind(s, r);
    if (needs_summary_) summary = design_summary(run.model, r, run.request);
  } catch (const OptimizeInputError&) {
    throw;
  } catch (const SceneError& e) {
    throw SceneError(e.where(), "optimize: at " + describe(x) + ": " + e.message());
  } catch (const Error& e) {
    throw Error("optimize: the run at " + describe(x) + " failed: " + e.what(), e.element());
  }
  for (std::size_t k = 0; k < sources_.size(); ++k) {
    const Source& src = sources_[k];
    values_[k] =
        Jet(src.parameter >= 0 ? s.parameters[static_cast<std::size_t>(src.parameter)].second
                               : run_value(src.value, r, &summary));
  }
  Values out;
  for (std::size_t k = 0; k < criteria_.size(); ++k) {
    const Criterion& c = criteria_[k];
    const double v = criterion_value(c, values_);
    if (!std::isfinite(v))
      throw Error("optimize: the " + c.what + " '" + c.text + "' is not finite (" + number_text(v) +
                  ") at " + describe(x));
    if (k == 0) {
      out.objective = v;
    } else {
      out.constraints.push_back(v);
      out.scaled.push_back(v / criterion_scale(c, values_));
      out.violation = std::max(out.violation, out.scaled.back());
    }
  }
  return out;
}

}  // namespace mo2d::optimize_detail
