// Run guards (issue 10, items 3, 4, 10 and 11): time grids double precision cannot resolve and
// fixed steps beyond the step budget are refused before the run; non-finite results are errors
// naming the time and the variable; budgets of steps and wall time end every run with a clear
// error; model sizes that cannot fit are refused before allocating; output files of one run land
// together or not at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "output/write_file.hpp"

namespace mo2d {
namespace {

// The pendulum of mechanisms/pendulum.yaml with `extra` appended (loads, motion, run, ...).
std::string pendulum_scene(const std::string& mass, const std::string& extra) {
  return R"(name: pendulum
parameters: {L: 1.0, m: )" +
         mass + R"(, g: 9.81}
ground: {O: [0, 0]}
bodies:
  link: {nodes: {O: [0, 0], P: [L, 0]}, mass: m, inertia: 0, com: P}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
)" + extra;
}

const char* kSwing = R"(
motion:
  link.angle: 0.5 * sin(3 * t) + t^2
initial:
  positions: {link.angle: 0.5}
  velocities: {link.w: 0}
)";

struct Loaded {
  Scene scene;
  Model model;
};
Loaded load(const std::string& text) {
  Scene s = parse_scene(text, "test.yaml");
  Model m = build_scene_model(s);
  return {std::move(s), std::move(m)};
}

// Message of the Error thrown by f ("" if none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// ---- item 3: time grid and fixed steps ----------------------------------------------------------

