// Loads, traced named points and labels in frames (FrameOptions::show_loads, traces,
// show_labels): pixels where the hand computation puts them.
#include <gtest/gtest.h>

#include <cmath>

#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"

namespace {

using namespace mo2d;

constexpr unsigned kPaper = 0xF4F1E8;
constexpr unsigned kGreen = 0x00FF00;

// A bar pivoted at the ground origin, free end A at (0.5, 0); a force at A of (0, -fy(t)) and a
// torque tau(t) on the bar; a named point "tip" at (0.3, 0.4), off the bar.
Model bar(Law fy, Law tau) {
  System s("bar");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"A", {0.5, 0}}},
              .mass = 1,
              .inertia = 0.02,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  s.add_force({.name = "push", .body = "bar", .point = {0.5, 0}, .fy = std::move(fy)});
  s.add_torque({.name = "turn", .body = "bar", .torque = std::move(tau)});
  s.add_point({.name = "tip", .body = "bar", .point = {0.3, 0.4}});
  return build_model(s);
}

// The bar turned by phi_k = k * 0.4 rad, k = 0..n-1, at rest (t = k).
Motion turning(const Model& m, int n) {
  Motion mo;
  mo.time.resize(n);
  mo.q0.resize(n, m.n0);
  mo.q1 = Eigen::MatrixXd::Zero(n, m.n1);
  for (int k = 0; k < n; ++k) {
    mo.time[k] = k;
    mo.q0(k, m.coordinate("bar.A.x")) = 0.5 * std::cos(0.4 * k);
    mo.q0(k, m.coordinate("bar.A.y")) = 0.5 * std::sin(0.4 * k);
  }
  return mo;
}

// 200 x 200 px at 72 dpi showing [-1, 1]^2: world (x, y) at (100 + 100 x, 100 - 100 y) in pixel
// units, inside the pixel of indices (floor(100 + 100 x), floor(100 - 100 y)).
FrameOptions window() {
  FrameOptions o;
  o.width = o.height = 200;
  o.dpi = 72;
  o.window = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  o.show_com = o.show_time = o.show_scale_bar = o.show_axes = o.show_efforts = false;
  o.style.background = rgb_hex(kPaper);
  o.style.load = rgb_hex(kGreen);
  return o;
}
unsigned at_world(const Image& im, double x, double y) {
  return rgb_of(im.at(static_cast<int>(std::floor(100 + 100 * x)),
                      static_cast<int>(std::floor(100 - 100 * y))));
}
int count(const Image& im, unsigned c) {
  int n = 0;
  for (auto p : im.argb) n += rgb_of(p) == c;
  return n;
}

TEST(RenderLoads, TracedNamedPointPassesThroughItsComputedPositions) {
  const Model m = bar(Law::constant(0), Law::constant(0));
  const Motion mo = turning(m, 5);
  FrameOptions o = window();
  const Image plain = render_frame(m, mo, 4, o);
  o.traces = {"tip"};
  const Image traced = render_frame(m, mo, 4, o);
  for (int k = 0; k < 5; ++k) {  // (0.3, 0.4) turned by 0.4 k, written out
    const double c = std::cos(0.4 * k), s = std::sin(0.4 * k);
    const double x = 0.3 * c - 0.4 * s, y = 0.3 * s + 0.4 * c;
    EXPECT_EQ(at_world(plain, x, y), kPaper) << k;  // off the bar: background without the trace
    EXPECT_NE(at_world(traced, x, y), kPaper) << k;
  }
  // half-way between two samples the polyline passes the chord's midpoint
  const double xm = 0.5 * ((0.3) + (0.3 * std::cos(0.4) - 0.4 * std::sin(0.4)));
  const double ym = 0.5 * ((0.4) + (0.3 * std::sin(0.4) + 0.4 * std::cos(0.4)));
  EXPECT_NE(at_world(traced, xm, ym), kPaper);
  EXPECT_THROW(
      {
        o.traces = {"tpi"};
        render_frame(m, mo, 0, o);
      },
      Error);
}

