// JSON summaries (nlohmann-json).
#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "table.hpp"

namespace mo2d::cli {

namespace {

using json = nlohmann::ordered_json;

// {label: {max, t_max, min, t_min, located}} for the columns of `labels` (mo2d/extremes.hpp:
// located between the samples; located false: the largest sample of a fine grid, or of the run).
json peaks(const std::vector<std::string>& labels, const std::vector<Extreme>& extremes) {
  json out = json::object();
  for (const Extreme& e : extremes)
    if (std::find(labels.begin(), labels.end(), e.label) != labels.end())
      out[e.label] = {{"max", e.max},
                      {"t_max", e.t_max},
                      {"min", e.min},
                      {"t_min", e.t_min},
                      {"located", e.located_max && e.located_min}};
  return out;
}

// The efforts, reactions and output columns' extremes of a run.
void add_peaks(json& j, const Trajectory& r, const std::vector<Extreme>& extremes) {
  j["efforts"] = peaks(r.input_labels, extremes);
  j["reactions"] = peaks(r.reaction_labels, extremes);
  if (!r.output_labels.empty()) j["outputs"] = peaks(r.output_labels, extremes);
}

json header(const SceneOptions& o, const Scene& s, const Model& m, const char* solve,
            const Trajectory& r) {
  json params = json::object();
  for (const auto& [name, value] : s.parameters) params[name] = value;
  json set = json::object(), run = json::object();  // as given on the command line
  for (const auto& text : o.set) {
    const ParameterOverride p = parse_override(text);
    set[p.name] = p.value;
  }
  for (const RunOverride& v : o.run) run[v.key] = v.value;
  const Eigen::VectorXd& time = r.time;
  return {{"mo2d_version", MO2D_VERSION},
          {"scene", s.file},
          {"name", s.name},
          {"solve", solve},
          {"model", {{"n0", m.n0}, {"n1", m.n1}, {"dof", m.dof}, {"bodies", m.bodies.size()}}},
          {"parameters", params},
          {"overrides", {{"set", set}, {"run", run}}},
          {"samples", time.size()},
          {"t0", time.size() ? time[0] : 0.0},
          {"t1", time.size() ? time[time.size() - 1] : 0.0}};
}

// Every CSV column with its unit ("" where the model cannot say, mo2d/csv.hpp).
json columns(const Model& m, const Trajectory& r) {
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  const std::vector<std::string> units = trajectory_csv_units(m, r);
  json out = json::object();
  for (std::size_t k = 0; k < labels.size(); ++k) out[labels[k]] = units[k];
  return out;
}

// The a-posteriori estimate of the global error (RunStats): value (null: not estimated), where,
// how, and the CPU time of the second run.
json estimated_error(const Trajectory& r) {
  const RunStats& st = r.stats;
  const bool done = !std::isnan(st.estimated_error);
  return {{"value", done ? json(st.estimated_error) : json(nullptr)},
          {"t", done ? json(st.estimated_error_t) : json(nullptr)},
          {"variable", st.estimated_error_variable},
          {"method", st.error_estimate},
          {"cpu_seconds", st.estimate_cpu_seconds}};
}

// An inverse run's contacts (mo2d/contact_inverse.hpp): held closed with their force's least value
// and where it goes negative (null: never), or left out with their least gap.
json inverse_contact_json(const std::vector<InverseContact>& contacts) {
  json out = json::object();
  for (const InverseContact& c : contacts) {
    if (!c.held) {
      out[c.name] = {
          {"held", false}, {"gap", c.gap}, {"min_gap", c.min_gap}, {"t_min_gap", c.t_min_gap}};
      continue;
    }
    out[c.name] = {{"held", true},
                   {"column", c.column},
                   {"min_force", c.min_force},
                   {"t_min", c.t_min},
                   {"t_negative", std::isnan(c.t_negative) ? json() : json(c.t_negative)},
                   {"preload", c.preload}};
  }
  return out;
}

// A contact run: its contacts (name, law, restitution, friction if any) and events in time order.
json contact_json(const Scene& s, const std::vector<ContactEvent>& events) {
  json contacts = json::object();
  for (const ContactDef& c : s.contacts) {
    contacts[c.name] = {{"law", c.law.kind == ContactLaw::Kind::rigid ? "rigid" : "compliant"},
                        {"restitution", c.law.restitution}};
    if (c.law.friction > 0) contacts[c.name]["friction"] = c.law.friction;
  }
  json list = json::array();
  for (const ContactEvent& e : events) {
    json item = {{"kind", contact_event_name(e.kind)},
                 {"t", e.t},
                 {"contact", e.contact},
                 {"speed", e.speed}};
    if (e.kind == ContactEvent::Kind::impact) {
      item["speed_after"] = e.speed_after;
      item["impulse"] = e.impulse;
      item["energy_lost"] = e.energy_lost;
    }
    if (e.kind == ContactEvent::Kind::zeno) item["predicted_t"] = e.predicted_t;
    list.push_back(item);
  }
  return {{"contacts", contacts}, {"events", list}};
}

}  // namespace

std::string inverse_summary(const SceneOptions& o, const Scene& s, const Model& m,
                            const Trajectory& r, const InverseOptions& run,
                            const std::vector<Extreme>& extremes, const std::string& design,
                            const std::vector<InverseContact>& contacts) {
  json j = header(o, s, m, "inverse", r);
  j["run"] = {{"t0", run.t0},
              {"duration", s.run.duration},
              {"samples", run.samples},
              {"tolerance", run.position_tolerance},
              {"max_seconds", run.max_seconds},
              {"max_memory", run.max_memory}};
  j["columns"] = columns(m, r);
  add_peaks(j, r, extremes);
  const bool any = r.time.size() > 0;
  j["max_residuals"] = {{"position", any ? r.residuals.col(0).maxCoeff() : 0.0},
                        {"velocity", any ? r.residuals.col(1).maxCoeff() : 0.0},
                        {"acceleration", any ? r.residuals.col(2).maxCoeff() : 0.0}};
  if (!design.empty()) j["design"] = json::parse(design);
  if (!contacts.empty()) j["contacts"] = inverse_contact_json(contacts);
  j["warnings"] = r.stats.warnings;
  j["cpu_seconds"] = r.stats.cpu_seconds;
  return j.dump(2) + "\n";
}

std::string forward_summary(const SceneOptions& o, const Scene& s, const Model& m,
                            const Trajectory& r, const ForwardOptions& run,
                            const std::vector<Extreme>& extremes, const std::string& design,
                            const std::vector<ContactEvent>& events) {
  json j = header(o, s, m, "forward", r);
  j["run"] = {
      {"t0", run.t0},
      {"duration", s.run.duration},
      {"samples", run.samples},
      {"integrator", r.stats.integrator.empty() ? to_string(run.integrator) : r.stats.integrator},
      {"formulation", to_string(run.formulation)},
      {"rtol", run.rtol},
      {"atol", run.atol},
      {"step", run.step},
      {"accuracy", run.accuracy},
      {"error_estimate", to_string(run.error_estimate)},
      {"method", r.stats.method},
      {"max_steps", run.max_steps},
      {"max_seconds", run.max_seconds},
      {"max_memory", run.max_memory}};
  j["columns"] = columns(m, r);
  add_peaks(j, r, extremes);
  const bool any = r.time.size() > 0;
  j["max_residuals"] = {{"position", any ? r.residuals.col(0).maxCoeff() : 0.0},
                        {"velocity", any ? r.residuals.col(1).maxCoeff() : 0.0}};
  j["energy_error"] = energy_error(r);
  j["estimated_error"] = estimated_error(r);
  if (!s.controllers.empty()) {  // the tracking error e = x - r of each controller
    json tracking = json::object();
    for (const TrackingError& e : tracking_errors(s, m, r))
      tracking[e.input] = {{"coordinate", e.coordinate},
                           {"max_error", e.max_error},
                           {"t_max", e.t_max},
                           {"final_error", e.final_error}};
    j["tracking"] = tracking;
  }
  j["integrator"] = {{"steps", r.stats.steps},
                     {"rhs_evaluations", r.stats.rhs_evaluations},
                     {"projections", r.stats.projections},
                     {"linear_algebra", r.stats.sparse ? "sparse" : "dense"},
                     {"stopped_by_event", r.stats.stopped_by_event},
                     {"t_end", r.stats.t_end},
                     {"warnings", r.stats.warnings}};
  if (!design.empty()) j["design"] = json::parse(design);
  if (!s.contacts.empty()) j["contacts"] = contact_json(s, events);
  j["cpu_seconds"] = r.stats.cpu_seconds;
  return j.dump(2) + "\n";
}

}  // namespace mo2d::cli
