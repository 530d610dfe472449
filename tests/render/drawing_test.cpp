// The drawing's numbers (mo2d/render/drawing.hpp, which the viewer page draws) against the Cairo
// frame of the same sample: every pin (revolute joint, pin in a slot) that drawing_of places is a
// pin on render_frame's image at that pixel (a light disc in a dark ring of the joint radius),
// and is not one 5 px aside (the check can fail).
#include "mo2d/render/drawing.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"
#include "mo2d/scene.hpp"

namespace {

using namespace mo2d;

double luma(const Image& im, double x, double y) {
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  if (i < 0 || j < 0 || i >= im.width || j >= im.height) return 255;
  const unsigned p = rgb_of(im.at(i, j));
  return 0.299 * ((p >> 16) & 0xFF) + 0.587 * ((p >> 8) & 0xFF) + 0.114 * (p & 0xFF);
}

// A pin centred at c: light near the centre, dark within 1.2 px of the radius in each of 16
// sectors (as tests/view/browser_test.py checks the page's screenshot).
bool pin_at(const Image& im, const Vec2& c, double radius) {
  for (const auto& [dx, dy] :
       std::array<std::pair<double, double>, 5>{{{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}})
    if (luma(im, c.x() + dx * 0.3 * radius, c.y() + dy * 0.3 * radius) < 170) return false;
  std::array<double, 16> darkest{};
  darkest.fill(255);
  const int reach = static_cast<int>(radius + 3);
  const int ci = static_cast<int>(std::floor(c.x())), cj = static_cast<int>(std::floor(c.y()));
  for (int j = cj - reach; j <= cj + reach; ++j)
    for (int i = ci - reach; i <= ci + reach; ++i) {
      const double dx = i + 0.5 - c.x(), dy = j + 0.5 - c.y();
      if (std::abs(std::hypot(dx, dy) - radius) > 1.2) continue;
      const double a = std::fmod(std::atan2(dy, dx) + M_PI / 16 + 2 * M_PI, 2 * M_PI);
      const int k = static_cast<int>(a / (M_PI / 8)) % 16;
      darkest[k] = std::min(darkest[k], luma(im, i, j));
    }
  for (const double d : darkest)
    if (d > 120) return false;
  return true;
}

class DrawingMatchesFrame : public testing::TestWithParam<std::string> {};

TEST_P(DrawingMatchesFrame, PinsAreWhereTheCairoFrameDrawsThem) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/" + GetParam() + ".yaml");
  const Model model = build_scene_model(scene);
  const Trajectory r = inverse_dynamics(model, scene.motion, inverse_options(scene));
  const Motion motion = motion_of(r);
  const int n = static_cast<int>(r.time.size());
  const std::vector<int> samples = {0, n / 3};
  const FrameOptions options;
  const Drawing d = drawing_of(model, motion, options, samples);
  ASSERT_EQ(d.samples.size(), samples.size());
  EXPECT_EQ(d.body_names.size(), model.bodies.size());
  EXPECT_NEAR(d.joint_radius, options.style.joint_radius * options.dpi / 72, 1e-12);
  int pins = 0;
  for (size_t s = 0; s < samples.size(); ++s) {
    const Image im = render_frame(model, motion, samples[s], options);
    EXPECT_EQ(d.samples[s].time, r.time[samples[s]]);
    for (size_t j = 0; j < d.joints.size(); ++j) {
      if (!d.joints[j].pin) continue;
      const Vec2 c = d.samples[s].joints[j];
      EXPECT_TRUE(pin_at(im, c, d.joint_radius))
          << d.joints[j].name << " at (" << c.x() << ", " << c.y() << "), sample " << samples[s];
      EXPECT_FALSE(pin_at(im, c + Vec2(5, 0), d.joint_radius)) << d.joints[j].name << " + 5 px";
      ++pins;
    }
  }
  EXPECT_GE(pins, 4);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DrawingMatchesFrame,
                         testing::Values("slider_crank", "rrr3", "whitworth"));

// The contacts' numbers (DrawnContact, DrawnSample::contacts) where the Cairo frame draws them:
// the bouncing ball's circle around ball.C at the view's pixel of ball.C with the radius r times
// the view's scale, its floor's ends at ground.L and ground.R; at a second sample, lower.
TEST(Drawing, ContactsAreAtTheirPointsInPixels) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/bouncing_ball.yaml");
  const Model model = build_scene_model(scene);
  Motion motion = single_configuration(model.q0);
  FrameOptions options;
  options.contacts = scene.contacts;
  const Drawing d = drawing_of(model, motion, options, {0});
  ASSERT_EQ(d.contacts.size(), 1u);
  EXPECT_EQ(d.contacts[0].name, "floor");
  EXPECT_EQ(d.contacts[0].target, "line");
  EXPECT_EQ(d.contacts[0].target_body, -1);
  EXPECT_NEAR(d.contacts[0].radius, 0.05 * d.view.scale, 1e-9);
  const auto& k = d.samples[0].contacts.at(0);
  const Vec2 ball(model.q0[model.coordinate("ball.C.x")], model.q0[model.coordinate("ball.C.y")]);
  for (const auto& [drawn, world] :
       {std::pair{k[0], ball}, std::pair{k[1], Vec2(-1, 0)}, std::pair{k[2], Vec2(1, 0)}})
    EXPECT_LT((drawn - Vec2(to_pixel(d.view, world))).norm(), 1e-9) << world.transpose();
  // the ball's ring on the Cairo frame of the same sample (a planted offset of 5 px fails)
  const Image im = render_frame(model, motion, 0, options);
  int dark = 0;
  for (int a = 0; a < 16; ++a) {
    const double t = a * M_PI / 8, r = d.contacts[0].radius;
    dark += luma(im, k[0].x() + r * std::cos(t), k[0].y() + r * std::sin(t)) < 200;
  }
  EXPECT_GE(dark, 12);
}

TEST(Drawing, FrameSvgIsTheFrameAsSvgText) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/slider_crank.yaml");
  const Model model = build_scene_model(scene);
  const std::string svg = frame_svg(model, single_configuration(model.q0), 0, {});
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_THROW(frame_svg(model, single_configuration(model.q0), 1, {}), Error);
}

}  // namespace
