// Bad slot contacts in scene files (`slot: [A, B]` with `width`, src/scene/load_contacts.cpp):
// each error at its file:line:column with what was expected (docs/scene-format.md, "Contacts").
#include <gtest/gtest.h>

#include <string>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A valid slot scene (a pin flying into a ground slot); each test replaces one piece of it.
const std::string kSlotBase = R"yaml(name: pin
ground:
  A: [0, 0]
  B: [1, 0]
bodies:
  ball:
    nodes: {C: [1.5, 0.01]}
    mass: 0.2
contacts:
  slot:
    point: ball.C
    radius: 0.1
    slot: [ground.A, ground.B]
    width: 0.3
    law: rigid
    restitution: 0.5
initial:
  velocities: {ball.C.vx: -1, ball.C.vy: 0}
run:
  solve: forward
  duration: 1
  samples: 3
  integrator: dopri5
)yaml";

std::string slot_replaced(const std::string& from, const std::string& to) {
  std::string s = kSlotBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The message of the error raised by loading, building and running `text` forward, "" if none.
std::string slot_error_of(const std::string& text) {
  try {
    const Scene s = parse_scene(text, "bad.yaml");
    const Model m = build_scene_model(s);
    const ForwardOptions o = forward_options(s, m);
    check_scene_options(s, m, o);
    const SceneRun r = scene_forward(s, m, initial_state(s, m), o);
    EXPECT_FALSE(r.events.empty());
  } catch (const SceneError& e) {
    return e.what();
  } catch (const Error& e) {
    return std::string("run: ") + e.what();
  }
  return "";
}

void expect_slot_error(const std::string& text, const std::string& where, const std::string& what) {
  const std::string e = slot_error_of(text);
  EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
  EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
}

TEST(SlotSceneErrors, BaseSceneIsValid) {
  EXPECT_EQ(slot_error_of(kSlotBase), "");
}

TEST(SlotSceneErrors, SlotTargets) {
  expect_slot_error(slot_replaced("width: 0.3", "width: 0.2"), "bad.yaml:14:12",
                    "contact 'slot'.width: the slot (0.200000 m) must be wider than the pin's "
                    "diameter (2 radius = 0.200000 m)");
  expect_slot_error(slot_replaced("width: 0.3", "width: -1"), "bad.yaml:14:12",
                    "width: must be > 0");
  expect_slot_error(slot_replaced("[ground.A, ground.B]", "[ground.A, ground.A]"), "bad.yaml:13:22",
                    "the slot's two ends are the same point ('ground.A')");
  expect_slot_error(slot_replaced("[ground.A, ground.B]", "[ground.A]"), "bad.yaml:13:11",
                    "expected two points [A, B] (its closed end A, its mouth B)");
  expect_slot_error(slot_replaced("    width: 0.3\n", ""), "bad.yaml:11:5",
                    "contact 'slot': a slot needs its width (width)");
  expect_slot_error(slot_replaced("slot: [ground.A, ground.B]", "line: [ground.A, ground.B]"),
                    "bad.yaml:14:12", "contact 'slot'.width: only for a slot");
  expect_slot_error(slot_replaced("    law:", "    target_radius: 1\n    law:"), "bad.yaml:15:20",
                    "target_radius: only for a circle or a hole");
  expect_slot_error(slot_replaced("    law:", "    line: [ground.A, ground.B]\n    law:"),
                    "bad.yaml:13:11",
                    "give one target, 'line', 'circle', 'hole', 'slot' or 'profile' (both 'line' "
                    "and 'slot' given)");
  expect_slot_error(slot_replaced("restitution: 0.5", "restitution: 0.5\n    friction: 0.2"),
                    "bad.yaml:17:15",
                    "contact 'slot'.friction: friction in a slot is not modelled");
  // the slot no longer than the pin's radius: at the contact's key, from the run's check
  expect_slot_error(slot_replaced("B: [1, 0]", "B: [0.05, 0]"), "bad.yaml:10:3",
                    "the slot from 'ground.A' to 'ground.B' is 0.05 m long, not longer than the "
                    "pin's radius 0.1 m");
}

// From outside through a wall: refused at the located time, naming the slot.
TEST(SlotSceneErrors, PinThroughAWall) {
  std::string text = slot_replaced("{C: [1.5, 0.01]}", "{C: [0.5, 0.5]}");
  text.replace(text.find("{ball.C.vx: -1, ball.C.vy: 0}"), 29, "{ball.C.vx: 0, ball.C.vy: -1}");
  text.replace(text.find("duration: 1"), 11, "duration: 0.5");
  const std::string e = slot_error_of(text);
  EXPECT_NE(e.find("contact 'slot': the pin 'ball.C' enters its slot through a wall at t = 0.35"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace mo2d
