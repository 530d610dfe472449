// The drawing module's entry point (draw_module.hpp): the subcommands that draw with Cairo or
// compare with Box2D, added one by one to the executable's command table (in its order). Only
// this symbol is exported (hidden visibility; the static libraries' symbols kept local).
#include <cstring>
#include <string_view>

#include "command.hpp"
#include "draw_module.hpp"
#include "mo2d/output.hpp"

extern "C" __attribute__((visibility("default"))) bool mo2d_add_drawing_command(
    const char* version, const char* name, CLI::App* app, mo2d::cli::Command* out) {
  using namespace mo2d::cli;
  if (std::strcmp(version, MO2D_VERSION) != 0) return false;
  if (!name) {
    // This module has its own copy of the output code (mo2d/output.hpp): its handler removes the
    // temporaries of the files it writes (installed first, so the executable's is not).
    mo2d::remove_temporaries_on_signal();
    return true;
  }
  const std::string_view n = name;
  Command (*add)(CLI::App&) = n == "demo"         ? add_demo_command
                              : n == "render"     ? add_render_command
                              : n == "view"       ? add_view_command
                              : n == "crosscheck" ? add_crosscheck_command
                              : n == "plot"       ? add_plot_command
                              : n == "modes"      ? add_modes_command
                              : n == "linearize"  ? add_linearize_command
                                                  : nullptr;
  if (!add) return false;
  *out = add(*app);
  return true;
}
