// Scene keys `points:` (named points, in system blocks and subsystems) and `outputs:` (the extra
// CSV columns): what they give the model and the run, and their errors at file:line:column.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A link pivoted at the origin, P at (1, 0), turned by link.angle = t; a named point "mark" at
// (0.5, 0.5) on the link pulled by a force that reads the point's velocity.
const std::string kScene = R"yaml(name: p
ground:
  O: [0, 0]
bodies:
  link:
    nodes: {O: [0, 0], P: [1, 0]}
    mass: 2
    inertia: 0.1
    com: {between: [O, P]}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
points:
  mark: {body: link, point: [0.5, 0.5]}
loads:
  forces:
    pull: {body: link, point: [0.5, 0.5], fx: -3 * mark.vx}
outputs:
  loads: true
  points: [mark]
motion:
  link.angle: t
run: {duration: 1, samples: 11}
)yaml";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

std::string error_of(const std::string& text) {
  try {
    build_scene_model(parse_scene(text, "bad.yaml"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOutputs, NamedPointIsReadByLawsAndWrittenWhenAsked) {
  const Scene scene = parse_scene(kScene, "p.yaml");
  EXPECT_TRUE(scene.outputs.loads);
  EXPECT_FALSE(scene.outputs.com);
  EXPECT_EQ(scene.outputs.points, std::vector<std::string>{"mark"});
  const Model m = build_scene_model(scene);
  ASSERT_EQ(m.points.size(), 1u);
  Trajectory r = inverse_dynamics(m, scene.motion, inverse_options(scene));
  add_output_columns(m, r, scene.outputs);
  for (int k = 0; k < r.time.size(); ++k) {  // the link at angle t, turning at 1 rad/s
    const double t = r.time[k], c = std::cos(t), s = std::sin(t);
    const double x = 0.5 * c - 0.5 * s, y = 0.5 * s + 0.5 * c, vx = -y, vy = x;
    EXPECT_NEAR(r.outputs(k, r.output("mark.x")), x, 1e-12);
    EXPECT_NEAR(r.outputs(k, r.output("mark.y")), y, 1e-12);
    EXPECT_NEAR(r.outputs(k, r.output("mark.vx")), vx, 1e-10);
    EXPECT_NEAR(r.outputs(k, r.output("mark.vy")), vy, 1e-10);
    EXPECT_NEAR(r.outputs(k, r.output("pull.fx")), -3 * vx, 1e-9);
    EXPECT_NEAR(r.outputs(k, r.output("pull.power")), -3 * vx * vx, 1e-9);
  }
  const std::string csv = trajectory_csv(r);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",pull.fx,pull.fy,pull.power,mark.x,mark.y,mark.vx,mark.vy"),
            std::string::npos)
      << header;
  EXPECT_EQ(header.find(".com."), std::string::npos);
}

TEST(SceneOutputs, DefaultsWriteEveryNamedPointAndNoLoads) {
  const std::string text = replaced(kScene, "outputs:\n  loads: true\n  points: [mark]\n", "");
  const Scene scene = parse_scene(text, "p.yaml");
  EXPECT_TRUE(scene.outputs.all_points);
  EXPECT_FALSE(scene.outputs.loads);
  const Model m = build_scene_model(scene);
  EXPECT_EQ(output_column_labels(m, scene.outputs),
            (std::vector<std::string>{"mark.x", "mark.y", "mark.vx", "mark.vy"}));
  const Scene none = parse_scene(replaced(kScene, "points: [mark]", "points: false"), "p.yaml");
  EXPECT_EQ(output_column_labels(m, none.outputs),
            (std::vector<std::string>{"pull.fx", "pull.fy", "pull.power"}));
  const Scene com = parse_scene(replaced(kScene, "  loads: true", "  com: true"), "p.yaml");
  EXPECT_EQ(output_column_labels(m, com.outputs),
            (std::vector<std::string>{"mark.x", "mark.y", "mark.vx", "mark.vy", "link.com.x",
                                      "link.com.y", "link.com.vx", "link.com.vy"}));
}

// outputs: columns: laws of t, the parameters and the state, one column each, after the others:
// the squared distance from (1, 0) to the point mark at angle t, (0.5 c - 0.5 s - 1)^2 +
// (0.5 s + 0.5 c)^2 = 1.5 - c + s, and the rate times the time.
TEST(SceneOutputs, LawColumnsAreExpressionsOfTheState) {
  const std::string text =
      replaced(replaced(kScene, "name: p\n", "name: p\nparameters: {X: 1}\n"), "  points: [mark]\n",
               "  points: [mark]\n  columns:\n"
               "    dist2: (mark.x - X)^2 + mark.y^2\n"
               "    wt: link.w * t\n");
  const Scene scene = parse_scene(text, "p.yaml");
  ASSERT_EQ(scene.outputs.columns.size(), 2u);
  const Model m = build_scene_model(scene);
  Trajectory r = inverse_dynamics(m, scene.motion, inverse_options(scene));
  add_output_columns(m, r, scene.outputs);
  EXPECT_EQ(r.output_labels.back(), "wt");
  for (int k = 0; k < r.time.size(); ++k) {
    const double t = r.time[k];
    EXPECT_NEAR(r.outputs(k, r.output("dist2")), 1.5 - std::cos(t) + std::sin(t), 1e-12) << t;
    EXPECT_NEAR(r.outputs(k, r.output("wt")), t, 1e-10) << t;
  }
  // the per-state function gives the same row
  Eigen::VectorXd row(static_cast<Eigen::Index>(output_column_labels(m, scene.outputs).size()));
  const int last = static_cast<int>(r.time.size()) - 1;
  output_column_values(m, scene.outputs, r.q0.row(last).transpose(), r.q1.row(last).transpose(),
                       r.time[last], row);
  EXPECT_NEAR(row[row.size() - 2], 1.5 - std::cos(1.0) + std::sin(1.0), 1e-12);
  const std::string csv = trajectory_csv(r);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",mark.vy,dist2,wt"), std::string::npos) << header;
  // an unknown quantity is refused before any run, where the column writes it
  const std::string bad = replaced(text, "mark.y^2", "mark.z^2");
  EXPECT_NE(error_of(bad).find("bad.yaml:24:29: "), std::string::npos) << error_of(bad);
  EXPECT_NE(error_of(bad).find("mark.z"), std::string::npos) << error_of(bad);
  const std::string named = replaced(text, "    wt:", "    w.t:");
  EXPECT_NE(error_of(named).find("names may not contain '.'"), std::string::npos)
      << error_of(named);
}

