// mo2d crosscheck SCENE [--set name=value]... [--out DIR] [--step H]: rebuilds the scene's
// mechanism in Box2D, drives its motors along the scene's prescribed motion, and compares Box2D's
// motor efforts and joint reactions with mo2d's inverse dynamics (docs/crosscheck.md). Prints the
// comparison table; writes DIR/NAME_crosscheck.csv (both series) and DIR/NAME_crosscheck.png:
// the efforts of both, their difference, the joint reactions and theirs (crosscheck_picture.cpp).
// Exit status 3 when the engines disagree (the tolerances are set so that a disagreement means a
// modelling error, docs/crosscheck.md); a step too coarse for the motion or too few compared steps
// is an error (status 1), never a verdict. A scene whose run solves forward (run: {solve:
// forward}), or --forward: from the scene's consistent initial state, under the scene's efforts and
// controllers, mo2d (CVODE BDF, rtol 1e-10) and Box2D integrate over the run; centres of mass and
// body angles are compared at the run's samples; writes DIR/NAME_crosscheck_forward.csv (t and the
// worst body's errors); exit status 3 when an error exceeds --position-tolerance (relative to the
// mechanism's size) or
// --angle-tolerance.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "command.hpp"
#include "crosscheck_picture.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"
#include "scene_options.hpp"
#include "table.hpp"

