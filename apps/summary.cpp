// JSON summaries (nlohmann-json).
#include "summary.hpp"

#include <nlohmann/json.hpp>

#include "table.hpp"

namespace mo2d::cli {

namespace {

using json = nlohmann::ordered_json;

// {label: {max, t_max, min, t_min}} for each column.
json peaks(const std::vector<std::string>& labels, const Eigen::MatrixXd& values,
           const Eigen::VectorXd& time) {
  json out = json::object();
  if (time.size() == 0) return out;
  for (size_t k = 0; k < labels.size(); ++k) {
    Eigen::Index imax, imin;
    const auto col = values.col(static_cast<Eigen::Index>(k));
    const double vmax = col.maxCoeff(&imax), vmin = col.minCoeff(&imin);
    out[labels[k]] = {{"max", vmax}, {"t_max", time[imax]}, {"min", vmin}, {"t_min", time[imin]}};
  }
  return out;
}

json header(const Scene& s, const Model& m, const char* solve, const Eigen::VectorXd& time) {
  json params = json::object();
  for (const auto& [name, value] : s.parameters) params[name] = value;
  return {{"scene", s.file},
          {"name", s.name},
          {"solve", solve},
          {"model", {{"n0", m.n0}, {"n1", m.n1}, {"dof", m.dof}, {"bodies", m.bodies.size()}}},
          {"parameters", params},
          {"samples", time.size()},
          {"t0", time.size() ? time[0] : 0.0},
          {"t1", time.size() ? time[time.size() - 1] : 0.0}};
}

}  // namespace

std::string inverse_summary(const Scene& s, const Model& m, const Trajectory& r) {
  json j = header(s, m, "inverse", r.time);
  j["efforts"] = peaks(r.input_labels, r.efforts, r.time);
  j["reactions"] = peaks(r.reaction_labels, r.reactions, r.time);
  const bool any = r.time.size() > 0;
  j["max_residuals"] = {{"position", any ? r.residuals.col(0).maxCoeff() : 0.0},
                        {"velocity", any ? r.residuals.col(1).maxCoeff() : 0.0},
                        {"acceleration", any ? r.residuals.col(2).maxCoeff() : 0.0}};
  j["warnings"] = r.stats.warnings;
  j["cpu_seconds"] = r.stats.cpu_seconds;
  return j.dump(2) + "\n";
}

std::string forward_summary(const Scene& s, const Model& m, const Trajectory& r) {
  json j = header(s, m, "forward", r.time);
  j["efforts"] = peaks(r.input_labels, r.efforts, r.time);
  j["reactions"] = peaks(r.reaction_labels, r.reactions, r.time);
  const bool any = r.time.size() > 0;
  j["max_residuals"] = {{"position", any ? r.residuals.col(0).maxCoeff() : 0.0},
                        {"velocity", any ? r.residuals.col(1).maxCoeff() : 0.0}};
  j["energy_error"] = energy_error(r);
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
                     {"stopped_by_event", r.stats.stopped_by_event},
                     {"t_end", r.stats.t_end},
                     {"warnings", r.stats.warnings}};
  j["cpu_seconds"] = r.stats.cpu_seconds;
  return j.dump(2) + "\n";
}

}  // namespace mo2d::cli