TEST(SceneOutputs, PointsOfSubsystemsCarryTheInstancePrefix) {
  const std::string text = R"yaml(name: legs
subsystems:
  leg:
    bodies:
      shin:
        nodes: {K: [0, 0], F: [0, -1]}
        mass: 1
        inertia: 0.1
        com: {between: [K, F]}
    points:
      foot: {body: shin, point: [0.1, -1]}
ground:
  O: [1, 0]
instances:
  left: {subsystem: leg, offset: [1, 0]}
joints:
  hip: {type: revolute, node_a: ground.O, node_b: left.shin.K}
outputs:
  points: [left.foot]
)yaml";
  const Scene scene = parse_scene(text, "legs.yaml");
  const Model m = build_scene_model(scene);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].name, "left.foot");
  EXPECT_TRUE(m.quantities.count("left.foot.x"));
}

TEST(SceneOutputs, ErrorsAtTheirLine) {
  auto expect = [](const std::string& text, const std::string& where, const std::string& what) {
    const std::string e = error_of(text);
    EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
    EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
  };
  EXPECT_EQ(error_of(kScene), "");
  expect(replaced(kScene, "mark: {body: link,", "mark: {body: lnk,"), "bad.yaml:15:16",
         "point 'mark'.body: undefined body 'lnk' (did you mean 'link'?)");
  expect(replaced(kScene, "points: [mark]", "points: [mrak]"), "bad.yaml:21:12",
         "outputs.points: undefined point 'mrak' (did you mean 'mark'?)");
  expect(replaced(kScene, "  loads: true", "  load: true"), "bad.yaml:20:3",
         "outputs: unknown key 'load' (did you mean 'loads'?)");
  expect(replaced(kScene, "  mark: {body", "  ma.rk: {body"), "bad.yaml:15:3",
         "names may not contain '.'");
  expect(replaced(kScene, "fx: -3 * mark.vx", "fx: -3 * mark.vz"), "bad.yaml:18:52", "mark.vz");
}

}  // namespace
}  // namespace mo2d
