// mo2d modes SCENE [--set name=value]... [--out DIR] [--amplitude F] [--filmstrip]
//   [--coordinates L,...] [--outputs L,...]: the static equilibrium nearest the scene's initial
//   configuration (under its gravity, springs and effort laws at t0), its stiffness and stability,
//   the vibration modes (natural frequency in rad/s and Hz, damping ratio) and a picture of each
//   (the mechanism at +- F x size along the mode, superposed); writes DIR/NAME_modes.json and
//   DIR/NAME_mode<k>.png (and _mode<k>_filmstrip.png), all or none.
// mo2d linearize SCENE --at t=T [...]: the linearization about the scene's run at time T (the
//   forward run from its initial state, or the inverse run with its efforts held), written as
//   DIR/NAME_G.csv, _H.csv, _C.csv, _D.csv and _linearization.json (docs/linearization.md).
// mo2d linearize SCENE --at t=A:B:N: along the run, at N equally spaced times from A to B, all in
//   the same independent coordinates (linearize_along): DIR/NAME_G_along.csv (one row per time
//   and state), _H_along.csv, _C_along.csv, _D_along.csv and _linearization_along.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "command.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/modes.hpp"
#include "mode_pictures.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

struct ModesCliOptions {
  SceneOptions scene{};
  double amplitude = 0.1;  // largest node displacement in the pictures, fraction of the size
  bool filmstrip = false, pictures = true;
  std::string at = "";  // linearize: "t=T"
  std::vector<std::string> coordinates{}, outputs{};
};

LinearizeOptions linearize_options(const ModesCliOptions& o, const Scene& s, const Model& m) {
  LinearizeOptions lo;
  lo.coordinates = o.coordinates;
  lo.outputs = o.outputs;
  lo.forward = forward_options(s, m);
  return lo;
}

// One wall-time budget for the whole command (run.max_seconds, --max-seconds): each stage (the
// reference run, the equilibrium, the linearization, the modes) gets what is left of it.
class CommandBudget {
 public:
  explicit CommandBudget(const Scene& s)
      : max_seconds_(s.run.max_seconds), start_(std::chrono::steady_clock::now()) {}
  double left() const {
    if (!(max_seconds_ > 0) || !std::isfinite(max_seconds_)) return max_seconds_;
    const double used =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return std::max(max_seconds_ - used, 1e-3);
  }

 private:
  double max_seconds_;
  std::chrono::steady_clock::time_point start_;
};

ModesOptions modes_options(const Scene& s, const CommandBudget& b) {
  return {.max_seconds = b.left(), .max_memory = s.run.max_memory};
}

void print_modes(const StateSpace& ss, const std::vector<Mode>& modes) {
  std::printf("  states: ");
  for (size_t i = 0; i < ss.states.size(); ++i)
    std::printf("%s%s", i ? ", " : "", ss.states[i].c_str());
  std::printf("\n  %-4s %14s %12s %12s %12s  %s\n", "mode", "omega_n rad/s", "f_n Hz", "zeta",
              "omega_d", "eigenvalue");
  for (size_t k = 0; k < modes.size(); ++k) {
    const Mode& md = modes[k];
    const char* kind = md.rigid ? "  (rigid / drift)" : md.oscillatory ? "" : "  (real)";
    std::printf("  %-4zu %14.8g %12.8g %12.6g %12.8g  %.6g %+.6gi%s\n", k + 1, md.omega_n, md.hz,
                md.damping_ratio + 0.0, md.omega_d, md.eigenvalue.real(), md.eigenvalue.imag(),
                kind);
  }
}

void print_equilibrium(const Model& m, const Equilibrium& e) {
  std::printf(
      "mo2d modes: %s\n  equilibrium: %d Newton iterations, |a| = %.3g m/s^2 at rest, largest "
      "coordinate change %.6g (m or rad)\n",
      m.name.c_str(), e.iterations, e.residual, e.moved);
  for (int i = 0; i < e.linear.p; ++i)
    std::printf("    %s = %.12g\n", e.linear.states[i].c_str(),
                e.state.q0[e.linear.coordinate_vars[i]]);
  if (e.stiffness_eigenvalues.size()) {
    std::printf("  reduced stiffness eigenvalues:");
    for (int i = 0; i < e.stiffness_eigenvalues.size(); ++i)
      std::printf(" %.6g", e.stiffness_eigenvalues[i]);
    std::printf(" (asymmetry %.2g)\n", e.asymmetry);
  }
  std::printf("  stability: %s\n", e.stability.c_str());
}

