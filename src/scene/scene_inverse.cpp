// A scene's inverse run with contacts (mo2d/scene.hpp): the model with the contacts closed at the
// start held (hold_closed_contacts, mo2d/contact_inverse.hpp) and the report of their forces.
#include <cmath>
#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {

namespace {

// An Error naming a contact: a SceneError at the contact's line.
[[noreturn]] void at_contact(const Scene& scene, const Error& e) {
  for (size_t k = 0; k < scene.contacts.size(); ++k)
    if (e.element() == scene.contacts[k].name && k < scene.contact_where.size())
      throw SceneError(scene.contact_where[k], e.what());
  throw e;
}

}  // namespace

ContactInverseModel scene_inverse_model(const Scene& scene, const BuildOptions& options) {
  ContactInverseModel out;
  out.model = build_scene_model(scene, options);
  if (scene.contacts.empty()) return out;
  try {
    return hold_closed_contacts(scene.system, options, out.model, scene.contacts);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {
    at_contact(scene, e);
  }
}

void check_inverse_motion(const Scene& scene, const Model& m,
                          const std::vector<InverseContact>& held) {
  if (static_cast<int>(scene.motion.size()) == m.dof) return;
  std::string contacts;
  for (const InverseContact& c : held)
    if (c.held) contacts += (contacts.empty() ? "" : ", ") + c.name;
  throw SceneError(
      Location{scene.file, 0, 0},
      "inverse dynamics needs one prescribed motion per DOF: the model has " +
          std::to_string(m.dof) + " DOF" +
          (contacts.empty() ? "" : " (the contacts held closed take one each: " + contacts + ")") +
          " and 'motion' prescribes " + std::to_string(scene.motion.size()));
}

void scene_inverse_contacts(const Scene& scene, const Model& m, std::vector<InverseContact>& report,
                            const InverseOptions& options, Trajectory& r) {
  if (scene.contacts.empty()) return;
  try {
    report_contact_forces(m, scene.contacts, report, scene.motion, options, r);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {
    if (!std::isnan(e.time())) throw;  // a contact the motion closes: at its time, not a line
    at_contact(scene, e);
  }
}

}  // namespace mo2d
