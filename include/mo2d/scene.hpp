#pragma once
// Scene files: a mechanism, its loads, its motion or initial state and the run settings in one
// YAML document (reference: docs/scene-format.md). load_scene() reads and checks the file and
// returns the System plus everything a run needs; every error names file:line:column.
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/contact_inverse.hpp"
#include "mo2d/control.hpp"
#include "mo2d/design.hpp"
#include "mo2d/error.hpp"
#include "mo2d/extremes.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"
#include "mo2d/output_columns.hpp"
#include "mo2d/system.hpp"

namespace mo2d {

// Where something was written: 1-based line and column (0 = unknown).
struct Location {
  // the scene file's path as given
  std::string file{};
  // 1-based line and column (0: unknown)
  int line = 0, column = 0;
  std::string str() const;  // "file:line:column" (or "file" when the line is unknown)
};

// An error in a scene: what() is "file:line:column: message".
class SceneError : public Error {
 public:
  // The error `message` at `where`.
  SceneError(const Location& where, const std::string& message);
  // Where the error is in the scene.
  const Location& where() const { return where_; }
  // The message without the location.
  const std::string& message() const { return message_; }

 private:
  Location where_{};
  std::string message_{};
};

// What a scene's run computes: inverse dynamics (a prescribed motion) or forward dynamics (the
// motion from the efforts).
enum class Solve { inverse, forward };

// A scene's `run:` block (docs/scene-format.md, "run"): what to solve, over which times, with which
// integrator, budgets and outputs.
struct RunSettings {
  // inverse or forward dynamics
  Solve solve = Solve::inverse;
  // start time (s)
  double t0 = 0;
  double duration = 1;       // s; t1 = t0 + duration
  int samples = 0;           // 0: 501 (inverse) or 101 (forward)
  double tolerance = 1e-12;  // inverse: position tolerance |psi|_inf relative to the model size
  // forward: the integrator and the equations of the accelerations (ForwardOptions)
  Integrator integrator = Integrator::cvode_bdf;
  Formulation formulation = Formulation::augmented_lagrangian;
  LinearAlgebra linear_algebra = LinearAlgebra::automatic;  // forward: dense or sparse matrices
  double rtol = 1e-8, atol = 1e-10;                         // forward, CVODE
  double step = 1e-3;                                       // forward, fixed-step integrators
  // forward: > 0, the accuracy asked for (ForwardOptions::accuracy): mo2d picks the integrator and
  // its tolerances, and integrator, rtol, atol and step are not used; 0: not asked for
  double accuracy = 0;
  // forward: run.integrator, rtol, atol or step written (in the scene or as a flag). Without them
  // and without accuracy, a forward run asks for kDefaultAccuracy (forward_options).
  bool method_set = false;
  // forward: the a-posteriori estimate of the global error (ForwardOptions::error_estimate)
  ErrorEstimate error_estimate = ErrorEstimate::automatic;
  int max_steps = kDefaultMaxSteps;         // forward: step budget of the run
  double max_seconds = kDefaultMaxSeconds;  // wall-clock budget of the run
  double max_memory = kDefaultMaxMemory;    // bytes of dense matrices and results
  bool csv = true, json = true;             // outputs
};

// A label written in the scene (prescribed coordinate, initial value, effort) with its place, so
// that a label the model does not have is reported at the line that wrote it.
struct LabelUse {
  // the label as written
  std::string label{};
  // what the label names: a coordinate, a quasi-velocity (rate) or an input
  enum class Kind { coordinate, rate, input } kind = Kind::coordinate;
  // where it was written
  Location where{};
};

// A controller of the scene (`controllers:`): PD feedback on a coordinate towards a reference,
// the effort of one input (mo2d/control.hpp).
struct SceneController {
  std::string input{};                // input label ("crank_pivot.torque")
  PdControl control{};                // its feed_forward: the expression given, if any
  bool feed_forward_inverse = false;  // feed-forward from inverse dynamics of the references
  // where the controller was written
  Location where{};
};

// A label read by the expression of an element (a constraint), with the instance prefixes.
struct ExpressionLabel {
  // the label read
  std::string label{};
  // the element whose expression reads it
  std::string element{};
  // where it was written
  Location where{};
};

// A scene file (docs/scene-format.md) read by load_scene(): the mechanism as a System, the run
// (motion or initial conditions, efforts, controllers, settings), the requested outputs and where
// every element was written.
struct Scene {
  // the file's path
  std::string file{};
  // the scene's name (its `name:`; the prefix of the output files)
  std::string name{};
  std::vector<std::pair<std::string, double>> parameters{};  // in dependency order, evaluated
  // the mechanism
  System system{};
  std::vector<Prescribed> motion{};  // inverse: one per DOF
  InitialConditions initial{};       // forward
  // forward: input label -> effort law (of t, or of t and the state: a feedback)
  std::vector<std::pair<std::string, Law>> efforts{};
  std::vector<SceneController> controllers{};  // forward: feedback efforts
  // the `run:` block
  RunSettings run{};
  // `outputs:` the columns mo2d inverse / forward add to the CSV (add_output_columns): every
  // named point unless told otherwise, loads and centres of mass when asked.
  OutputRequest outputs{.all_points = true};
  // `contacts:` unilateral contacts (mo2d/contact.hpp, docs/contact.md): a forward run of a scene
  // with any is a contact run (scene_forward), in the order written
  std::vector<ContactDef> contacts{};
  std::vector<Location> contact_where{};  // where each contact is written (its name's key)
  // the contact run's settings of `run:` (max_events, zeno_time, zeno_speed, baumgarte_rate); its
  // forward options are the run's (scene_forward sets them)
  ContactOptions contact{};
  // `design:` the designer's measures mo2d inverse / forward add to the CSV and the JSON summary
  // (add_design_columns, design_summary; mo2d/design.hpp, docs/design.md); none by default.
  DesignRequest design{};
  // every label the scene writes, with its place (checked by build_scene_model)
  std::vector<LabelUse> labels{};
  // element name -> definition (run keys as "run.t0", "run.step", ...)
  std::vector<std::pair<std::string, Location>> elements{};
  // "element/label" -> where a law (a load's, an effort's) names a quantity of the state
  std::vector<std::pair<std::string, Location>> law_labels{};
  // labels read by constraint expressions, so that a label the model refuses is reported at its
  // column
  std::vector<ExpressionLabel> expression_labels{};
};

// A parameter override "name=value" (value: an expression of the other parameters).
struct ParameterOverride {
  // the parameter's name
  std::string name{};
  // its new value: an expression of the other parameters
  std::string value{};
};
ParameterOverride parse_override(std::string_view name_equals_value);  // throws Error

// A run setting given on the command line: `key` a key of the scene's `run:` block that a run
// may override (kRunOverrideKeys), `value` its text as the scene would write it (a number may be
// an expression of the parameters). Applied on top of the scene's `run:` block with the same
// checks; a refusal is a SceneError at Location{"--KEY"} (the key with '-' for '_', as the mo2d
// flag: "--max-steps: run.max_steps: must be >= 1"), and so are the later refusals of
// check_scene_options for that key.
struct RunOverride {
  // the run key ("step", "max_steps", ...)
  std::string key{};
  // its value as text
  std::string value{};
};
// The keys of `run:` a RunOverride may set.
inline constexpr const char* kRunOverrideKeys[] = {
    "t0",          "duration",   "samples",        "tolerance", "integrator",
    "formulation", "rtol",       "atol",           "step",      "max_steps",
    "max_seconds", "max_memory", "linear_algebra", "accuracy",  "error_estimate"};
std::string run_override_flag(const std::string& key);  // "max_steps" -> "--max-steps"

// Read a scene file / text. Throws SceneError (file:line:column) on any problem.
Scene load_scene(const std::string& path, std::span<const ParameterOverride> overrides = {},
                 std::span<const RunOverride> run_overrides = {});
Scene parse_scene(std::string_view yaml, const std::string& file_name = "<scene>",
                  std::span<const ParameterOverride> overrides = {},
                  std::span<const RunOverride> run_overrides = {});

// The scene text `yaml` (read from `file`, for messages) with each parameter of `values` given
// that number: its value's text replaced in place (the shortest text that reads back to the same
// double), everything else kept (comments, layout, the other parameters, which follow it as
// expressions). The result is read back and checked: a SceneError when a parameter is not in
// the parameters: block or does not read back to its value.
std::string set_parameter_values(std::string_view yaml, const std::string& file,
                                 std::span<const std::pair<std::string, double>> values);

// build_model() plus the checks that need the model: the labels the scene uses exist (else a
// SceneError at their line, with a suggestion); a build error is reported against the file.
Model build_scene_model(const Scene& scene, const BuildOptions& options = {});

// Run options of the scene's settings.
InverseOptions inverse_options(const Scene& scene);
// Efforts are ordered like Model::inputs (inputs without an effort get none: zero); a controller
// gives its input the PD law, with the exact feed-forward from inverse dynamics of the
// controllers' references if asked (all controllers asking it together must prescribe the DOF).
// A scene that names no method (run.integrator, rtol, atol, step) nor an accuracy asks for
// kDefaultAccuracy; forward_dynamics then chooses the method (choose_method: explicit unless
// stiff at the initial state).
ForwardOptions forward_options(const Scene& scene, const Model& model);
// check_inverse_options / check_forward_options (and the model's magnitudes), a refusal reported
// as a SceneError at the line of the run key it names (run.t0, run.step, ...; the file alone for
// a setting left at its default or overridden on the command line).
void check_scene_options(const Scene& scene, const Model& model, const InverseOptions& options);
void check_scene_options(const Scene& scene, const Model& model, const ForwardOptions& options);
// Tracking error e = x - r of each controller over a forward run of the scene's model: the
// signed error of largest |e| and its time, and e at the last sample (rad or m).
struct TrackingError {
  // the controlled input's label and the label of its coordinate
  std::string input, coordinate;
  // the largest error (signed; rad or m), its time (s), and the error at the last sample
  double max_error = 0, t_max = 0, final_error = 0;
};
// The TrackingError of every controller of the scene over the forward run r.
std::vector<TrackingError> tracking_errors(const Scene& scene, const Model& model,
                                           const Trajectory& r);
// Consistent initial state of a forward run (consistent_state with the scene's initial values).
State initial_state(const Scene& scene, const Model& model);

// A forward run of a scene: its trajectory and, with contacts, the contact events in time order.
struct SceneRun {
  Trajectory trajectory;             // the run (kind forward)
  std::vector<ContactEvent> events;  // contacts: every onset, exit, impact, lift-off, Zeno
};
// Forward dynamics of the scene's model from `initial` with o (forward_options): forward_dynamics,
// or, for a scene with contacts, contact_dynamics with them and the run's contact settings. An
// accuracy asked for (o.accuracy, also the default) then runs the method options_for_accuracy
// gives it, without the stiffness test and the error estimate (contact_dynamics takes a method;
// stats.method says so). An error naming a contact before the run starts (a point it cannot find,
// a contact that starts penetrating) is a SceneError at the contact's line.
SceneRun scene_forward(const Scene& scene, const Model& model, const State& initial,
                       const ForwardOptions& o);
// The extremes of a forward run r of the scene (o: the options scene_forward ran): located
// between the samples (locate_extremes), or for a scene with contacts the samples' own
// (sampled_extremes: a re-integration between samples would not know the contacts).
std::vector<Extreme> scene_forward_extremes(const Scene& scene, const Model& model,
                                            const ForwardOptions& o, const Trajectory& r);
// The model of a scene's inverse run: build_scene_model, and for a scene with contacts the model
// with its rigid contacts closed at the start held closed (hold_closed_contacts,
// mo2d/contact_inverse.hpp; docs/contact.md, "Inverse dynamics"); an error naming a contact is a
// SceneError at its line.
ContactInverseModel scene_inverse_model(const Scene& scene, const BuildOptions& options = {});
// A SceneError at the scene's file unless its motion prescribes one coordinate per DOF of m, the
// model of its inverse run; `held` (scene_inverse_model's contacts) names the held contacts, which
// took one DOF each.
void check_inverse_motion(const Scene& scene, const Model& m,
                          const std::vector<InverseContact>& held = {});
// For a scene with contacts, after the inverse run r of its scene_inverse_model m
// (inverse_options(scene)): report_contact_forces (the contacts' report in `report`, a warning in
// r.stats.warnings for each that goes negative; an Error naming a contact left out that the
// motion closes, and the time).
void scene_inverse_contacts(const Scene& scene, const Model& m, std::vector<InverseContact>& report,
                            const InverseOptions& options, Trajectory& r);
// A SceneError at the scene's first contact if it has contacts: `what` (the cross-check, modes)
// does not take them into account yet. Nothing for a scene without contacts.
void refuse_contacts(const Scene& scene, const std::string& what);
// The designer's measures a run of the scene adds: its design: block, and with `measures` also the
// frame's shaking force and moment and every joint's bearing load. A SceneError at the scene's
// first contact for a scene with contacts (the measures read the joints' reactions, not the
// contact forces).
DesignRequest scene_design_request(const Scene& scene, bool measures);

}  // namespace mo2d