int modes(const ModesCliOptions& o) {
  const Scene scene = load_scene_with_overrides(o.scene);
  refuse_contacts(scene, "linearization and modes");
  const CommandBudget budget(scene);
  const Model model = build_model_of(scene);
  EquilibriumOptions eo;
  eo.t = scene.run.t0;
  eo.linearize = linearize_options(o, scene, model);
  // from the initial state of a forward scene, the assembled configuration of an inverse one
  const VectorXd start =
      scene.run.solve == Solve::forward ? initial_state(scene, model).q0 : model.q0;
  eo.linearize.forward.max_seconds = budget.left();
  const Equilibrium e = static_equilibrium(model, start, eo);
  print_equilibrium(model, e);
  const std::vector<Mode> ms = vibration_modes(e.linear, modes_options(scene, budget));
  print_modes(e.linear, ms);
  OutputSet files;
  OutputSet::Scope scope(files);
  files.add(output_path(o.scene, scene, "modes.json"), state_space_json(e.linear, ms));
  const double amplitude = o.amplitude * model.scale;
  for (size_t k = 0; o.pictures && k < ms.size(); ++k) {
    if (ms[k].rigid || ms[k].dz.size() == 0 || ms[k].dz.isZero()) continue;
    const std::string tag = "mode" + std::to_string(k + 1);
    write_mode_picture(model, e.linear, ms[k], static_cast<int>(k + 1), amplitude,
                       output_path(o.scene, scene, tag + ".png"));
    if (o.filmstrip)
      write_mode_filmstrip(model, e.linear, ms[k], static_cast<int>(k + 1), amplitude,
                           output_path(o.scene, scene, tag + "_filmstrip.png"));
  }
  files.commit();
  for (const auto& p : files.paths()) std::printf("  wrote %s\n", p.c_str());
  return 0;
}

// --at t=A:B:N: N >= 2 times from A to B; {} for a single time.
struct TimeRange {
  double a = 0, b = 0;
  int n = 0;
};
bool range_of(const std::string& at, TimeRange& r) {
  if (at.rfind("t=", 0) != 0 || at.find(':') == std::string::npos) return false;
  const std::string body = at.substr(2);
  const size_t c1 = body.find(':'), c2 = body.find(':', c1 + 1);
  if (c2 == std::string::npos || body.find(':', c2 + 1) != std::string::npos)
    throw Error("--at: expected t=A:B:N (N times from A to B), got '" + at + "'", "--at");
  try {
    size_t ua = 0, ub = 0, un = 0;
    const std::string sa = body.substr(0, c1), sb = body.substr(c1 + 1, c2 - c1 - 1),
                      sn = body.substr(c2 + 1);
    r.a = std::stod(sa, &ua);
    r.b = std::stod(sb, &ub);
    r.n = std::stoi(sn, &un);
    if (ua != sa.size() || ub != sb.size() || un != sn.size()) throw std::invalid_argument(at);
  } catch (const std::logic_error&) {
    throw Error("--at: '" + at + "' is not t=A:B:N with numbers A < B and an integer N >= 2",
                "--at");
  }
  if (!std::isfinite(r.a) || !std::isfinite(r.b) || !(r.a < r.b) || r.n < 2 || r.n > 100000)
    throw Error("--at: '" + at + "' needs finite A < B and 2 <= N <= 100000", "--at");
  return true;
}

double time_of(const std::string& at, double t0) {
  if (at.empty()) return t0;
  if (at.rfind("t=", 0) != 0) throw Error("--at: expected t=TIME, got '" + at + "'", "--at");
  const std::string number = at.substr(2);
  char* end = nullptr;
  const double t = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(t))
    throw Error("--at: '" + at + "' is not t=<number> (a finite time in s)", "--at");
  return t;
}

