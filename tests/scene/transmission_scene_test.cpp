// The transmission element from scene files (mechanisms/gearbox.yaml): full and lumped fidelity
// of the same text agree on every housing signal, the pivot's reaction and gearbox.phi to solver
// tolerance (the housing pinned off its centre of mass and swinging, then free in the plane);
// the full fidelity agrees with the train written by hand (mechanisms/gear_train.yaml); bad input
// is refused at its line.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace transmission_scene_test {

std::string scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

Trajectory run(const std::string& text, double t1 = 1.5) {
  const Scene scene = parse_scene(text, "gearbox.yaml");
  const Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  o.t1 = t1;
  o.samples = 16;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  o.accuracy = 0;  // the tolerances above, not the scene's accuracy
  return forward_dynamics(m, initial_state(scene, m), o);
}

double q0(const Trajectory& r, int i, const std::string& c) {
  return r.q0(i, r.column(c));
}
double q1(const Trajectory& r, int i, const std::string& c) {
  return r.q1(i, r.rate_column(c));
}

// Every housing signal and gearbox.phi of the full and lumped runs of `text`.
void expect_fidelities_agree(const std::string& text, bool pinned) {
  const Trajectory full = run(text);
  const Trajectory lumped = run(replaced(text, "    fidelity: full ", "    fidelity: lumped "));
  ASSERT_EQ(full.time.size(), lumped.time.size());
  EXPECT_NO_THROW((void)full.rate_column("idler.w"));  // the shafts, and A and B
  EXPECT_NO_THROW((void)lumped.rate_column("gearbox_a.w"));
  EXPECT_THROW((void)lumped.rate_column("idler.w"), Error);
  for (int i = 0; i < full.time.size(); ++i) {
    const double t = full.time[i];
    for (const char* c : {"case.G.x", "case.G.y", "gearbox.phi"})
      EXPECT_NEAR(q0(full, i, c), q0(lumped, i, c), 1e-8) << c << " at " << t;
    if (!pinned) {
      for (const char* c : {"case.O.x", "case.O.y"})
        EXPECT_NEAR(q0(full, i, c), q0(lumped, i, c), 1e-8) << c << " at " << t;
    }
    for (const char* c : {"case.w", "gearbox.phi.rate"}) {
      EXPECT_NEAR(q1(full, i, c), q1(lumped, i, c), 1e-7) << c << " at " << t;
      EXPECT_NEAR(full.a1(i, full.rate_column(c)), lumped.a1(i, lumped.rate_column(c)), 1e-6)
          << c << " at " << t;
    }
    if (pinned) {
      for (const char* c : {"pivot.Fx", "pivot.Fy"})
        EXPECT_NEAR(full.reactions(i, full.reaction(c)), lumped.reactions(i, lumped.reaction(c)),
                    1e-6)
            << c << " at " << t;
    }
  }
  EXPECT_GT(std::abs(q0(full, full.time.size() - 1, "gearbox.phi")), 1.0);  // the train turns
  EXPECT_GT(std::abs(q1(full, full.time.size() - 1, "case.w")), 0.05);      // the housing moves
}

TEST(TransmissionScene, FullAndLumpedAgreeOnAPinnedHousing) {
  const std::string text = text_of(scene_path("gearbox"));
  expect_fidelities_agree(replaced(text, "velocities: {case.w: 0, gearbox.phi.rate: 0}",
                                   "velocities: {case.w: 0.8, gearbox.phi.rate: 3}"),
                          true);
}

TEST(TransmissionScene, FullAndLumpedAgreeOnAFreeHousing) {
  std::string text = text_of(scene_path("gearbox"));
  text = replaced(text, "  pivot: {type: revolute, node_a: ground.O, node_b: case.O}\n", "");
  text = replaced(text, "joints:\n", "");
  text = replaced(text, "velocities: {case.w: 0, gearbox.phi.rate: 0}",
                  "velocities: {case.w: 0.8, gearbox.phi.rate: 3, case.O.vx: 0.3, case.O.vy: 1.5}");
  expect_fidelities_agree(text, false);
}

// The full fidelity is the train of gear_train.yaml (without the gearbox's load torque).
TEST(TransmissionScene, FullFidelityIsTheTrainWrittenByHand) {
  const std::string text = replaced(text_of(scene_path("gearbox")), "load: -0.1", "load: 0");
  const Trajectory a = run(text);
  const Trajectory b = run(text_of(scene_path("gear_train")));
  for (int i = 0; i < a.time.size(); ++i) {
    for (const char* c : {"case.w", "input.w", "idler.w", "output.w"})
      EXPECT_NEAR(q1(a, i, c), q1(b, i, c), 1e-7) << c << " at " << a.time[i];
    for (const char* c : {"case.G.x", "case.G.y"}) EXPECT_NEAR(q0(a, i, c), q0(b, i, c), 1e-8) << c;
    for (const char* c : {"pivot.Fx", "pivot.Fy"})
      EXPECT_NEAR(a.reactions(i, a.reaction(c)), b.reactions(i, b.reaction(c)), 1e-6) << c;
    EXPECT_NEAR(q0(a, i, "gearbox.phi"), q0(b, i, "first.phi") - q0(b, 0, "first.phi"), 1e-8);
  }
  EXPECT_GT(std::abs(q1(a, a.time.size() - 1, "input.w")), 2.0);
}

std::string error_of(const std::string& text) {
  try {
    build_scene_model(parse_scene(text, "bad.yaml"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const std::string kBox = R"yaml(name: box
bodies:
  case: {nodes: {O: [0, 0], X: [0.1, 0]}, mass: 1, inertia: 0.1}
transmissions:
  box:
    housing: HOUSING
    input: INPUT
    shafts:
      a: {axis: [0, 0], mass: 0.1, inertia: INERTIA}
      b: {axis: [0.05, 0], mass: 0.1, inertia: 0.01, ratio: -2}
)yaml";

std::string box(const std::string& housing, const std::string& input, const std::string& inertia) {
  return replaced(replaced(replaced(kBox, "HOUSING", housing), "INPUT", input), "INERTIA", inertia);
}

void expect_error(const std::string& text, const std::string& at, const std::string& what) {
  const std::string e = error_of(text);
  EXPECT_NE(e.find(at), std::string::npos) << e;
  EXPECT_NE(e.find(what), std::string::npos) << e;
}

TEST(TransmissionScene, BadInputAtItsLine) {
  EXPECT_EQ(error_of(box("case", "a", "0.001")), "");
  EXPECT_EQ(
      error_of(replaced(box("case", "a", "0.001"), "input: a", "input: a\n    fidelity: lumped")),
      "");
  expect_error(box("cse", "a", "0.001"), "bad.yaml:6:14", "undefined body 'cse' (did you mean");
  expect_error(box("case", "a", "-0.001"), "bad.yaml:9:45", "shaft 'a'.inertia: must be >= 0");
  expect_error(box("case", "c", "0.001"), "bad.yaml:7:12", "'c' is not one of its shafts");
  std::string none = box("case", "a", "0.001");
  none = none.substr(0, none.find("    shafts:")) + "    shafts: {}\n";
  expect_error(none, "bad.yaml:8:13", "at least one shaft");
  expect_error(replaced(box("case", "a", "0.001"), "input: a", "input: a\n    fidelity: lumpd"),
               "bad.yaml:8:15", "did you mean 'lumped'");
  expect_error(box("case", "b", "0.001"), "bad.yaml:10:", "input shaft's ratio is 1");
}

}  // namespace transmission_scene_test
}  // namespace mo2d
