// build_model: a shipped mechanism builds; labels, counts and the merged nodes of the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

TEST(Smoke, WhitworthBuilds) {
  auto ex = mo2d::mechanisms::whitworth();
  const mo2d::Model m = mo2d::build_model(ex.system);
  EXPECT_EQ(m.dof, 1);
}

TEST(Model, LabelsAndCounts) {
  const Model m = build_model(mechanisms::rrr3().system);
  EXPECT_EQ(m.dof, 3);
  EXPECT_NO_THROW(m.coordinate("platform.angle"));
  EXPECT_NO_THROW(m.coordinate("platform.C.x"));
  EXPECT_EQ(m.coordinate("platform.P2.x"), m.coordinate("leg2.distal.P.x"));  // merged node
  EXPECT_NO_THROW(m.rate("leg2.proximal.w"));
  std::vector<std::string> inputs, reactions;
  for (const auto& in : m.inputs) inputs.push_back(in.label);
  for (const auto& r : m.reactions) reactions.push_back(r.label);
  EXPECT_EQ(inputs, (std::vector<std::string>{"leg1.pivot.torque", "leg2.pivot.torque",
                                              "leg3.pivot.torque"}));
  EXPECT_NE(std::find(reactions.begin(), reactions.end(), "leg2.elbow.Fx"), reactions.end());
  EXPECT_NE(std::find(reactions.begin(), reactions.end(), "attach3.Fy"), reactions.end());
  const std::string text = describe(m);
  EXPECT_NE(text.find("3 DOF"), std::string::npos);
  EXPECT_NE(text.find("leg1.pivot.torque"), std::string::npos);
  const Model w = build_model(mechanisms::whitworth().system);
  EXPECT_EQ(w.n0, 9);
  EXPECT_EQ(w.n1, 12);
  EXPECT_EQ(w.dof, 1);
  EXPECT_NO_THROW(w.coordinate("slide.q"));
  EXPECT_NO_THROW(w.coordinate("crank_pin.q"));
}