// The times of --at lie on the scene's run [t0, t0 + duration] (a run to a later time would be
// a run the scene did not ask for, to any length: t = 1e300 integrated until its budget ran out).
void check_on_run(const Scene& s, double a, double b) {
  const double t0 = s.run.t0, t1 = s.run.t0 + s.run.duration;
  auto text = [](double t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", t);
    return std::string(buf);
  };
  if (a < t0)
    throw Error("--at: t = " + text(a) +
                    " s is before the scene's run, which starts at t0 = " + text(t0) + " s",
                "--at");
  if (b > t1)
    throw Error("--at: t = " + text(b) +
                    " s is after the end of the scene's run, t0 + duration = " + text(t1) +
                    " s: lengthen the run with --duration (or --t0)",
                "--at");
}

// The scene's state (and, for an inverse scene, its efforts held constant) at time t.
State reference_state(const Scene& s, const Model& m, double t, LinearizeOptions& lo,
                      const CommandBudget& budget) {
  if (s.run.solve == Solve::forward) {
    const State start = initial_state(s, m);
    if (t == start.t) return start;
    ForwardOptions run = forward_options(s, m);
    run.max_seconds = budget.left();
    run.t1 = t;
    run.samples = 2;
    const Trajectory r = forward_dynamics(m, start, run);
    return {t, r.q0.row(1).transpose(), r.q1.row(1).transpose()};
  }
  InverseOptions run = inverse_options(s);
  run.max_seconds = budget.left();
  const bool first = t == run.t0;
  run.t1 = first ? run.t0 + 1e-3 : t;
  run.samples = 2;
  const Trajectory r = inverse_dynamics(m, s.motion, run);
  const int i = first ? 0 : 1;
  lo.forward.efforts.clear();
  for (int k = 0; k < m.n_inputs(); ++k)
    lo.forward.efforts.push_back(Law::constant(r.efforts(i, k)));
  return {t, r.q0.row(i).transpose(), r.q1.row(i).transpose()};
}

int linearize_along_command(const ModesCliOptions& o, const TimeRange& tr);

int linearize_command(const ModesCliOptions& o) {
  if (TimeRange tr; range_of(o.at, tr)) return linearize_along_command(o, tr);
  const Scene scene = load_scene_with_overrides(o.scene);
  refuse_contacts(scene, "linearization and modes");
  const CommandBudget budget(scene);
  const Model model = build_model_of(scene);
  LinearizeOptions lo = linearize_options(o, scene, model);
  const double t = time_of(o.at, scene.run.t0);
  check_on_run(scene, t, t);
  const State ref = reference_state(scene, model, t, lo, budget);
  lo.forward.max_seconds = budget.left();
  const StateSpace ss = linearize(model, ref, lo);
  const std::vector<Mode> ms = vibration_modes(ss, modes_options(scene, budget));
  std::printf("mo2d linearize: %s at t = %g s (%d states, %d inputs, %d outputs), |drift| = %.3g\n",
              model.name.c_str(), ss.t, ss.n(), static_cast<int>(ss.inputs.size()),
              static_cast<int>(ss.outputs.size()), ss.drift.norm());
  print_modes(ss, ms);
  OutputSet out;
  for (char c : {'G', 'H', 'C', 'D'})
    out.add(output_path(o.scene, scene, std::string(1, c) + ".csv"), state_space_csv(ss, c));
  out.add(output_path(o.scene, scene, "linearization.json"), state_space_json(ss, ms));
  out.commit();
  for (const auto& p : out.paths()) std::printf("  wrote %s\n", p.c_str());
  return 0;
}

