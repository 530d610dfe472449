#pragma once
// A subcommand of the mo2d tool: one file per subcommand defines add_<name>_command(), which
// declares its options on the CLI11 app and returns the function that runs it. Adding a
// subcommand = one file + one line in mo2d.cpp's table.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace mo2d::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run{};  // exit status; throws on failure (reported by main)
};

Command add_demo_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_inverse_command(CLI::App& app);
Command add_forward_command(CLI::App& app);
Command add_render_command(CLI::App& app);
Command add_view_command(CLI::App& app);  // cmd_view.cpp
Command add_crosscheck_command(CLI::App& app);
Command add_plot_command(CLI::App& app);
Command add_modes_command(CLI::App& app);      // cmd_modes.cpp
Command add_linearize_command(CLI::App& app);  // cmd_modes.cpp
Command add_sweep_command(CLI::App& app);
Command add_optimize_command(CLI::App& app);  // cmd_optimize.cpp
Command add_doctor_command(CLI::App& app);    // cmd_doctor.cpp

}  // namespace mo2d::cli
