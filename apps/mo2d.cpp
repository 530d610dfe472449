// mo2d command-line tool: `mo2d SUBCOMMAND ...` (mo2d --help). Each subcommand lives in its own
// cmd_<name>.cpp and is registered by one line in the table below. Without arguments, `mo2d`
// runs `mo2d demo` (as before the subcommands existed). Failures print one line
// "mo2d: error: ..." on stderr and exit with status 1 (2 for a command-line usage error).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <vector>

#include "command.hpp"
#include "mo2d/error.hpp"
#include "mo2d/output.hpp"

// Building the command table throws only on a programming error (CLI::ConstructionError, a name
// registered twice), which should abort; every error of a run is caught below.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape)
  using namespace mo2d::cli;
  // SIGINT/SIGTERM/SIGHUP remove the temporaries of unfinished output files (mo2d/output.hpp)
  mo2d::remove_temporaries_on_signal();
  CLI::App app{"mo2d: dynamics of planar mechanisms (scene files: docs/scene-format.md)", "mo2d"};
  app.require_subcommand(0, 1);
  app.fallthrough(false);
  const std::vector<Command> commands = {
      add_demo_command(app),    add_info_command(app),   add_inverse_command(app),
      add_forward_command(app), add_render_command(app), add_crosscheck_command(app),
      add_sweep_command(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "mo2d: error: %s (see mo2d --help)\n", e.what());
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
    return commands.front().run();     // no subcommand: the demo
  } catch (const std::exception& e) {  // mo2d::Error, SceneError (file:line:col), file system
    std::fprintf(stderr, "mo2d: error: %s\n", e.what());
    return 1;
  }
}
