// Bad velocity-level constraints in scene files (`constraints: NAME: {g: ...}`): every one is
// reported as "file:line:column: what was expected", a wrong label at its column in the
// expression with a suggestion, a g that is not linear in the rates at the constraint.
#include <gtest/gtest.h>

#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A disc rolling on the line y = r; each test replaces one piece. Lines are numbered from 1.
const std::string kBase = R"yaml(name: disc
parameters:
  r: 0.2
bodies:
  disc:
    nodes: {C: [0, r]}
    mass: 1
    inertia: 0.02
constraints:
  on_line: {psi: disc.C.y - r}
  rolls: {g: disc.C.vx + r * disc.w}
loads:
  gravity: [1, -9.81]
initial:
  velocities: {disc.w: 0}
run: {solve: forward}
)yaml";

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

std::string error_of(const std::string& text) {
  try {
    const Scene s = parse_scene(text, "bad.yaml");
    build_scene_model(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& text, const std::string& where, const std::string& what) {
  const std::string e = error_of(text);
  EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
  EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
}

TEST(RollingSceneErrors, BaseSceneIsValid) {
  EXPECT_EQ(error_of(kBase), "");
  const Scene s = parse_scene(kBase, "ok.yaml");
  const Model m = build_scene_model(s);
  EXPECT_EQ(m.dof, 1);
  EXPECT_FALSE(m.holonomic);
}

// The model's labels are known only when it is built: the error names the label at its column,
// with the closest coordinate or quasi-velocity label.
TEST(RollingSceneErrors, UnknownLabelAtItsColumnWithSuggestion) {
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.vx + r * disc.wz}"),
               "bad.yaml:11:30",
               "constraint 'rolls': unknown coordinate or quasi-velocity 'disc.wz' (did you mean "
               "'disc.w'?)");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: \"disc.C.vxx + r * disc.w\"}"),
               "bad.yaml:11:15", "unknown coordinate or quasi-velocity 'disc.C.vxx' (did you mean");
  // a name that is neither a parameter nor a label: the same error (it could be a typo of either)
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.vx + rr * disc.w}"),
               "bad.yaml:11:26", "unknown coordinate or quasi-velocity 'rr'");
  // a block scalar folded over lines: at its indicator (>-)
  expect_error(replaced("{g: disc.C.vx + r * disc.w}",
                        "\n    g: >-\n      disc.C.vx\n"
                        "      + r * disc.ww"),
               "bad.yaml:12:8", "'disc.ww' (did you mean 'disc.w'?)");
}

TEST(RollingSceneErrors, UnknownLabelInAPositionConstraintAtItsColumnToo) {
  expect_error(replaced("{psi: disc.C.y - r}", "{psi: disc.C.yy - r}"), "bad.yaml:10:18",
               "constraint 'on_line': unknown coordinate 'disc.C.yy' (did you mean 'disc.C.y'?)");
}

TEST(RollingSceneErrors, NotLinearInTheRates) {
  // a square of one rate: named
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.vx^2 + r * disc.w}"),
               "bad.yaml:11:3", "constraint 'rolls': g is not linear in 'disc.C.vx'");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.vx + r * abs(disc.w)}"),
               "bad.yaml:11:3", "g is not linear in 'disc.w'");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: sin(disc.C.vx) + r * disc.w}"),
               "bad.yaml:11:3", "g is not linear in 'disc.C.vx'");
  // a product of two rates: zero along each alone
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.vx * disc.w + disc.C.vy}"),
               "bad.yaml:11:3", "g is not linear in the quasi-velocities (a product of rates?)");
  // coefficients may depend on coordinates and time, and a term free of rates is allowed
  EXPECT_EQ(error_of(replaced("{g: disc.C.vx + r * disc.w}",
                              "{g: \"(1 + disc.C.x^2) * disc.C.vx + r * cos(t) * disc.w - 0.1\"}")),
            "");
}

TEST(RollingSceneErrors, WrongKeysAndForms) {
  // the velocity-level key is g; psi and g together, neither, or another key are refused
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{rate: disc.C.vx + r * disc.w}"),
               "bad.yaml:11:11", "unknown key 'rate'; expected one of: psi, g");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{gg: disc.C.vx + r * disc.w}"),
               "bad.yaml:11:11", "unknown key 'gg' (did you mean 'g'?)");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{psi: disc.C.x, g: disc.C.vx}"),
               "bad.yaml:11:10", "give exactly one of 'psi' (position level");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{}"), "bad.yaml:11:10",
               "give exactly one of 'psi'");
  // only coordinates: not a velocity constraint
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: disc.C.x - 1}"), "bad.yaml:11:3",
               "constraint 'rolls': uses no quasi-velocity");
  expect_error(replaced("{g: disc.C.vx + r * disc.w}", "{g: r + t}"), "bad.yaml:11:14",
               "a constraint must use at least one quasi-velocity");
}

// In a subsystem the labels are local; the error names the prefixed label at the subsystem's line.
TEST(RollingSceneErrors, LabelInASubsystemInstance) {
  const std::string text = R"yaml(name: two
subsystems:
  roller:
    bodies:
      disc: {nodes: {C: [0, 0.2]}, mass: 1, inertia: 0.02}
    constraints:
      on_line: {psi: disc.C.y - 0.2}
      rolls: {g: disc.C.vx + 0.2 * disc.v}
instances:
  a: {subsystem: roller}
run: {solve: forward}
)yaml";
  expect_error(text, "bad.yaml:8:36",
               "constraint 'a.rolls': unknown coordinate or quasi-velocity 'a.disc.v' (did you "
               "mean 'a.disc.w'?)");
}

}  // namespace
}  // namespace mo2d
