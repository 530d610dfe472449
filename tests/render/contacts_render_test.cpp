// Contacts in frames (render/contacts.cpp): each contact's circle and what it touches drawn at
// their world size and place (a slot's walls and end), the fitted view keeping them inside, a bad
// point named.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"

namespace {

using namespace mo2d;

constexpr unsigned kContactPaper = 0xF4F1E8;

// A bar pivoted at the ground origin, its end A at (0.5, 0); on the ground a centre C at
// (-0.5, 0.5) and a line from L1 (-0.9, -0.6) to L2 (0.9, -0.6).
Model contact_bar() {
  System s("bar");
  s.add_ground_node("O", {0, 0});
  s.add_ground_node("C", {-0.5, 0.5});
  s.add_ground_node("L1", {-0.9, -0.6});
  s.add_ground_node("L2", {0.9, -0.6});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"A", {0.5, 0}}},
              .mass = 1,
              .inertia = 0.02,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  return build_model(s);
}

// A circle of radius 0.2 around bar.A against a circle of radius 0.3 around ground.C, and a point
// (bar.O) above the line L1 -> L2 reversed (its free side, the left of L2 -> L1, is below: the
// drawing does not depend on it).
std::vector<ContactDef> frame_contacts() {
  ContactDef circle{.name = "rim", .point = "bar.A", .radius = 0.2};
  circle.target = ContactDef::Target::circle;
  circle.a = "ground.C";
  circle.target_radius = 0.3;
  ContactDef line{.name = "floor", .point = "bar.O", .radius = 0};
  line.target = ContactDef::Target::line;
  line.a = "ground.L2";
  line.b = "ground.L1";
  circle.law.kind = line.law.kind = ContactLaw::Kind::rigid;
  return {circle, line};
}

// 200 x 200 pixels at 72 dpi showing the world square [-1, 1]^2: a world point (x, y) is at pixel
// (100 + 100 x, 100 - 100 y).
FrameOptions contact_window() {
  FrameOptions o;
  o.width = o.height = 200;
  o.dpi = 72;
  o.window = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  o.show_com = o.show_time = o.show_scale_bar = o.show_axes = o.show_efforts = false;
  o.style.background = rgb_hex(kContactPaper);
  return o;
}
unsigned contact_pixel(const Image& im, double x, double y) {
  return rgb_of(im.at(static_cast<int>(std::lround(100 + 100 * x)),
                      static_cast<int>(std::lround(100 - 100 * y))));
}

TEST(ContactRender, ShapesAreDrawnAtTheirWorldSizeAndPlace) {
  const Model m = contact_bar();
  const Motion motion = single_configuration(m.q0);
  FrameOptions o = contact_window();
  const Image without = render_frame(m, motion, 0, o);
  o.contacts = frame_contacts();
  const Image with = render_frame(m, motion, 0, o);
  // on each outline: the top of the circle around bar.A (r = 0.2), the top, left and bottom of
  // the circle around ground.C (R = 0.3), the line at y = -0.6; paper before the contacts
  for (const auto& [x, y] : {std::pair{0.5, 0.2}, std::pair{-0.5, 0.8}, std::pair{-0.8, 0.5},
                             std::pair{-0.5, 0.2}, std::pair{0.0, -0.6}, std::pair{0.6, -0.6}}) {
    EXPECT_EQ(contact_pixel(without, x, y), kContactPaper) << x << ", " << y;
    EXPECT_NE(contact_pixel(with, x, y), kContactPaper) << x << ", " << y;
  }
  // inside the circles, away from their outlines and hatching: paper
  for (const auto& [x, y] : {std::pair{0.5, 0.12}, std::pair{-0.5, 0.5}, std::pair{-0.5, 0.65}})
    EXPECT_EQ(contact_pixel(with, x, y), kContactPaper) << x << ", " << y;
  // and outside them
  for (const auto& [x, y] : {std::pair{0.5, 0.28}, std::pair{-0.5, 0.9}, std::pair{-0.9, 0.5}})
    EXPECT_EQ(contact_pixel(with, x, y), kContactPaper) << x << ", " << y;
}

