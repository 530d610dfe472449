// mo2d inverse SCENE [--set name=value]... [--out DIR] [--units-row] [run settings]: inverse
// dynamics of a scene; writes DIR/NAME_inverse.csv and DIR/NAME_inverse.json (both or neither).
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "command.hpp"
#include "design_output.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene_sensitivity.hpp"
#include "scene_options.hpp"
#include "sensitivity_output.hpp"
#include "summary.hpp"
#include "table.hpp"

namespace mo2d::cli {

namespace {

// The parameter models of --sensitivity (mo2d/scene_sensitivity.hpp): the scene file read again
// with each parameter moved, under the same --set and run flags.
std::vector<ParameterModels> sensitivity_models(const SceneOptions& o,
                                                const std::vector<std::string>& names,
                                                const Scene& scene, const Model& model,
                                                const InverseOptions& run) {
  std::ifstream in(o.scene, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<ParameterOverride> set;
  for (const std::string& s : o.set) set.push_back(parse_override(s));
  BuildOptions build;  // as inverse_model_of builds the run's model
  build.max_memory = scene.run.max_memory;
  return scene_parameter_models(text.str(), scene, set, o.run, names, model, build, run);
}

int inverse(const SceneOptions& o, const std::vector<std::string>& sensitivity) {
  const Scene scene = load_scene_with_overrides(o);
  // with contacts: those closed at the start held closed (docs/contact.md, "Inverse dynamics")
  ContactInverseModel held = inverse_model_of(scene);
  const Model& model = held.model;
  check_inverse_motion(scene, model, held.contacts);
  InverseOptions run = inverse_options(scene);
  check_scene_options(scene, model, run);
  Progress progress("inverse dynamics of '" + model.name + "'", run.t0, run.t1, "samples");
  run.monitor = [&progress](const RunProgress& p) { progress.report(p); };
  Trajectory r;
  std::vector<ParameterModels> parameters;
  InverseSensitivity sens;
  if (sensitivity.empty()) {
    r = inverse_dynamics(model, scene.motion, run);
  } else {  // exact derivatives of the efforts and reactions (docs/design.md, "Sensitivities")
    parameters = sensitivity_models(o, sensitivity, scene, model, run);
    sens = inverse_dynamics_sensitivity(model, scene.motion, run, parameters, r);
  }
  scene_inverse_contacts(scene, model, held.contacts, run,
                         r);                    // the contacts' forces; warnings where they pull
  add_output_columns(model, r, scene.outputs);  // the columns the scene asks for
  const std::vector<Extreme> extremes =
      locate_extremes(model, scene.motion, run, r, scene.outputs);  // the peaks between samples
  std::optional<DesignSummary> design;    // the designer's measures (docs/design.md)
  if (wants_design(scene, o.measures)) {  // (their columns after the extremes' columns)
    const DesignRequest request = scene_design_request(scene, o.measures);
    add_design_columns(model, r, request);
    design = design_summary(model, r, request);
  }
  if (!parameters.empty()) add_sensitivity_columns(r, sens);  // after the located extremes
  progress.finish();
  std::printf("mo2d inverse dynamics: %s\n", model.name.c_str());
  print_inverse_table(model, r, run);
  print_inverse_contacts(held.contacts);
  print_peaks_table(r, extremes);
  if (design) print_design_table(r, *design);
  if (!parameters.empty()) print_sensitivity_table(r, sens);
  // all outputs land together or not at all (mo2d/output.hpp)
  OutputSet out;
  if (scene.run.csv)
    out.add(output_path(o, scene, "inverse.csv"),
            trajectory_csv(
                r, o.units_row ? trajectory_csv_units(model, r) : std::vector<std::string>{}));
  if (scene.run.json) {
    std::string summary =
        inverse_summary(o, scene, model, r, run, extremes,
                        design ? design_json(r, *design) : std::string(), held.contacts);
    if (!parameters.empty()) summary = add_sensitivity_json(summary, r, sens, parameters);
    out.add(output_path(o, scene, "inverse.json"), summary);
  }
  out.commit();
  for (const auto& path : out.paths()) std::printf("  wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

Command add_inverse_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  auto sensitivity = std::make_shared<std::vector<std::string>>();
  CLI::App* sub = app.add_subcommand(
      "inverse", "Inverse dynamics of a scene: efforts and reactions for its prescribed motion");
  add_scene_options(sub, *o, true, RunFlags::inverse);
  sub->add_flag("--measures", o->measures,
                "add the designer's measures: the frame's shaking force and moment, every joint's "
                "bearing load, the efforts' RMS and peak-to-peak (docs/design.md)");
  sub->add_flag("--units-row", o->units_row,
                "write the unit of every column as a second header line of the CSV (the JSON "
                "summary lists them either way)");
  sub->add_option("--sensitivity", *sensitivity,
                  "exact derivatives of every effort and reaction (and of their peak, RMS, ...) to "
                  "these parameters of the scene's parameters: block, comma-separated: columns "
                  "d(COLUMN)/d(NAME) and the JSON's \"sensitivities\"; parameters of mass data "
                  "and loads only (docs/design.md, \"Sensitivities\")")
      ->delimiter(',');
  return {sub, [o, sensitivity] { return inverse(*o, *sensitivity); }};
}

}  // namespace mo2d::cli
