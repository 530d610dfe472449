// Locating and loading the drawing module (draw_module.hpp).
#include "draw_module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <span>
#include <string_view>

namespace mo2d::cli {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kCoreCommands[] = {"info",     "inverse", "forward",  "sweep",
                                              "optimize", "doctor",  "--version"};
constexpr std::string_view kDrawingCommands[] = {"demo", "render", "view",     "crosscheck",
                                                 "plot", "modes",  "linearize"};

bool first_argument_in(int argc, char** argv, std::span<const std::string_view> names) {
  if (argc <= 1) return false;
  for (const auto name : names)
    if (argv[1] == name) return true;
  return false;
}

// Where the module may be, in the order tried.
std::vector<std::string> module_paths() {
  if (const char* env = std::getenv("MO2D_DRAW_MODULE"); env && *env) return {env};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const fs::path dir = exe.parent_path();
  return {(dir / "mo2d_draw.so").string(),
          (dir / MO2D_DRAW_INSTALL_REL / "mo2d_draw.so").lexically_normal().string()};
}

}  // namespace

bool needs_drawing_commands(int argc, char** argv) {
  return !first_argument_in(argc, argv, kCoreCommands);
}

bool names_drawing_command(int argc, char** argv) {
  return first_argument_in(argc, argv, kDrawingCommands);
}

AddDrawingCommand load_drawing_module(std::string& why) {
  const std::vector<std::string> paths = module_paths();
  std::string tried;
  for (const auto& path : paths) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      tried += (tried.empty() ? "" : ", ") + path + " (missing)";
      continue;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += (tried.empty() ? "" : ", ") + path + " (" + ::dlerror() + ")";
      continue;
    }
    // POSIX: a function pointer from dlsym's object pointer
    auto add = reinterpret_cast<AddDrawingCommand>(::dlsym(handle, kDrawEntry));
    if (!add) {
      tried += (tried.empty() ? "" : ", ") + path + " (no entry point " + kDrawEntry + ")";
      continue;
    }
    if (!add(MO2D_VERSION, nullptr, nullptr, nullptr)) {
      tried += (tried.empty() ? "" : ", ") + path + " (built for another version of mo2d)";
      continue;
    }
    return add;
  }
  why = "the drawing module mo2d_draw.so (Cairo, Box2D), which cannot be loaded: tried " +
        (tried.empty() ? std::string("no path (/proc/self/exe unreadable)") : tried) +
        "; build the target mo2d_draw or reinstall mo2d, or set MO2D_DRAW_MODULE to its path";
  return nullptr;
}

}  // namespace mo2d::cli
