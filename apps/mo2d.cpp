// mo2d command-line tool: `mo2d SUBCOMMAND ...` (mo2d --help). Each subcommand lives in its own
// cmd_<name>.cpp and is registered by one line in the table below. Without arguments, `mo2d`
// prints its help (`mo2d demo` runs the demo); `mo2d --version` prints the project's version.
// Failures print one line "mo2d: error: ..." on stderr and exit with status 1, 2 for a
// command-line usage error (a bad option or value, a --set that names no parameter).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "command.hpp"
#include "draw_module.hpp"
#include "mo2d/error.hpp"
#include "mo2d/output.hpp"
#include "scene_options.hpp"

// Building the command table throws only on a programming error (CLI::ConstructionError, a name
// registered twice), which should abort; every error of a run is caught below.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape)
  using namespace mo2d::cli;
  CLI::App app{"mo2d: dynamics of planar mechanisms (scene files: docs/scene-format.md)", "mo2d"};
  app.require_subcommand(0, 1);
  app.fallthrough(false);
  app.set_version_flag("--version", "mo2d " MO2D_VERSION);
  // the drawing commands: from a module loaded only when asked for or listed (draw_module.hpp)
  AddDrawingCommand draw = nullptr;
  if (needs_drawing_commands(argc, argv)) {
    std::string why;
    draw = load_drawing_module(why);
    if (!draw && names_drawing_command(argc, argv)) {
      std::fprintf(stderr, "mo2d: error: '%s' needs %s\n", argv[1], why.c_str());
      return 1;
    }
    if (!draw)
      std::fprintf(stderr,
                   "mo2d: note: demo, render, view, crosscheck, plot, modes and linearize are not "
                   "available: %s\n",
                   why.c_str());
  }
  // A core command (or --version) named first: only that one is built. CLI11 builds every option
  // of every subcommand it is given, about 0.5 M instructions for the four (docs/performance.md,
  // "CLI start-up"); the help that lists them all is asked for otherwise.
  const bool core_first = !needs_drawing_commands(argc, argv);
  std::vector<Command> commands;
  auto add = [&](Command (*core)(CLI::App&), const char* name) {
    Command c;
    if (core) {
      if (!core_first || std::strcmp(argv[1], name) == 0) commands.push_back(core(app));
    } else if (draw && draw(MO2D_VERSION, name, &app, &c)) {
      commands.push_back(c);
    }
  };
  add(nullptr, "demo");
  add(add_info_command, "info");
  add(add_inverse_command, "inverse");
  add(add_forward_command, "forward");
  add(nullptr, "render");
  add(nullptr, "view");
  add(nullptr, "crosscheck");
  add(nullptr, "plot");
  add(nullptr, "modes");
  add(nullptr, "linearize");
  add(add_sweep_command, "sweep");
  add(add_optimize_command, "optimize");
  add(add_doctor_command, "doctor");
  // SIGINT/SIGTERM/SIGHUP remove the temporaries of unfinished output files (mo2d/output.hpp);
  // after the module, which installs its own handler for the files it writes
  mo2d::remove_temporaries_on_signal();
  if (argc <= 1) {  // a bare mo2d: what it can do, nothing run or written
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "mo2d: error: %s (see mo2d --help)\n", e.what());
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
    std::fputs(app.help().c_str(), stdout);  // options without a subcommand
    return 0;
  } catch (const UsageError& e) {  // a value on the command line the scene refuses
    std::fprintf(stderr, "mo2d: error: %s (see mo2d --help)\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // mo2d::Error, SceneError (file:line:col), file system
    std::fprintf(stderr, "mo2d: error: %s\n", e.what());
    return 1;
  }
}
