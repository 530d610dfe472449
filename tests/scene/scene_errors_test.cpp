// Scene errors: every bad input is reported as "file:line:column: what was expected".
#include <gtest/gtest.h>

#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A valid scene; each test replaces one piece of it. Lines are numbered from 1 ("name: p").
const std::string kBase = R"yaml(name: p
parameters:
  L: 1.0
  m: 2.0
ground:
  O: [0, 0]
bodies:
  link:
    nodes: {O: [0, 0], P: [L, 0]}
    mass: m
    inertia: 0.1
    com: P
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
loads:
  gravity: [0, -9.81]
  torques:
    brake: {body: link, torque: -0.1 * t}
motion:
  link.angle: sin(t)
)yaml";

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The message of the error raised by loading (and building) `text`, "" if none.
std::string error_of(const std::string& text, std::vector<ParameterOverride> overrides = {}) {
  try {
    const Scene s = parse_scene(text, "bad.yaml", overrides);
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

TEST(SceneErrors, BaseSceneIsValid) {
  EXPECT_EQ(error_of(kBase), "");
}

TEST(SceneErrors, MalformedYaml) {
  expect_error(replaced("nodes: {O: [0, 0], P: [L, 0]}", "nodes: {O: [0, 0], P: [L, 0]"),
               "bad.yaml:10:5", "YAML: ");
}

TEST(SceneErrors, UnknownKeyWithSuggestion) {
  expect_error(replaced("    mass: m", "    masss: m"), "bad.yaml:10:5",
               "body 'link': unknown key 'masss' (did you mean 'mass'?)");
  expect_error(replaced("coordinates:", "coordinate:"), "bad.yaml:15:1",
               "unknown key 'coordinate' (did you mean 'coordinates'?)");
}

TEST(SceneErrors, MissingRequiredField) {
  expect_error(replaced("    mass: m\n", ""), "bad.yaml:9:5",
               "body 'link': missing required key 'mass'");
  expect_error(replaced("node_b: link.O, ", ""), "bad.yaml:14:10",
               "joint 'pivot': missing required key 'node_b'");
}

TEST(SceneErrors, WrongType) {
  expect_error(replaced("mass: m", "mass: [1, 2]"), "bad.yaml:10:11",
               "body 'link'.mass: expected a number or an expression, got a sequence");
  expect_error(replaced("actuated: true", "actuated: 3"), "bad.yaml:14:71",
               "expected true or false, got '3'");
  expect_error(replaced("P: [L, 0]", "P: [L, 0, 0]"), "bad.yaml:9:27",
               "expected a point [x, y], got 3 values");
}

TEST(SceneErrors, UndefinedReferences) {
  expect_error(replaced("node_b: link.O", "node_b: link.Q"), "bad.yaml:14:53",
               "undefined node 'link.Q' (did you mean 'link.O'?)");
  expect_error(replaced("{body: link,", "{body: lnik,"), "bad.yaml:20:19",
               "undefined body 'lnik' (did you mean 'link'?)");
  expect_error(replaced("com: P", "com: Q"), "bad.yaml:12:10", "body 'link' has no node 'Q'");
  expect_error(replaced("mass: m", "mass: 2 * mm"), "bad.yaml:10:15",
               "undefined name 'mm' (did you mean 'm'?)");
  expect_error(replaced("  link.angle: sin(t)", "  link.angel: sin(t)"), "bad.yaml:22:3",
               "unknown coordinate 'link.angel' (did you mean 'link.angle'?)");
  expect_error(replaced("rate: {link.w: 1}", "rate: {link.ww: 1}"), "bad.yaml:16:3",
               "unknown quasi-velocity");
}

TEST(SceneErrors, BadExpression) {
  expect_error(replaced("inertia: 0.1", "inertia: 0.1 + * 2"), "bad.yaml:11:20",
               "expected a number, a name or '('");
  expect_error(replaced("inertia: 0.1", "inertia: \"sinn(1)\""), "bad.yaml:11:15",
               "unknown function 'sinn' (did you mean 'sin'?)");
  expect_error(replaced("inertia: 0.1", "inertia: 0.1 * t"), "bad.yaml:11:14",
               "a constant is expected here");
  expect_error(replaced("L: 1.0\n  m: 2.0", "L: m\n  m: 2 * L"), "bad.yaml:3:6",
               "parameters depend on each other in a cycle");
}

TEST(SceneErrors, NegativeMassOrInertia) {
  expect_error(replaced("mass: m", "mass: -m"), "bad.yaml:10:11", "a mass must be >= 0 kg");
  expect_error(replaced("inertia: 0.1", "inertia: -0.1"), "bad.yaml:11:14",
               "an inertia must be >= 0");
}

TEST(SceneErrors, UnknownChoices) {
  expect_error(replaced("type: revolute", "type: revolut"), "bad.yaml:14:17",
               "unknown joint type 'revolut' (did you mean 'revolute'?)");
  expect_error(kBase + "run: {solve: inverze}\n", "bad.yaml:23:14",
               "run.solve: unknown value 'inverze' (did you mean 'inverse'?)");
  expect_error(kBase + "instances: {leg: {subsystem: lge}}\nsubsystems: {leg: {}}\n",
               "bad.yaml:23:30", "undefined subsystem 'lge' (did you mean 'leg'?)");
}

TEST(SceneErrors, DuplicateKey) {
  expect_error(replaced("    inertia: 0.1\n", "    inertia: 0.1\n    inertia: 0.2\n"),
               "bad.yaml:12:5", "key 'inertia' appears twice");
}

TEST(SceneErrors, OverridesOfUnknownParameters) {
  const std::string e = error_of(kBase, {parse_override("mm=3")});
  EXPECT_NE(e.find("'mm' is not a parameter of bad.yaml (did you mean 'm'?)"), std::string::npos)
      << e;
  EXPECT_THROW(parse_override("m"), Error);
  const std::string e2 = error_of(kBase, {parse_override("m=2*")});
  EXPECT_NE(e2.find("m=2*: "), std::string::npos) << e2;
}

TEST(SceneErrors, DeepNesting) {
  const std::string yaml = "name: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  EXPECT_NE(error_of(yaml).find("YAML: nested too deeply"), std::string::npos) << error_of(yaml);
  const std::string expr =
      "name: p\nparameters: {a: \"" + std::string(300, '(') + "1" + std::string(300, ')') + "\"}\n";
  EXPECT_NE(error_of(expr).find("expression nested too deeply"), std::string::npos);
  EXPECT_LT(error_of(expr).size(), 300u);  // the expression is shortened in the message
}

TEST(SceneErrors, MissingFile) {
  try {
    load_scene("/nonexistent/scene.yaml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/scene.yaml: cannot open the scene file");
  }
}

}  // namespace
}  // namespace mo2d
