#include <gtest/gtest.h>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

TEST(Smoke, WhitworthBuilds) {
  auto ex = mo2d::mechanisms::whitworth();
  const mo2d::Model m = mo2d::build_model(ex.system);
  EXPECT_EQ(m.dof, 1);
}