// The force at A points down: its arrow ends at A (short of the pin, 3.4 + 1 pt = 0.044 m) and
// starts 34 pt (= 34 px = 0.34 m) above at the run's peak, half as far at half the peak; drawn
// above the bar, in the free space over A (an arrow from A along the force would lie on the bar's
// extension below A). A force of 1/100 of the peak still shows its head.
TEST(RenderLoads, ForceArrowPushesOnItsPointAndIsSizedByIt) {
  const Model m =
      bar([](double t) { return t == 0   ? -2.0
                                : t == 1 ? -1.0
                                         : -0.02; }, Law::constant(0));
  Motion mo = turning(m, 3);
  mo.q0.row(1) = mo.q0.row(0);  // all samples at phi = 0: only the force differs
  mo.q0.row(2) = mo.q0.row(0);
  FrameOptions o = window();
  EXPECT_EQ(count(render_frame(m, mo, 0, o), kGreen), 0);  // loads not asked for
  o.show_loads = true;
  const Image peak = render_frame(m, mo, 0, o), half = render_frame(m, mo, 1, o);
  EXPECT_EQ(at_world(peak, 0.5, 0.08), kGreen);   // the head just above A
  EXPECT_EQ(at_world(peak, 0.5, 0.30), kGreen);   // the shaft
  EXPECT_NE(at_world(peak, 0.5, -0.05), kGreen);  // nothing below A
  EXPECT_NE(at_world(peak, 0.5, 0.40), kGreen);   // nor beyond its tail at 0.384 m
  EXPECT_EQ(at_world(half, 0.5, 0.08), kGreen);
  EXPECT_NE(at_world(half, 0.5, 0.25), kGreen);  // its tail at 0.214 m
  EXPECT_GT(count(peak, kGreen), count(half, kGreen));
  const Image small = render_frame(m, mo, 2, o);
  EXPECT_EQ(at_world(small, 0.5, 0.08), kGreen);
  EXPECT_GT(count(small, kGreen), 10);
}

// The legend (with the scale bar) shows each load at its run's peak: a full-length arrow.
TEST(RenderLoads, LegendShowsTheArrowAtThePeak) {
  const Model m = bar(Law::constant(-2), Law::constant(0));
  const Motion mo = turning(m, 1);
  FrameOptions o = window();
  o.show_loads = true;
  const int without = count(render_frame(m, mo, 0, o), kGreen);
  o.show_scale_bar = true;
  EXPECT_GT(count(render_frame(m, mo, 0, o), kGreen), without + 34);
}

TEST(RenderLoads, TorqueArcIsDrawnAroundTheCentreOfMassAndNeedsTheVelocities) {
  const Model m = bar(Law::constant(0), Law::constant(3));
  Motion mo = turning(m, 1);
  FrameOptions o = window();
  o.show_loads = true;
  const Image im = render_frame(m, mo, 0, o);
  EXPECT_GT(count(im, kGreen), 30);
  // 13 pt radius around the centre of mass (0.25, 0): the top of the arc at (0.25, 0.13)
  EXPECT_EQ(at_world(im, 0.25, 0.13), kGreen);
  mo.q1.resize(0, 0);
  EXPECT_THROW(render_frame(m, mo, 0, o), Error);
}

TEST(RenderLoads, LabelsWriteTheBodyNames) {
  const Model m = bar(Law::constant(0), Law::constant(0));
  const Motion mo = turning(m, 1);
  FrameOptions o = window();
  o.style.palette = {rgb_hex(0x0000FF)};
  const int without = count(render_frame(m, mo, 0, o), kPaper);
  o.show_labels = true;
  EXPECT_LT(count(render_frame(m, mo, 0, o), kPaper), without - 20);
}

// FrameOptions::title is written at the top left (the mode pictures' "mode 1: ... Hz").
TEST(RenderLoads, TitleIsWrittenAtTheTopLeft) {
  const Model m = bar(Law::constant(0), Law::constant(0));
  const Motion mo = turning(m, 1);
  FrameOptions o = window();
  o.style.ink = rgb_hex(kGreen);
  const Image plain = render_frame(m, mo, 0, o);
  o.title = "mode 1: 2.5 Hz";
  const Image titled = render_frame(m, mo, 0, o);
  int changed = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 100; ++x) changed += titled.at(x, y) != plain.at(x, y);
  EXPECT_GT(changed, 40);
}

}  // namespace
