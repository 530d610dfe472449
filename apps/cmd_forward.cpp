// mo2d forward SCENE [--set name=value]... [--out DIR] [--units-row] [run settings]: forward
// dynamics of a scene from its initial state; writes DIR/NAME_forward.csv and
// DIR/NAME_forward.json (both or neither).
#include <cstdio>
#include <optional>

#include "command.hpp"
#include "design_output.hpp"
#include "mo2d/mo2d.hpp"
#include "scene_options.hpp"
#include "summary.hpp"
#include "table.hpp"

namespace mo2d::cli {

namespace {

int forward(const SceneOptions& o) {
  const Scene scene = load_scene_with_overrides(o);
  const Model model = build_model_of(scene);
  ForwardOptions run = forward_options(scene, model);
  check_scene_options(scene, model, run);
  const State initial = initial_state(scene, model);
  Progress progress("forward dynamics of '" + model.name + "'", run.t0, run.t1);
  run.progress = [&progress](double t) { progress.update(t); };
  run.monitor = [&progress](const RunProgress& p) { progress.report(p); };
  SceneRun ran = scene_forward(scene, model, initial, run);  // with the contacts, if any
  Trajectory& r = ran.trajectory;
  if (scene.run.accuracy == 0 && !scene.run.method_set)  // no method named: kDefaultAccuracy
    r.stats.method = "default " + r.stats.method;
  add_output_columns(model, r, scene.outputs);  // the columns the scene asks for
  run.progress = {};
  run.monitor = {};
  const std::vector<Extreme> extremes =
      scene_forward_extremes(scene, model, run, r);  // the peaks between samples
  std::optional<DesignSummary> design;               // the designer's measures (docs/design.md)
  if (wants_design(scene, o.measures)) {             // (their columns after the extremes' columns)
    const DesignRequest request = scene_design_request(scene, o.measures);
    add_design_columns(model, r, request);
    design = design_summary(model, r, request);
  }
  progress.finish();
  std::printf("mo2d forward dynamics: %s\n", model.name.c_str());
  print_forward_table(model, r, run);
  print_peaks_table(r, extremes);
  if (design) print_design_table(r, *design);
  print_tracking_table(tracking_errors(scene, model, r));
  print_contact_events(ran.events);
  // all outputs land together or not at all (mo2d/output.hpp)
  OutputSet out;
  if (scene.run.csv)
    out.add(output_path(o, scene, "forward.csv"),
            trajectory_csv(
                r, o.units_row ? trajectory_csv_units(model, r) : std::vector<std::string>{}));
  if (scene.run.json)
    out.add(output_path(o, scene, "forward.json"),
            forward_summary(o, scene, model, r, run, extremes,
                            design ? design_json(r, *design) : std::string(), ran.events));
  out.commit();
  for (const auto& path : out.paths()) std::printf("  wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

Command add_forward_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* sub = app.add_subcommand(
      "forward", "Forward dynamics of a scene from its initial state under its loads and efforts");
  add_scene_options(sub, *o, true, RunFlags::forward);
  sub->add_flag("--measures", o->measures,
                "add the designer's measures: the frame's shaking force and moment, every joint's "
                "bearing load, the efforts' RMS and peak-to-peak (docs/design.md)");
  sub->add_flag("--units-row", o->units_row,
                "write the unit of every column as a second header line of the CSV (the JSON "
                "summary lists them either way)");
  return {sub, [o] { return forward(*o); }};
}

}  // namespace mo2d::cli