TEST(ContactRender, TheFittedViewKeepsTheContactsShapesInside) {
  const Model m = contact_bar();
  const Motion motion = single_configuration(m.q0);
  FrameOptions o;
  o.contacts = frame_contacts();
  const View v = fit_view(m, motion, o);
  // the extremes of the circle around ground.C and of the line
  for (const auto& [x, y] :
       {std::pair{-0.8, 0.5}, std::pair{-0.5, 0.8}, std::pair{-0.9, -0.6}, std::pair{0.9, -0.6}}) {
    const Eigen::Vector2d px = to_pixel(v, {x, y});
    EXPECT_GT(px.x(), 0) << x << ", " << y;
    EXPECT_LT(px.x(), o.width) << x << ", " << y;
    EXPECT_GT(px.y(), 0) << x << ", " << y;
    EXPECT_LT(px.y(), o.height) << x << ", " << y;
  }
}

// A slot of width 0.4 from its closed end L1 (-0.9, -0.6) to its mouth L2 (0.9, -0.6): its walls
// at y = -0.4 and -0.8 and its end across x = -0.9 drawn, the channel between them left empty,
// the mouth open.
TEST(ContactRender, ASlotsWallsAndEndAreDrawnAndItsChannelLeftOpen) {
  const Model m = contact_bar();
  FrameOptions o = contact_window();
  ContactDef slot{.name = "slot", .point = "bar.O", .radius = 0};
  slot.target = ContactDef::Target::slot;
  slot.a = "ground.L1";
  slot.b = "ground.L2";
  slot.width = 0.4;
  slot.law.kind = ContactLaw::Kind::rigid;
  o.contacts = {slot};
  const Image im = render_frame(m, single_configuration(m.q0), 0, o);
  for (const auto& [x, y] : {std::pair{0.0, -0.4}, std::pair{0.5, -0.8}, std::pair{-0.9, -0.6}})
    EXPECT_NE(contact_pixel(im, x, y), kContactPaper) << x << ", " << y;
  for (const auto& [x, y] : {std::pair{0.0, -0.6}, std::pair{0.3, -0.5}, std::pair{0.3, -0.7},
                             std::pair{-0.8, -0.6}, std::pair{0.92, -0.6}})
    EXPECT_EQ(contact_pixel(im, x, y), kContactPaper) << x << ", " << y;
}

TEST(ContactRender, AContactWithAnUnknownPointIsNamed) {
  const Model m = contact_bar();
  FrameOptions o = contact_window();
  o.contacts = frame_contacts();
  o.contacts[1].b = "ground.L3";
  try {
    render_frame(m, single_configuration(m.q0), 0, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("contact 'floor'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ground.L3"), std::string::npos) << e.what();
  }
}

// A cam profile r(phi) = 0.5 + 0.2 cos 2 phi on the bar around bar.O, its axis bar.O -> bar.A
// (along +x), touched by the point ground.C: the closed curve of its spline drawn through
// (0.7, 0), (0, 0.3), (-0.7, 0), (0, -0.3), nothing inside or outside it.
TEST(ContactRender, ProfileIsDrawnAsItsClosedCurveOnItsBody) {
  const Model m = contact_bar();
  const Motion motion = single_configuration(m.q0);
  FrameOptions o = contact_window();
  const Image without = render_frame(m, motion, 0, o);
  std::vector<double> x, y;
  for (int i = 0; i <= 72; ++i) {
    x.push_back(2 * std::numbers::pi * i / 72);
    y.push_back(0.5 + 0.2 * std::cos(2 * x.back()));
  }
  ContactDef cam{.name = "cam", .point = "ground.C", .radius = 0};
  cam.target = ContactDef::Target::profile;
  cam.a = "bar.O";
  cam.b = "bar.A";
  cam.profile = std::make_shared<const LookupTable>(
      "r", x, y, TableOptions{Interpolation::cubic, Extrapolation::periodic});
  cam.law.kind = ContactLaw::Kind::rigid;
  o.contacts = {cam};
  const Image with = render_frame(m, motion, 0, o);
  for (const auto& [px, py] : {std::pair{0.7, 0.0}, std::pair{0.0, 0.3}, std::pair{-0.7, 0.0},
                               std::pair{0.0, -0.3}, std::pair{0.3536, 0.3536}}) {
    EXPECT_EQ(contact_pixel(without, px, py), kContactPaper) << px << ", " << py;
    EXPECT_NE(contact_pixel(with, px, py), kContactPaper) << px << ", " << py;
  }
  for (const auto& [px, py] : {std::pair{0.0, 0.15}, std::pair{0.0, 0.45}, std::pair{-0.85, 0.0},
                               std::pair{-0.5, 0.0}, std::pair{0.0, -0.15}})
    EXPECT_EQ(contact_pixel(with, px, py), kContactPaper) << px << ", " << py;
}

}  // namespace
