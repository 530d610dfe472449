// The summary values an optimization reads (src/optimize/run_values.hpp) on a trajectory built by
// hand (a column x = t^2 over [0, 2] at 5 samples: trapezoid integrals by hand), and
// set_parameter_values (mo2d/scene.hpp): a value replaced in place, the rest of the text kept.
#include "optimize/run_values.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mo2d/scene.hpp"

namespace run_values_test {
namespace {

using namespace mo2d;
using namespace mo2d::optimize_detail;

TEST(RunValues, StatisticsOfAColumn) {
  Trajectory r;
  r.time = Eigen::VectorXd::LinSpaced(5, 0, 2);  // 0, 0.5, 1, 1.5, 2
  r.input_labels = {"pivot.torque"};
  r.efforts = Eigen::MatrixXd(5, 1);
  r.efforts << -1, 0, 1, 2, -3;
  auto value = [&](const std::string& name) {
    const std::optional<RunValue> v = parse_run_value(name);
    EXPECT_TRUE(v.has_value()) << name;
    return run_value(*v, r, nullptr);
  };
  EXPECT_EQ(value("peak.pivot.torque"), 3);
  EXPECT_EQ(value("max.pivot.torque"), 2);
  EXPECT_EQ(value("min.pivot.torque"), -3);
  EXPECT_EQ(value("peak_to_peak.pivot.torque"), 5);
  // trapezoid: 0.5 * (0.5 (-1 + 0) + 0.5 (0 + 1) + 0.5 (1 + 2) + 0.5 (2 - 3)) / 2
  EXPECT_DOUBLE_EQ(value("mean.pivot.torque"), 0.25 * (-1 + 1 + 3 - 1) / 2);
  EXPECT_DOUBLE_EQ(value("rms.pivot.torque"), std::sqrt(0.25 * (1 + 1 + 5 + 13) / 2));
  EXPECT_FALSE(parse_run_value("pivot.torque").has_value());
  EXPECT_FALSE(parse_run_value("peak.").has_value());
  EXPECT_EQ(parse_run_value("peak_to_peak.a.b")->column, "a.b");
  EXPECT_THROW(run_value(*parse_run_value("rms.nothing"), r, nullptr), Error);
  EXPECT_THROW(run_value(*parse_run_value("flywheel.pivot.torque"), r, nullptr), Error);
}

TEST(SetParameterValues, ReplacesTheValueAndKeepsTheRest) {
  const std::string text =
      "name: p\n"
      "parameters:\n"
      "  L: 1.0     # m, a comment\n"
      "  m: \"2 * L\"\n"
      "  k: 'L'   # quoted\n"
      "  g: 9.81\n"
      "ground: {O: [0, 0]}\n"
      "bodies:\n"
      "  link: {nodes: {O: [0, 0], P: [L, 0]}, mass: m, com: P}\n"
      "joints:\n"
      "  pivot: {type: revolute, node_a: ground.O, node_b: link.O}\n";
  const std::vector<std::pair<std::string, double>> v{
      {"L", 0.30000000000000004}, {"m", 5}, {"k", -1e-300}};
  const std::string out = set_parameter_values(text, "p.yaml", v);
  EXPECT_NE(out.find("  L: 0.30000000000000004     # m, a comment\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  m: 5\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  k: -1e-300   # quoted\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  g: 9.81\n"), std::string::npos) << out;
  const Scene s = parse_scene(out, "p.yaml");
  EXPECT_EQ(s.parameters.size(), 4u);
  // in a flow map
  const std::string flow =
      "name: p\nparameters: {L: 1, m: 2 * L}\nground: {O: [0, 0]}\n"
      "bodies: {link: {nodes: {O: [0, 0], P: [L, 0]}, mass: m, com: P}}\n"
      "joints: {pivot: {type: revolute, node_a: ground.O, node_b: link.O}}\n";
  const std::pair<std::string, double> l{"L", 3};
  EXPECT_NE(set_parameter_values(flow, "p.yaml", {&l, 1}).find("{L: 3, m: 2 * L}"),
            std::string::npos);
  const std::pair<std::string, double> x{"x", 3};
  EXPECT_THROW(set_parameter_values(text, "p.yaml", {&x, 1}), SceneError);
}

}  // namespace
}  // namespace run_values_test
