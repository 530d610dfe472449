// mo2d doctor: which parts of mo2d this build has and can use, and how to get a missing one (the
// Debian package and the CMake option). The core (the library, scene files, the command line) is
// checked by a run: a pendulum's pivot torque against its closed form; the exit status is 0 when
// it works, 1 otherwise, whatever optional part is missing. The optional parts: the drawing module
// (Cairo pictures, the Box2D cross-check) and its font, the Python package and the Python
// libraries Debian's python3 can import, what the build configuration includes (tests,
// benchmarks, the MuJoCo comparison) and the development tools on PATH.
#include <dlfcn.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "draw_module.hpp"
#include "mo2d/mo2d.hpp"
#include "python_package.hpp"

namespace mo2d::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kReconfigure = "then configure and build again (./scripts/test.sh does both)";

int missing_count = 0;

void line(bool ok, const std::string& what, const std::string& detail) {
  if (!ok) ++missing_count;
  std::printf("  %-8s %s%s%s\n", ok ? "ok" : "missing", what.c_str(), detail.empty() ? "" : ": ",
              detail.c_str());
}

// The pendulum of the README: a 1 kg point mass at the tip of a 1 m link on an actuated pivot,
// theta(t) = 0.5 sin 3t; the largest difference of the pivot torque from m L^2 theta'' +
// m g L cos(theta) over 21 samples (N m).
double pendulum_error() {
  const double L = 1, mass = 1, g = 9.81;
  System s("pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {L, 0}}},
              .mass = mass,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O", .actuated = true});
  s.add_coordinate({.name = "link.angle", .rate = {{"link.w", 1.0}}});
  s.set_gravity({0, -g});
  InverseOptions run;
  run.t1 = 2;
  run.samples = 21;
  const std::vector<Prescribed> motion = {{"link.angle", [](Jet t) { return 0.5 * sin(3.0 * t); }}};
  const Trajectory r = inverse_dynamics(build_model(s), motion, run);
  const int u = r.effort("pivot.torque");
  double error = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const double th = 0.5 * std::sin(3 * r.time[k]), th_dd = -4.5 * std::sin(3 * r.time[k]);
    const double expected = mass * L * L * th_dd + mass * g * L * std::cos(th);
    error = std::fmax(error, std::abs(r.efforts(k, u) - expected));
  }
  return error;
}

bool check_core() {
  std::printf("core (required)\n");
  try {
    const double error = pendulum_error();
    char detail[160];
    std::snprintf(detail, sizeof detail,
                  "a pendulum's pivot torque against its closed form, error %.2g N m", error);
    const bool ok = error < 1e-9;  // (the README's example: 1.3e-11 over 201 samples)
    std::printf(
        "  %-8s library (Eigen, SUNDIALS, SuiteSparse), scene files (yaml-cpp), command "
        "line: %s\n",
        ok ? "ok" : "FAILED", detail);
    return ok;
  } catch (const std::exception& e) {
    std::printf("  %-8s library: the pendulum's inverse dynamics failed: %s\n", "FAILED", e.what());
    return false;
  }
}

void check_drawing() {
  std::printf("drawing: demo, render, view, crosscheck, plot, modes, linearize\n");
  std::string why;
  const AddDrawingCommand add = load_drawing_module(why);
  std::string where;
  Dl_info info{};
  // POSIX: the module's file from the address of its entry point
  if (add && ::dladdr(reinterpret_cast<void*>(add), &info) != 0 && info.dli_fname)
    where = info.dli_fname;
  line(add != nullptr, "module mo2d_draw.so (Cairo pictures, Box2D cross-check)",
       add ? where
           : why +
                 " (packages libcairo2-dev libbox2d-dev zlib1g-dev pkg-config; target "
                 "mo2d_draw, built with mo2d_cli)");
  const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  std::error_code ec;
  line(fs::exists(font, ec), "font DejaVu Sans (the text of pictures)",
       fs::exists(font, ec) ? font : "sudo apt-get install fonts-dejavu-core");
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// "name status ..." lines printed by the interpreter: mo2d imported, the others found.
std::map<std::string, std::string> python_report(const std::string& python, bool with_mo2d,
                                                 int& status) {
  const std::string script =
      "import importlib.util, sys\n"
      "print('python', sys.version.split()[0])\n" +
      std::string(with_mo2d
                      ? "try:\n"
                        "    import mo2d\n"
                        "    print('mo2d ok', mo2d.__file__)\n"
                        "except Exception as e:\n"
                        "    print('mo2d error', type(e).__name__, str(e).split(chr(10))[0])\n"
                      : "") +
      "for m in ('numpy', 'pandas', 'dask', 'distributed', 'matplotlib', 'pytest'):\n"
      "    print(m, 'ok' if importlib.util.find_spec(m) else 'missing')\n";
  std::map<std::string, std::string> out;
  std::fflush(stdout);
  FILE* p = ::popen((shell_quote(python) + " -c " + shell_quote(script) + " 2>&1").c_str(), "r");
  if (!p) {
    status = -1;
    return out;
  }
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, p)) {
    std::string text(buffer);
    if (!text.empty() && text.back() == '\n') text.pop_back();
    const auto space = text.find(' ');
    if (space != std::string::npos) out[text.substr(0, space)] = text.substr(space + 1);
  }
  status = ::pclose(p);
  return out;
}