// The scene's run sampled at the range's times: a forward scene's run to A, then from there with
// N samples to B; an inverse scene's run from A to B (its efforts are held at each sample).
Trajectory reference_run(const Scene& s, const Model& m, const TimeRange& tr,
                         const CommandBudget& budget) {
  if (s.run.solve == Solve::forward) {
    State start = initial_state(s, m);
    ForwardOptions run = forward_options(s, m);
    run.max_seconds = budget.left();
    if (tr.a > run.t0) {
      ForwardOptions to_a = run;
      to_a.t1 = tr.a;
      to_a.samples = 2;
      const Trajectory r = forward_dynamics(m, start, to_a);
      start = {tr.a, r.q0.row(1).transpose(), r.q1.row(1).transpose()};
    }
    run.t0 = tr.a;
    run.t1 = tr.b;
    run.samples = tr.n;
    run.max_seconds = budget.left();
    return forward_dynamics(m, start, run);
  }
  InverseOptions run = inverse_options(s);
  run.max_seconds = budget.left();
  run.t0 = tr.a;
  run.t1 = tr.b;
  run.samples = tr.n;
  return inverse_dynamics(m, s.motion, run);
}

int linearize_along_command(const ModesCliOptions& o, const TimeRange& tr) {
  const Scene scene = load_scene_with_overrides(o.scene);
  refuse_contacts(scene, "linearization and modes");
  const CommandBudget budget(scene);
  const Model model = build_model_of(scene);
  LinearizeOptions lo = linearize_options(o, scene, model);
  check_on_run(scene, tr.a, tr.b);
  const Trajectory r = reference_run(scene, model, tr, budget);
  lo.forward.max_seconds = budget.left();
  const std::vector<StateSpace> along = linearize_along(model, r, lo);
  const StateSpace& f = along.front();
  std::printf(
      "mo2d linearize: %s along its run, %d times from t = %g to %g s (%d states, %d "
      "inputs, %d outputs)\n  states: ",
      model.name.c_str(), tr.n, tr.a, tr.b, f.n(), static_cast<int>(f.inputs.size()),
      static_cast<int>(f.outputs.size()));
  for (size_t i = 0; i < f.states.size(); ++i)
    std::printf("%s%s", i ? ", " : "", f.states[i].c_str());
  double worst = 1, largest = 0;
  for (const StateSpace& ss : along) {
    worst = std::min(worst, ss.conditioning);
    largest = std::max(largest, ss.G.cwiseAbs().maxCoeff());
  }
  std::printf("\n  conditioning of the coordinates >= %.3g, largest |G| entry %.6g\n", worst,
              largest);
  OutputSet out;
  for (char c : {'G', 'H', 'C', 'D'})
    out.add(output_path(o.scene, scene, std::string(1, c) + "_along.csv"),
            state_space_along_csv(along, c));
  out.add(output_path(o.scene, scene, "linearization_along.json"), state_space_along_json(along));
  out.commit();
  for (const auto& p : out.paths()) std::printf("  wrote %s\n", p.c_str());
  return 0;
}

void add_common(CLI::App* sub, ModesCliOptions& o) {
  add_scene_options(sub, o.scene, true);
  sub->add_option("--coordinates", o.coordinates,
                  "the independent coordinates (q0 labels; default: chosen by pivoting)")
      ->delimiter(',');
  sub->add_option("--outputs", o.outputs,
                  "outputs y = C x + D u: coordinates, rates, quantities (body angles, joint "
                  "angles and rates, spring lengths, named points)")
      ->delimiter(',');
}

}  // namespace

Command add_modes_command(CLI::App& app) {
  auto o = std::make_shared<ModesCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "modes", "Static equilibrium, stiffness, vibration modes and their pictures");
  add_common(sub, *o);
  sub->add_option("--amplitude", o->amplitude,
                  "largest node displacement in the mode pictures, fraction of the size (0.1)")
      ->check(finite_positive());
  sub->add_flag("--filmstrip", o->filmstrip, "also a filmstrip of one period of each mode");
  sub->add_flag("!--no-pictures", o->pictures, "no mode pictures");
  return {sub, [o] { return modes(*o); }};
}

Command add_linearize_command(CLI::App& app) {
  auto o = std::make_shared<ModesCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "linearize", "State-space model dx/dt = G x + H u, y = C x + D u about the run at a time");
  add_common(sub, *o);
  sub->add_option("--at", o->at,
                  "t=TIME on the scene's run (default: its start), or t=A:B:N: N times from A "
                  "to B along it, in the same coordinates");
  return {sub, [o] { return linearize_command(*o); }};
}

}  // namespace mo2d::cli
