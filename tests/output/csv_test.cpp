// CSV tables of a run: labelled header, one row per sample, written atomically.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

TEST(Output, CsvHasLabelledHeaderAndIsWrittenAtomically) {
  auto ex = mechanisms::pendulum();
  const Model m = build_model(ex.system);
  InverseOptions o = ex.run;
  o.samples = 5;
  const Trajectory r = inverse_dynamics(m, ex.motion, o);
  const std::string csv = trajectory_csv(r);
  EXPECT_EQ(csv.substr(0, csv.find('\n')).find("t,link.P.x,link.P.y,link.angle"), 0u);
  EXPECT_NE(csv.find("pivot.torque"), std::string::npos);
  EXPECT_NE(csv.find("pivot.Fx"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);
  const std::string path = ::testing::TempDir() + "/mo2d_csv_test.csv";
  write_trajectory_csv(r, path);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  EXPECT_THROW(write_trajectory_csv(r, "/nonexistent-dir/x.csv"), Error);
}