namespace mo2d::cli {

namespace {

struct CrosscheckCliOptions {
  SceneOptions scene{};
  double step = 1.0 / 2000;
  double inertia_fraction = 1.0 / 12;
  double feedback_time = -1;                 // < 0: the library's default
  std::vector<std::string> reference_set{};  // name=value, mo2d's model only
  bool strict = false;
  bool forward = false;
  bool step_set = false;  // --step given: the forward check does not refine it
  double position_tolerance = kForwardPositionTolerance;  // --forward: max |com error| / size
  double angle_tolerance = kForwardAngleTolerance;        // --forward: rad
  // contacts: intervals between impacts (Box2D steps) and speeds (relative to the largest
  // compared approach speed)
  double impact_time_tolerance = ContactTolerances{}.interval_steps;
  double impact_speed_tolerance = ContactTolerances{}.speed;
  double restitution_threshold = 0;  // Box2D's, m/s
};

// The cross-check's settings, with the scene's budgets (Box2D steps, wall time, result memory:
// CrosscheckOptions::max_steps, checked by the library).
CrosscheckOptions check_options(const CrosscheckCliOptions& o, const Scene& scene) {
  CrosscheckOptions check;
  check.step = o.step;
  check.max_steps = scene.run.max_steps;
  check.max_seconds = scene.run.max_seconds;
  check.max_memory = scene.run.max_memory;
  check.zero_inertia_fraction = o.inertia_fraction;
  check.refine_step = !o.step_set;
  if (o.feedback_time >= 0) check.feedback_time = o.feedback_time;
  return check;
}

// The contact cross-check (docs/contact.md, "Box2D"): mo2d's contact run and Box2D with the
// contacts' shapes; the motion at the samples and the impacts one by one.
int contact_check(const CrosscheckCliOptions& o, const Scene& scene) {
  build_model_of(scene);               // checks the scene's labels, prints the sketch's warnings
  SceneOptions ref_options = o.scene;  // --reference-set: mo2d's model and contacts only
  ref_options.set.insert(ref_options.set.end(), o.reference_set.begin(), o.reference_set.end());
  const Scene ref_scene = o.reference_set.empty() ? scene : load_scene_with_overrides(ref_options);
  const Model model = build_scene_model(scene, {.reduction = Reduction::none});
  const Model reference = build_scene_model(ref_scene, {.reduction = Reduction::none});
  const State initial = initial_state(scene, model);
  const int samples = scene.run.samples > 0 ? scene.run.samples : 101;
  ContactOptions run = scene.contact;
  const Model ref_model = build_model_of(ref_scene);
  run.forward = options_for_accuracy(ref_model, forward_options(ref_scene, ref_model));
  run.forward.accuracy = 0;  // as scene_forward: the explicit method of that accuracy
  run.forward.error_estimate = ErrorEstimate::off;
  CrosscheckOptions check = check_options(o, scene);
  check.restitution_threshold = o.restitution_threshold;
  ContactCrosscheck r;
  try {
    r = crosscheck_contacts(reference, ref_scene.contacts, model, scene.contacts, initial,
                            scene.run.t0 + scene.run.duration, check, samples, run);
  } catch (const SceneError&) {
    throw;
  } catch (const Error& e) {  // a contact Box2D cannot represent: at the contact's line
    for (size_t k = 0; k < scene.contacts.size() && k < scene.contact_where.size(); ++k)
      if (e.element() == scene.contacts[k].name && std::isnan(e.time()))
        throw SceneError(scene.contact_where[k], e.what());
    throw;
  }
  const ContactTolerances tol{.position = o.position_tolerance,
                              .interval_steps = o.impact_time_tolerance,
                              .speed = o.impact_speed_tolerance};
  const bool agree = contact_agrees(r, tol);
  const ForwardCrosscheck& f = r.motion;
  std::printf("mo2d contact cross-check against Box2D: %s\n", f.mechanism.c_str());
  for (const std::string& n : f.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("  step %.6g s, %d steps over [%g, %g] s, %d compared instants\n", f.step, f.steps,
              initial.t, initial.t + f.steps * f.step, static_cast<int>(f.time.size()));
  std::printf(
      "  impacts: mo2d %d, Box2D %d (closings); %d compared (each at least %d steps "
      "after its contact's previous event)\n",
      r.mo2d_impacts, r.box2d_impacts, static_cast<int>(r.impacts.size()), check.min_impact_steps);
  std::printf("  %-10s %3s %14s %14s %10s %10s %10s %10s\n", "contact", "k", "t mo2d", "t Box2D",
              "v- mo2d", "v- Box2D", "v+ mo2d", "v+ Box2D");
  for (const ImpactComparison& c : r.impacts) {
    if (c.found)
      std::printf("  %-10s %3d %14.9f %14.9f %10.6f %10.6f %10.6f %10.6f\n", c.contact.c_str(),
                  c.index, c.t_mo2d, c.t_box2d, c.speed_mo2d, c.speed_box2d, c.after_mo2d,
                  c.after_box2d);
    else
      std::printf("  %-10s %3d %14.9f %14s\n", c.contact.c_str(), c.index, c.t_mo2d,
                  "none in Box2D");
  }
  std::printf(
      "  impact time error:   max %.3e s; between impacts max %.3g steps (tolerance %.3g)\n",
      r.max_time_error, r.max_interval_error, tol.interval_steps);
  std::printf(
      "  impact speed error:  approach %.3e, separation %.3e of %.4g m/s (tolerance %.3g)\n",
      r.max_speed_error, r.max_rebound_error, r.speed_scale, tol.speed);
  std::printf("  Box2D's deepest penetration: %.3e m (mo2d's gap on Box2D's state)\n",
              -r.deepest_penetration);
  std::printf(
      "  centre of mass error: max %.3e m (%.3e of the size, tolerance %.3g), final "
      "%.3e m\n",
      f.max_position_error, f.relative_position_error, tol.position, f.final_position_error);
  std::printf("  body angle error:     max %.3e rad: %s\n", f.max_angle_error,
              agree ? "AGREE" : "DISAGREE");
  std::string csv = "t,position_error,angle_error\n";  // the worst body at each instant
  for (Eigen::Index k = 0; k < f.time.size(); ++k)
    csv += shortest(f.time[k]) + "," + shortest(f.position_error[k]) + "," +
           shortest(f.angle_error[k]) + "\n";
  OutputSet files;
  files.add(output_path(o.scene, scene, "crosscheck_forward.csv"), csv);
  files.commit();
  for (const auto& path : files.paths()) std::printf("  wrote %s\n", path.c_str());
  return agree ? 0 : 3;
}

// The forward cross-check: the motion of both engines from the scene's initial state.
int forward_check(const CrosscheckCliOptions& o) {
  const Scene scene = load_scene_with_overrides(o.scene);
  if (!scene.contacts.empty()) return contact_check(o, scene);
  build_model_of(scene);  // checks the scene's labels, prints the sketch's warnings
  const Model model = build_scene_model(scene, {.reduction = Reduction::none});
  const State initial = initial_state(scene, model);
  const int samples = scene.run.samples > 0 ? scene.run.samples : 101;
  // the scene's efforts and controllers, in both engines (Box2D evaluates them on its state)
  const EffortLaws efforts = forward_options(scene, build_model_of(scene)).efforts;
  const ForwardCrosscheck r = mo2d::crosscheck_forward(
      model, initial, scene.run.t0 + scene.run.duration, check_options(o, scene), samples, efforts);
  const bool agree = forward_agrees(r, o.position_tolerance, o.angle_tolerance);
  std::printf("mo2d forward cross-check against Box2D: %s\n", r.mechanism.c_str());
  if (!scene.efforts.empty() || !scene.controllers.empty())
    std::printf(
        "  note: the scene's efforts and controllers act in both engines (Box2D's evaluated on "
        "its own state)\n");
  for (const std::string& n : r.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("  step %.6g s, %d steps over [%g, %g] s, %d compared instants\n", r.step, r.steps,
              initial.t, initial.t + r.steps * r.step, static_cast<int>(r.time.size()));
  std::printf(
      "  centre of mass error: max %.3e m (%.3e of the size, tolerance %.3g), final "
      "%.3e m\n",
      r.max_position_error, r.relative_position_error, o.position_tolerance,
      r.final_position_error);
  std::printf("  body angle error:     max %.3e rad (tolerance %.3g), final %.3e rad: %s\n",
              r.max_angle_error, o.angle_tolerance, r.final_angle_error,
              agree ? "AGREE" : "DISAGREE");
  if (agree && !r.branch_switch.empty()) std::printf("  note: %s\n", r.branch_switch.c_str());
  if (!agree) {
    const std::string cause = box2d_cause(r, o.position_tolerance, o.angle_tolerance);
    if (!cause.empty()) std::printf("  DISAGREE caused by Box2D: %s\n", cause.c_str());
  }
  std::string csv = "t,position_error,angle_error\n";  // the worst body at each instant
  for (Eigen::Index k = 0; k < r.time.size(); ++k)
    csv += shortest(r.time[k]) + "," + shortest(r.position_error[k]) + "," +
           shortest(r.angle_error[k]) + "\n";
  OutputSet files;
  files.add(output_path(o.scene, scene, "crosscheck_forward.csv"), csv);
  files.commit();
  for (const auto& path : files.paths()) std::printf("  wrote %s\n", path.c_str());
  return agree ? 0 : 3;
}

int crosscheck(const CrosscheckCliOptions& o) {
  const Scene scene = load_scene_with_overrides(o.scene);
  if (!scene.contacts.empty() && !o.forward && scene.run.solve != Solve::forward)
    refuse_contacts(scene, "the Box2D cross-check of inverse dynamics");
  // the scene's run says which: forward (no motion, initial conditions) or inverse
  if (o.forward || scene.run.solve == Solve::forward) return forward_check(o);
  const Model model = build_model_of(scene);  // checks the scene's labels
  if (static_cast<int>(scene.motion.size()) != model.dof)
    throw SceneError(Location{scene.file, 0, 0},
                     "the cross-check drives the prescribed motion: the model has " +
                         std::to_string(model.dof) + " DOF and 'motion' prescribes " +
                         std::to_string(scene.motion.size()));
  const CrosscheckOptions check = check_options(o, scene);
  const InverseOptions run = inverse_options(scene);
  check_scene_options(scene, model, run);
  // mo2d's reference model: the scene's, or (--reference-set) the scene with some parameters
  // changed in mo2d only, to see which modelling errors the cross-check detects
  SceneOptions ref_options = o.scene;
  ref_options.set.insert(ref_options.set.end(), o.reference_set.begin(), o.reference_set.end());
  const Scene ref_scene = o.reference_set.empty() ? scene : load_scene_with_overrides(ref_options);
  const CrosscheckReport r = crosscheck_inverse(
      build_scene_model(ref_scene), build_scene_model(scene, {.reduction = Reduction::none}),
      scene.motion, run, check);
  print_crosscheck_table(std::cout, r);
  std::cout.flush();
  OutputSet files;  // the CSV and the plot land together or not at all
  int panels = 0;
  {
    OutputSet::Scope scope(files);
    write_crosscheck_csv(r, output_path(o.scene, scene, "crosscheck.csv"));
    panels = write_crosscheck_picture(r, output_path(o.scene, scene, "crosscheck.png"));
  }
  files.commit();
  for (const auto& path : files.paths()) std::printf("  wrote %s\n", path.c_str());
  if (panels > 0)
    std::printf("  picture: %d panels (efforts, their difference%s)\n", panels,
                panels > 2 ? ", joint reactions, theirs" : "");
  return r.agree ? 0 : 3;
}

}  // namespace

Command add_crosscheck_command(CLI::App& app) {
  auto o = std::make_shared<CrosscheckCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "crosscheck", "Rebuild the scene in Box2D and compare motor efforts and joint reactions");
  add_scene_options(sub, o->scene, true, RunFlags::inverse);
  sub->add_flag(
      "--forward", o->forward,
      "forward cross-check (the default for a scene with run: {solve: forward}): the motion "
      "from the scene's initial state under its efforts and controllers in "
      "both engines, centres of mass and body angles compared");
  sub->add_option("--position-tolerance", o->position_tolerance,
                  "--forward: largest centre-of-mass error, relative to the mechanism's size "
                  "(default 1e-2)")
      ->check(finite_positive());
  sub->add_option("--angle-tolerance", o->angle_tolerance,
                  "--forward: largest body angle error in rad (default 2e-2)")
      ->check(finite_positive());
  sub->add_option("--impact-time-tolerance", o->impact_time_tolerance,
                  "contacts: largest error of the time between two impacts of a contact, in "
                  "Box2D steps (default " +
                      std::to_string(ContactTolerances{}.interval_steps) + ")")
      ->check(finite_positive());
  sub->add_option("--impact-speed-tolerance", o->impact_speed_tolerance,
                  "contacts: largest error of an impact's approach or separation speed, "
                  "relative to the largest approach speed (default " +
                      std::to_string(ContactTolerances{}.speed) + ")")
      ->check(finite_positive());
  sub->add_option("--restitution-threshold", o->restitution_threshold,
                  "contacts: Box2D applies restitution above this approach speed in m/s "
                  "(default 0: always, as mo2d; Box2D's own default is 1)")
      ->check(finite_non_negative());
  CLI::Option* step = sub->add_option("--step", o->step,
                                      "Box2D time step in s (default 1/2000; a forward check "
                                      "halves the default until no body turns more than 0.01 "
                                      "rad per step)")
                          ->check(finite_positive());
  sub->add_option(
         "--point-mass-inertia", o->inertia_fraction,
         "give point masses on massless links I = f m L^2 in both engines (Box2D cannot "
         "turn a body without inertia; the comparison does not depend on f); default 1/12, "
         "0: refuse them")
      ->check(finite_non_negative());
  sub->add_option("--feedback-time", o->feedback_time,
                  "time constant of the motors' position feedback in s (0: none)")
      ->check(finite_non_negative());
  sub->add_option("--reference-set", o->reference_set,
                  "override a parameter in mo2d's model only (Box2D keeps the scene's value): "
                  "shows which modelling errors the cross-check detects; repeatable")
      ->check(name_equals_value());
  sub->add_flag("--strict", o->strict,
                "kept for old scripts: a disagreement always exits with status 3");
  return {sub, [o, step] {
            o->step_set = step->count() > 0;
            return crosscheck(*o);
          }};
}

}  // namespace mo2d::cli
