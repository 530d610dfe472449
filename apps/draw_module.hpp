#pragma once
// The drawing commands (demo, render, crosscheck, plot, modes, linearize) live in a module loaded
// at run time, mo2d_draw.so (apps/draw_entry.cpp): it links Cairo's X11/xcb/fontconfig chain and
// Box2D, whose loading costs about as much CPU as a short run, so the other commands (info,
// inverse, forward, sweep, --version) start without them (docs/performance.md, "CLI start-up").
// The module is looked for in $MO2D_DRAW_MODULE, else beside the executable (build tree), else in
// BIN/MO2D_DRAW_INSTALL_REL (install tree: PREFIX/lib/mo2d), located through /proc/self/exe.
#include <CLI/CLI.hpp>
#include <string>

#include "command.hpp"

namespace mo2d::cli {

// The module's entry point (extern "C", found by dlsym): false if it was built for another
// `version` or knows no command `name`; else adds the subcommand `name` to `app` and sets `out`.
// With name == nullptr: only the version check (and the module's signal handler installed).
using AddDrawingCommand = bool (*)(const char* version, const char* name, CLI::App* app,
                                   Command* out);
inline constexpr const char* kDrawEntry = "mo2d_add_drawing_command";

// Whether the command line asks for a drawing command, or for something that lists them (no
// arguments, --help, an unknown subcommand): everything but info, inverse, forward, sweep, doctor
// (which loads the module itself) and --version.
bool needs_drawing_commands(int argc, char** argv);
// Whether argv[1] names a drawing command.
bool names_drawing_command(int argc, char** argv);

// Loads the module and returns its entry point. On failure returns nullptr with `why` (the paths
// tried and the loader's message); the module is never unloaded (its code runs until exit).
AddDrawingCommand load_drawing_module(std::string& why);

}  // namespace mo2d::cli
