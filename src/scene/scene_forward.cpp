// A scene's forward run: forward_dynamics, or contact_dynamics with its contacts (scene_forward),
// and the extremes of that run (mo2d/scene.hpp); what does not take contacts into account refuses
// them (refuse_contacts, scene_design_request).
#include <cmath>

#include "mo2d/scene.hpp"
#include "run/format.hpp"

namespace mo2d {

namespace {

std::string number(double v) {
  return detail::fmt(v, 3);
}

std::string method_text(const ForwardOptions& o) {
  if (o.integrator == Integrator::rk4 || o.integrator == Integrator::baumgarte)
    return std::string(to_string(o.integrator)) + ", step " + number(o.step) + " s";
  return std::string(to_string(o.integrator)) + ", rtol " + number(o.rtol) + ", atol " +
         number(o.atol);
}

}  // namespace

SceneRun scene_forward(const Scene& scene, const Model& model, const State& initial,
                       const ForwardOptions& o) {
  if (scene.contacts.empty()) return {forward_dynamics(model, initial, o), {}};
  ContactOptions c = scene.contact;
  c.forward = options_for_accuracy(model, o);
  std::string method;
  if (o.accuracy > 0) {  // the explicit method of that accuracy; no stiffness test
    c.forward.accuracy = 0;
    method = "accuracy " + number(o.accuracy) +
             " with contacts (no stiffness test): " + method_text(c.forward);
  } else {
    method = method_text(c.forward) + " (as named), with contacts";
  }
  // the error estimate against the accuracy asked for (contact_dynamics runs it)
  c.accuracy = o.accuracy;
  c.forward.error_estimate = o.error_estimate;
  ContactRun run;
  try {
    run = contact_dynamics(model, scene.contacts, initial, c);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {
    // a contact the model refuses (a point it cannot find, a line of zero length) or one that
    // starts penetrating: at the contact's line
    const bool at_start = std::isnan(e.time()) || e.time() == o.t0;
    for (size_t k = 0; k < scene.contacts.size(); ++k)
      if (at_start && e.element() == scene.contacts[k].name && k < scene.contact_where.size())
        throw SceneError(scene.contact_where[k], e.what());
    throw;
  }
  run.trajectory.stats.integrator = to_string(c.forward.integrator);
  run.trajectory.stats.method = method;
  return {std::move(run.trajectory), std::move(run.events)};
}

std::vector<Extreme> scene_forward_extremes(const Scene& scene, const Model& model,
                                            const ForwardOptions& o, const Trajectory& r) {
  if (scene.contacts.empty()) return locate_extremes(model, o, r, scene.outputs);
  return sampled_extremes(model, r, scene.outputs);
}

void refuse_contacts(const Scene& scene, const std::string& what) {
  if (scene.contacts.empty()) return;
  throw SceneError(
      scene.contact_where.empty() ? Location{scene.file, 0, 0} : scene.contact_where.front(),
      "contact '" + scene.contacts.front().name + "': " + what +
          " does not take contacts into account yet");
}

DesignRequest scene_design_request(const Scene& scene, bool measures) {
  refuse_contacts(scene,
                  "the designer's measures (the frame's shaking force and the bearing loads read "
                  "the joints' reactions, not the contact forces)");
  DesignRequest d = scene.design;
  if (measures) d.frame = d.bearings = true;
  return d;
}

}  // namespace mo2d
