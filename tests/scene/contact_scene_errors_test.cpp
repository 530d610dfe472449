// Bad contacts in scene files (src/scene/load_contacts.cpp, scene_forward.cpp): each kind of
// error reported at its file:line:column with what was expected (docs/scene-format.md,
// "Contacts").
#include <gtest/gtest.h>

#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A valid contact scene; each test replaces one piece of it. Lines are numbered from 1.
const std::string kContactBase = R"yaml(name: ball
ground:
  L: [-1, 0]
  R: [1, 0]
  C: [0, -1]
bodies:
  ball:
    nodes: {C: [0, 0.5]}
    mass: 0.2
loads:
  gravity: [0, -9.81]
contacts:
  floor:
    point: ball.C
    radius: 0.05
    line: [ground.L, ground.R]
    law: rigid
    restitution: 0.8
initial:
  velocities: {ball.C.vx: 0, ball.C.vy: 0}
run:
  solve: forward
  duration: 0.1
  samples: 3
  integrator: dopri5
)yaml";

std::string contact_replaced(const std::string& from, const std::string& to) {
  std::string s = kContactBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The message of the error raised by loading, building and running `text` forward, "" if none.
std::string contact_error_of(const std::string& text) {
  try {
    const Scene s = parse_scene(text, "bad.yaml");
    const Model m = build_scene_model(s);
    const ForwardOptions o = forward_options(s, m);
    check_scene_options(s, m, o);
    scene_forward(s, m, initial_state(s, m), o);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expect_contact_error(const std::string& text, const std::string& where,
                          const std::string& what) {
  const std::string e = contact_error_of(text);
  EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
  EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
}

TEST(ContactSceneErrors, BaseSceneIsValid) {
  EXPECT_EQ(contact_error_of(kContactBase), "");
}

TEST(ContactSceneErrors, UnknownKeyAndPoint) {
  expect_contact_error(contact_replaced("    radius:", "    radios:"), "bad.yaml:15:5",
                       "contact 'floor': unknown key 'radios' (did you mean 'radius'?)");
  expect_contact_error(contact_replaced("point: ball.C", "point: ball.D"), "bad.yaml:14:12",
                       "contact 'floor'.point: undefined node or point 'ball.D'");
  expect_contact_error(contact_replaced("[ground.L, ground.R]", "[ground.L, ground.Q]"),
                       "bad.yaml:16:22",
                       "contact 'floor'.line: undefined node or point 'ground.Q'");
  expect_contact_error(contact_replaced("    point: ball.C\n", ""), "bad.yaml:14:5",
                       "contact 'floor': missing required key 'point'");
}

// friction: a number >= 0 (0.3 runs)
TEST(ContactSceneErrors, Friction) {
  expect_contact_error(
      contact_replaced("    restitution: 0.8", "    restitution: 0.8\n    friction: -1"),
      "bad.yaml:19:15", "contact 'floor'.friction: must be >= 0");
  EXPECT_EQ(contact_error_of(contact_replaced("    restitution: 0.8",
                                              "    restitution: 0.8\n    friction: 0.3")),
            "");
}

TEST(ContactSceneErrors, Targets) {
  expect_contact_error(contact_replaced("    line: [ground.L, ground.R]\n", ""), "bad.yaml:14:5",
                       "contact 'floor': no target");
  expect_contact_error(contact_replaced("    law:", "    circle: ground.C\n    law:"),
                       "bad.yaml:17:13", "give one target");
  expect_contact_error(contact_replaced("[ground.L, ground.R]", "[ground.L]"), "bad.yaml:16:11",
                       "expected two points [A, B]");
  expect_contact_error(contact_replaced("[ground.L, ground.R]", "[ground.L, ground.L]"),
                       "bad.yaml:16:22", "the line's two points are the same");
  expect_contact_error(contact_replaced("    law:", "    target_radius: 1\n    law:"),
                       "bad.yaml:17:20", "target_radius: only for a circle or a hole");
  expect_contact_error(contact_replaced("line: [ground.L, ground.R]", "circle: ground.C"),
                       "bad.yaml:14:5", "a circle needs its radius (target_radius)");
  expect_contact_error(
      contact_replaced("line: [ground.L, ground.R]", "hole: ground.C\n    target_radius: 0.04"),
      "bad.yaml:17:20", "the hole (0.040000 m) must be larger than the circle in it");
  expect_contact_error(
      contact_replaced("line: [ground.L, ground.R]", "circle: ground.C\n    target_radius: -1"),
      "bad.yaml:17:20", "target_radius: must be > 0");
  expect_contact_error(contact_replaced("point: ball.C", "point: ground.L"), "bad.yaml:14:12",
                       "'ground.L' is also a point of its target");
  expect_contact_error(contact_replaced("radius: 0.05", "radius: -0.05"), "bad.yaml:15:13",
                       "radius: must be >= 0");
}

TEST(ContactSceneErrors, Laws) {
  expect_contact_error(contact_replaced("law: rigid", "law: rigit"), "bad.yaml:17:10",
                       "unknown law 'rigit' (did you mean 'rigid'?)");
  expect_contact_error(contact_replaced("restitution: 0.8", "restitution: 1.2"), "bad.yaml:18:18",
                       "restitution: must be in [0, 1]");
  expect_contact_error(contact_replaced("    restitution: 0.8\n", ""), "bad.yaml:14:5",
                       "missing required key 'restitution'");
  expect_contact_error(contact_replaced("    law: rigid\n", "    law: rigid\n    stiffness: 1e6\n"),
                       "bad.yaml:18:16", "stiffness: only for law: compliant");
  expect_contact_error(contact_replaced("law: rigid", "law: compliant"), "bad.yaml:14:5",
                       "missing required key 'stiffness'");
  expect_contact_error(
      contact_replaced("law: rigid", "law: compliant\n    stiffness: 1e6\n    exponent: 0"),
      "bad.yaml:19:15", "exponent: must be > 0");
}

TEST(ContactSceneErrors, ContactRunSettings) {
  expect_contact_error(contact_replaced("  samples: 3\n", "  samples: 3\n  max_events: 0\n"),
                       "bad.yaml:25:15", "run.max_events: must be >= 1");
  expect_contact_error(contact_replaced("  samples: 3\n", "  samples: 3\n  zeno_time: -1\n"),
                       "bad.yaml:25:14", "run.zeno_time: must be > 0");
  std::string no_contacts = kContactBase;  // without the contacts: block (lines 12 to 18)
  no_contacts.erase(no_contacts.find("contacts:"),
                    no_contacts.find("initial:") - no_contacts.find("contacts:"));
  no_contacts.replace(no_contacts.find("  samples: 3\n"), 13, "  samples: 3\n  zeno_speed: 1\n");
  expect_contact_error(no_contacts, "bad.yaml:18:15",
                       "run.zeno_speed: only for a scene with contacts");
}

// A contact that starts penetrating is reported at the contact, with its gap; a command that does
// not take contacts into account refuses the scene at its first contact.
TEST(ContactSceneErrors, StartsPenetratingAndRefused) {
  expect_contact_error(contact_replaced("nodes: {C: [0, 0.5]}", "nodes: {C: [0, 0.01]}"),
                       "bad.yaml:13:3", "contact 'floor' starts penetrating: its gap is -0.04 m");
  const Scene s = parse_scene(kContactBase, "bad.yaml");
  try {
    refuse_contacts(s, "inverse dynamics");
    ADD_FAILURE() << "not refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "bad.yaml:13:3: contact 'floor': inverse dynamics does not "
              "take contacts into account yet");
  }
}

// Inverse dynamics holds a contact closed at the start, which takes one DOF: a motion that
// prescribes one coordinate too many or too few is an error that names the held contacts.
TEST(ContactSceneErrors, InverseMotionCountNamesTheHeldContacts) {
  const Scene s =
      parse_scene(contact_replaced("nodes: {C: [0, 0.5]}", "nodes: {C: [0, 0.05]}"), "bad.yaml");
  const ContactInverseModel held = scene_inverse_model(s);
  EXPECT_EQ(held.model.dof, 1);  // the ball's 2, less the floor's
  try {
    check_inverse_motion(s, held.model, held.contacts);
    ADD_FAILURE() << "not refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "bad.yaml: inverse dynamics needs one prescribed motion per DOF: the model has 1 DOF "
              "(the contacts held closed take one each: floor) and 'motion' prescribes 0");
  }
}

}  // namespace
}  // namespace mo2d
