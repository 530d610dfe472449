// The QSS half-bike (tests/data/half_bike_qss.yaml: the suspension reduce: quasi_steady, the chain
// fidelity: quasi_steady; Gamba 2009, 2.32-2.40): the file is half_bike.yaml with its five
// documented changes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dynamics/chain.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::half_bike_qss_test {

std::string read(const std::string& name) {
  std::ifstream in(std::string(MO2D_MECHANISMS_DIR) + "/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string read_data(const std::string& name) {
  std::ifstream in(std::string(MO2D_TEST_DATA_DIR) + "/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(HalfBikeQss, IsTheFullSceneWithItsFiveChanges) {
  std::string full = read("half_bike.yaml");
  const std::string qss = read_data("half_bike_qss.yaml");
  const std::string line = "# ---- mechanisms/half_bike.yaml, changed as above ----\n";
  ASSERT_NE(qss.find(line), std::string::npos);
  auto edit = [&](const std::string& a, const std::string& b) {
    ASSERT_NE(full.find(a), std::string::npos) << a;
    full.replace(full.find(a), a.size(), b);
  };
  edit("name: half_bike\n", "name: half_bike_qss\n");
  edit("tau_pre}\n", "tau_pre, reduce: quasi_steady}\n");
  edit("fidelity: unilateral,", "fidelity: quasi_steady,");
  edit("velocities: {shaft.w: 0, arm.w: 0, wheel.w: 0}", "velocities: {shaft.w: 0}");
  const size_t from = full.find("  # kept (measured"), to = full.find("  integrator: cvode_bdf\n");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  full.replace(from, to + 24 - from,
               "  integrator: dopri5  # the QSS rows need an explicit integrator that projects\n");
  EXPECT_EQ(qss.substr(qss.find(line) + line.size()), full);
}

}  // namespace mo2d::half_bike_qss_test
