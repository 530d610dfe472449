// mo2d sweep SCENE --set name=start:stop:count --set name=v1,v2 [--scheduler ADDRESS] [--jobs N]
// [-o OUT.csv]: a parameter sweep on Dask. The sweep is written in Python (python/mo2d/_sweep.py,
// docs/sweeps.md): this command replaces the process by `python3 -m mo2d sweep ARGS...`, with the
// interpreter and the package directory this build knows, so both spellings behave the same.
// The package is looked for next to this executable first (an installed tree:
// BIN/../MO2D_PYTHON_INSTALL_DIR), then in the build tree (python_package.hpp); PYTHONPATH keeps
// what it had after it.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "command.hpp"
#include "mo2d/error.hpp"
#include "python_package.hpp"

namespace mo2d::cli {

namespace {

#ifdef MO2D_PYTHON_EXECUTABLE
int sweep(const std::vector<std::string>& args) {
  const std::string dir = python_package_dir();
  if (!dir.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = old != nullptr && *old != 0 ? dir + ":" + old : dir;
    setenv("PYTHONPATH", path.c_str(), 1);
  }
  std::vector<std::string> argv = {MO2D_PYTHON_EXECUTABLE, "-m", "mo2d", "sweep"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c_argv;
  c_argv.reserve(argv.size() + 1);
  for (auto& a : argv) c_argv.push_back(a.data());
  c_argv.push_back(nullptr);
  std::fflush(stdout);
  execv(MO2D_PYTHON_EXECUTABLE, c_argv.data());
  throw Error(std::string("sweep: cannot run ") + MO2D_PYTHON_EXECUTABLE + ": " +
              std::strerror(errno));
}
#else
int sweep(const std::vector<std::string>&) {
  throw Error(
      "sweep: this mo2d was built without its Python package (configure with -DMO2D_PYTHON=ON, "
      "docs/sweeps.md)");
}
#endif

}  // namespace

Command add_sweep_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "sweep",
      "Parameter sweep of a scene on Dask, one CSV row per run (python3 -m mo2d sweep; "
      "mo2d sweep --help)");
  // every argument goes to the Python command, --help included
  sub->prefix_command();
  sub->set_help_flag();
  return {sub, [sub] { return sweep(sub->remaining()); }};
}

}  // namespace mo2d::cli