// step 1e-12 s over 2 s needs 2e12 steps: a static_cast<int> of the per-interval count overflowed
// and the run took 200 steps of 0.01 s with exit 0. Now refused, naming the step and the count.
TEST(RunGuards, FixedStepBeyondTheStepBudgetIsRefused) {
  const Loaded r = load(pendulum_scene("1", std::string(kSwing) + R"(
loads: {gravity: [0, -g]}
run: {solve: forward, duration: 2, samples: 201, integrator: rk4, step: 1e-12}
)"));
  const ForwardOptions o = forward_options(r.scene, r.model);
  const State s0 = initial_state(r.scene, r.model);
  const std::string msg = error_of([&] { forward_dynamics(r.model, s0, o); });
  EXPECT_NE(msg.find("step 1e-12 s over [0, 2] s needs 2e+12 steps, more than max_steps"),
            std::string::npos)
      << msg;
  // through the scene: at the line of run.step
  const std::string scene_msg = error_of([&] { check_scene_options(r.scene, r.model, o); });
  EXPECT_NE(scene_msg.find("test.yaml:"), std::string::npos) << scene_msg;
  EXPECT_NE(scene_msg.find("run.step: "), std::string::npos) << scene_msg;
  // duration 1e9 with the default step (1e-3 s): 1e12 steps, refused the same way (baumgarte too)
  ForwardOptions o2 = o;
  o2.t1 = 1e9;
  o2.step = 1e-3;
  o2.integrator = Integrator::baumgarte;
  EXPECT_NE(error_of([&] { forward_dynamics(r.model, s0, o2); }).find("needs 1e+12 steps"),
            std::string::npos);
}

// A step the budget allows still runs, and its count is exact (no integer conversion).
TEST(RunGuards, FixedStepWithinTheBudgetRuns) {
  const Loaded r = load(pendulum_scene("1", std::string(kSwing) + R"(
loads: {gravity: [0, -g]}
run: {solve: forward, duration: 0.1, samples: 11, integrator: rk4, step: 1e-5}
)"));
  const Trajectory f =
      forward_dynamics(r.model, initial_state(r.scene, r.model), forward_options(r.scene, r.model));
  EXPECT_EQ(f.stats.steps, 10000);
}

// t0 = 1e17 s: double precision resolves 16 s there, all 201 samples 0.01 s apart fell on one
// time. Refused (inverse and forward), naming t0, the spacing and the resolution.
TEST(RunGuards, TimeGridBelowTheResolutionIsRefused) {
  const std::string base = pendulum_scene("1", std::string(kSwing) + "loads: {gravity: [0, -g]}\n");
  // in a scene: at the line of run.t0, with the spacing as written (t0 + 2 s rounds to t0)
  const std::string scene_msg = error_of(
      [&] { parse_scene(base + "run: {t0: 1e17, duration: 2, samples: 201}\n", "test.yaml"); });
  EXPECT_NE(scene_msg.find("test.yaml:17:"), std::string::npos) << scene_msg;
  EXPECT_NE(scene_msg.find("run.t0: t0 = 1e+17 s: samples 0.01 s apart are not resolved by "
                           "double precision there (doubles are 16 s apart"),
            std::string::npos)
      << scene_msg;
  // through the C++ API (inverse and forward)
  const Loaded r = load(base + "run: {duration: 2, samples: 201}\n");
  InverseOptions io = inverse_options(r.scene);
  io.t0 = 1e17;
  io.t1 = 1e17 + 2;
  const std::string msg = error_of([&] { inverse_dynamics(r.model, r.scene.motion, io); });
  EXPECT_NE(msg.find("inverse dynamics: t0 = 1e+17 s: 201 samples over [1e+17, 1e+17] s, 0 s "
                     "apart, are not resolved by double precision"),
            std::string::npos)
      << msg;
  ForwardOptions fo = forward_options(r.scene, r.model);
  fo.t0 = 1e17;
  fo.t1 = 1e17 + 2;
  const State s0 = initial_state(r.scene, r.model);
  EXPECT_NE(error_of([&] { forward_dynamics(r.model, s0, fo); }).find("not resolved"),
            std::string::npos);
  // a resolvable offset runs, and its samples are distinct and equally spaced
  io.t0 = 1e6;
  io.t1 = 1e6 + 2;
  const Trajectory res = inverse_dynamics(r.model, r.scene.motion, io);
  for (int k = 1; k < res.time.size(); ++k) EXPECT_NEAR(res.time[k] - res.time[k - 1], 0.01, 1e-9);
}

// ---- item 4: non-finite results -----------------------------------------------------------------

// mass 1e308: m g L overflows, the efforts were NaN in the table, CSV and JSON with exit 0.
TEST(RunGuards, MassOutOfRangeIsRefusedNamingTheBody) {
  const Loaded r =
      load(pendulum_scene("1e308", std::string(kSwing) + "loads: {gravity: [0, -g]}\n"));
  const InverseOptions io = inverse_options(r.scene);
  const std::string msg = error_of([&] { inverse_dynamics(r.model, r.scene.motion, io); });
  EXPECT_NE(msg.find("body 'link': mass 1e+308 kg is out of range"), std::string::npos) << msg;
  const std::string scene_msg = error_of([&] { check_scene_options(r.scene, r.model, io); });
  EXPECT_NE(scene_msg.find("test.yaml:5:"), std::string::npos) << scene_msg;  // the body's line
}

// Two torques, each finite, whose sum overflows from t = 0.0572 s (1.7e308 (1 + t) > DBL_MAX):
// the first sample with a non-finite effort is an error naming the time and the effort.
const char* kOverflowingTorques = R"yaml(
loads:
  gravity: [0, -g]
  torques:
    big: {body: link, torque: 1.7e308}
    growing: {body: link, torque: "1.7e308 * min(1, t)"}
)yaml";

TEST(RunGuards, NonFiniteInverseResultNamesTimeAndVariable) {
  const Loaded r = load(pendulum_scene(
      "1", std::string(kSwing) + kOverflowingTorques + "run: {duration: 2, samples: 201}\n"));
  try {
    inverse_dynamics(r.model, r.scene.motion, inverse_options(r.scene));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NEAR(e.time(), 0.06, 1e-12) << e.what();
    EXPECT_EQ(e.element(), "pivot.torque") << e.what();
    EXPECT_NE(std::string(e.what()).find("'pivot.torque' = -inf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("are not finite at t = 0.06 s"), std::string::npos)
        << e.what();
  }
}

// Forward: the same torques; the reactions overflow at once (1.7e308 N m on a 1 m link), an error
// at t = 0 for every integrator (before: NaN columns in a returned result).
TEST(RunGuards, NonFiniteForwardResultIsAnError) {
  const Loaded r =
      load(pendulum_scene("1", std::string(kSwing) + kOverflowingTorques +
                                   "run: {solve: forward, duration: 1, samples: 101}\n"));
  const State s0 = initial_state(r.scene, r.model);
  for (Integrator i : {Integrator::rk4, Integrator::dopri5, Integrator::cvode_bdf,
                       Integrator::cvode_adams, Integrator::baumgarte}) {
    ForwardOptions o = forward_options(r.scene, r.model);
    o.integrator = i;
    try {
      const Trajectory f = forward_dynamics(r.model, s0, o);
      FAIL() << to_string(i) << ": no error, t_end " << f.stats.t_end << ", last link.w "
             << f.q1(f.q1.rows() - 1, 0);
    } catch (const Error& e) {
      EXPECT_GE(e.time(), 0.0) << to_string(i) << ": " << e.what();
      EXPECT_LE(e.time(), 0.07) << to_string(i) << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos)
          << to_string(i) << ": " << e.what();
    }
  }
}

// The CSV writers never write nan or inf.
TEST(RunGuards, CsvRefusesNonFiniteValues) {
  const Loaded r = load(pendulum_scene("1", std::string(kSwing) + "loads: {gravity: [0, -g]}\n"));
  InverseOptions io = inverse_options(r.scene);
  io.samples = 5;
  Trajectory res = inverse_dynamics(r.model, r.scene.motion, io);
  EXPECT_NO_THROW(trajectory_csv(res));
  res.efforts(3, 0) = NAN;
  const std::string msg = error_of([&] { trajectory_csv(res); });
  EXPECT_NE(msg.find("'pivot.torque' is not finite"), std::string::npos) << msg;
}

// ---- item 11: budgets and sizes -----------------------------------------------------------------

// The 40-loop chain on cvode_bdf ground for over 5 minutes: with a wall-time budget it ends in
// about that time, with an error naming the time reached and the steps.
TEST(RunGuards, WallTimeBudgetEndsARun) {
  const Scene s = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/chain40_bdf.yaml");
  const Model m = build_scene_model(s);
  ForwardOptions o = forward_options(s, m);
  o.max_seconds = 0.5;
  int monitored = 0;
  o.monitor_interval = 0.1;
  o.monitor = [&](const RunProgress& p) {
    ++monitored;
    EXPECT_GE(p.t, o.t0);
  };
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = error_of([&] { forward_dynamics(m, initial_state(s, m), o); });
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(msg.find("the wall-time budget of 0.5 s ran out at t = "), std::string::npos) << msg;
  EXPECT_NE(msg.find(" steps in "), std::string::npos) << msg;
  EXPECT_NE(msg.find("--max-seconds"), std::string::npos) << msg;
  EXPECT_LT(secs, 5.0);
  EXPECT_GE(monitored, 1);
}

// The step budget bounds the whole run, for every integrator.
TEST(RunGuards, StepBudgetEndsARun) {
  const Loaded r = load(pendulum_scene("1", std::string(kSwing) + R"(
loads: {gravity: [0, -g]}
run: {solve: forward, duration: 10, samples: 11, rtol: 1e-10, atol: 1e-12}
)"));
  const State s0 = initial_state(r.scene, r.model);
  for (Integrator i : {Integrator::cvode_bdf, Integrator::cvode_adams, Integrator::dopri5}) {
    ForwardOptions o = forward_options(r.scene, r.model);
    o.integrator = i;
    o.max_steps = 50;
    const std::string msg = error_of([&] { forward_dynamics(r.model, s0, o); });
    EXPECT_NE(msg.find("the step budget of 50 steps ran out at t = "), std::string::npos)
        << to_string(i) << ": " << msg;
  }
}

// A chain of n links pivoted end to end (2 nodes each).
System chain(int n) {
  System s("chain");
  s.add_ground_node("O", {0, 0});
  for (int k = 0; k < n; ++k) {
    std::string name = "l";  // (appends: GCC 12 warns falsely on "l" + std::string, -Wrestrict)
    name += std::to_string(k);
    std::string previous = "l";
    previous += std::to_string(k - 1);
    s.add_body({.name = name,
                .nodes = {{"A", {k, 0}}, {"B", {k + 1, 0}}},
                .mass = 1,
                .inertia = 0.1,
                .com = CenterOfMass::between("A", "B", 0.5)});
    s.add_revolute({.name = "j" + name,
                    .node_a = k == 0 ? "ground.O" : previous + ".B",
                    .node_b = name + ".A"});
  }
  return s;
}

// mo2d info on a 20,000-link chain grew to 24 GB of dense matrices. From kSparseKinematics
// (src/kinematics/sparse_kinematics.hpp) the build is sparse, O(n) in memory: the chain builds;
// a limit below its estimate still refuses it before anything is allocated, naming the size and
// the limit.
TEST(RunGuards, ModelTooLargeForTheMemoryLimitIsRefused) {
  const System big = chain(20000);
  EXPECT_EQ(build_model(big).dof, 20000);
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = error_of([&] { build_model(big, {.max_memory = 1e8}); });
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(msg.find("GB of dense matrices"), std::string::npos) << msg;
  EXPECT_NE(msg.find("more than the limit of 0.1 GB (max_memory)"), std::string::npos) << msg;
  EXPECT_LT(secs, 10.0);
  // a small chain builds; its runs are refused only when their estimate exceeds the limit
  const Model small = build_model(chain(3));
  InverseOptions io;
  io.max_memory = 1e3;
  std::vector<Prescribed> none;
  EXPECT_NE(error_of([&] { check_inverse_options(small, io); }).find("max_memory"),
            std::string::npos);
  ForwardOptions fo;
  fo.samples = 1'000'000'000;  // 1e9 samples of 20 columns: 160 GB of results
  EXPECT_NE(error_of([&] { check_forward_options(small, fo); }).find("GB of dense matrices"),
            std::string::npos);
}

// ---- item 10: outputs land together or not at all -----------------------------------------------

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  if (!std::filesystem::exists(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RunGuards, OutputSetLandsAllFilesOrNone) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("mo2d_outputs_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  {  // failure before commit: nothing left, not even the folder the set created
    OutputSet set;
    set.add((dir / "a.csv").string(), "1\n");
    set.add((dir / "a.json").string(), "{}\n");
    EXPECT_EQ(files_in(dir).size(), 2u);  // two hidden temporaries
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
  {
    OutputSet set;
    {
      OutputSet::Scope scope(set);
      write_file_atomically((dir / "a.csv").string(), "1\n");  // routed to the set
    }
    set.add((dir / "a.json").string(), "{}\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.csv"));
    set.commit();
  }
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.csv", "a.json"}));
  {  // a target that cannot be replaced: neither file changes
    std::filesystem::create_directory(dir / "b.json");
    OutputSet set;
    set.add((dir / "b.csv").string(), "2\n");
    set.add((dir / "b.json").string(), "{}\n");
    EXPECT_THROW(set.commit(), Error);
  }
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.csv", "a.json", "b.json"}));
  std::filesystem::remove_all(dir);
}

// A model without quasi-velocities (a scene without bodies: found by the run fuzzer, which made
// ForwardData take the smallest pivot of an empty mass matrix and crash) is refused by name.
TEST(RunGuards, ForwardDynamicsOfNothingIsRefused) {
  const Scene scene =
      parse_scene("run: {solve: forward, duration: 1, samples: 11}\n", "empty.yaml");
  const Model model = build_scene_model(scene);
  ASSERT_EQ(model.n1, 0);
  try {
    forward_dynamics(model, State{0, model.q0, VectorXd::Zero(0)}, forward_options(scene, model));
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no moving parts"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mo2d