void check_python() {
  std::printf("Python\n");
  const std::string built = python_executable();
  std::string python = built;
  if (python.empty()) python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string dir = python_package_dir();
  if (!dir.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = old != nullptr && *old != 0 ? dir + ":" + old : dir;
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  int status = 0;
  const auto report = python_report(python, !built.empty(), status);
  if (!report.contains("python")) {
    line(false, "python3", python + " does not run: sudo apt-get install python3");
    return;
  }
  line(true, "python3 " + report.at("python"), python);
  if (built.empty()) {
    line(false, "package mo2d",
         "this mo2d was built without it: sudo apt-get install pybind11-dev python3-pybind11 "
         "python3-dev, cmake -DMO2D_PYTHON=ON (the release preset), " +
             std::string(kReconfigure));
  } else {
    const auto it = report.find("mo2d");
    const bool ok = it != report.end() && it->second.starts_with("ok");
    const std::string env =
        dir.empty() ? std::string("python3's own sys.path") : "PYTHONPATH=" + dir;
    line(ok, "package mo2d (import mo2d; mo2d sweep)",
         ok ? it->second.substr(3) + " (" + env + " " + python + ")"
            : (it == report.end() ? std::string("not imported") : it->second) + " with " + env +
                  ": build the target mo2d_python");
  }
  const std::vector<std::vector<std::string>> libraries = {
      {"numpy", "NumPy (results as arrays)", "python3-numpy"},
      {"pandas", "pandas (to_pandas, sweep tables)", "python3-pandas"},
      {"dask", "Dask (mo2d.sweep, mo2d sweep)", "python3-dask"},
      {"distributed", "dask.distributed (LocalCluster, Client)", "python3-distributed"},
      {"matplotlib", "matplotlib (the example script of docs/python.md)", "python3-matplotlib"},
      {"pytest", "pytest (tests/python)", "python3-pytest"}};
  for (const auto& l : libraries) {
    const auto it = report.find(l[0]);
    const bool ok = it != report.end() && it->second == "ok";
    line(ok, l[1], ok ? "" : "sudo apt-get install " + l[2]);
  }
}

// The executable `name` on PATH, or "".
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const fs::path file = fs::path(folder.empty() ? "." : folder) / name;
    if (::access(file.c_str(), X_OK) == 0) return file.string();
  }
  return {};
}

void check_development() {
  std::printf("development (./scripts/test.sh installs and builds these)\n");
  line(MO2D_DOCTOR_TESTS != 0, "test suite (GoogleTest)",
       MO2D_DOCTOR_TESTS != 0 ? "MO2D_BUILD_TESTS=ON"
                              : "sudo apt-get install libgtest-dev, cmake -DMO2D_BUILD_TESTS=ON, " +
                                    std::string(kReconfigure));
  line(MO2D_DOCTOR_BENCH != 0, "benchmarks (Google Benchmark)",
       MO2D_DOCTOR_BENCH != 0
           ? "MO2D_BUILD_BENCH=ON"
           : "sudo apt-get install libbenchmark-dev, cmake -DMO2D_BUILD_BENCH=ON, " +
                 std::string(kReconfigure));
  line(MO2D_DOCTOR_MUJOCO != 0, "MuJoCo (the benchmark mo2d_peers_bench, docs/performance.md)",
       MO2D_DOCTOR_MUJOCO != 0
           ? "found"
           : "sudo apt-get install libmujoco-dev, cmake -DMO2D_BUILD_BENCH=ON, " +
                 std::string(kReconfigure));
  // Siconos: a benchmark peer driven from Debian's python3 (bench/siconos_ball.py); found, not
  // imported (importing it costs 0.2 s)
  const std::string debian_python =
      fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : std::string("python3");
  const std::string find =
      "import importlib.util, sys; sys.exit(importlib.util.find_spec('siconos') is None)";
  std::fflush(stdout);
  const bool siconos =
      std::system(
          (shell_quote(debian_python) + " -c " + shell_quote(find) + " >/dev/null 2>&1").c_str()) ==
      0;
  line(siconos, "Siconos (the benchmark peer bench/siconos_ball.py, docs/contact.md)",
       siconos ? debian_python + " finds python3-siconos"
               : "sudo apt-get install python3-siconos (optional: a benchmark peer only)");
  const std::vector<std::vector<std::string>> tools = {
      {"doxygen", "doxygen (the API reference, target mo2d_docs; test docs.api)", "doxygen"},
      {"clang-format", "clang-format (scripts/check-style.sh)", "clang-format"},
      {"clang-tidy", "clang-tidy (scripts/check-style.sh)", "clang-tidy"}};
  for (const auto& t : tools) {
    const std::string where = on_path(t[0]);
    line(!where.empty(), t[1], where.empty() ? "sudo apt-get install " + t[2] : where);
  }
}

int doctor() {
  std::printf("mo2d %s: what this build has and can use\n", MO2D_VERSION);
  const bool core = check_core();
  check_drawing();
  check_python();
  check_development();
  if (!core) {
    std::printf("the core does not work: see the first line above\n");
    return 1;
  }
  std::printf("the core works; %d optional part%s missing%s\n", missing_count,
              missing_count == 1 ? "" : "s", missing_count == 0 ? "" : " (how to get each: above)");
  return 0;
}

}  // namespace

Command add_doctor_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "doctor",
      "Which parts of mo2d this build has (drawing, Box2D, Python, Dask, tests, benchmarks...) "
      "and how to get a missing one; exit status 0 when the core works");
  return {sub, [] { return doctor(); }};
}

}  // namespace mo2d::cli
