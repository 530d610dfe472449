// Rendering (mo2d_render): pixels at known places, deterministic output, sizes, errors.
#include "mo2d/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace {

using namespace mo2d;
namespace fs = std::filesystem;

constexpr unsigned kMagenta = 0xFF00FF;
constexpr unsigned kPaper = 0xF4F1E8;

// A two-link arm in a known configuration: shoulder at the ground origin, elbow at (0.5, 0.3),
// hand at (0.8, 0.6). Nothing is symmetric in x or y, so a flipped axis moves the joints.
Model arm() {
  System s("arm");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "upper",
              .nodes = {{"O", {0, 0}}, {"A", {0.5, 0.3}}},
              .mass = 1,
              .inertia = 0.02,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "fore",
              .nodes = {{"A", {0.5, 0.3}}, {"B", {0.8, 0.6}}},
              .mass = 1,
              .inertia = 0.01,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_revolute({.name = "shoulder", .node_a = "ground.O", .node_b = "upper.O", .actuated = true});
  s.add_revolute({.name = "elbow", .node_a = "upper.A", .node_b = "fore.A"});
  return build_model(s);
}

// 200 x 200 pixels at 72 dpi (1 px = 1 pt) showing the world square [-1, 1]^2: a world point
// (x, y) is at pixel (100 + 100 x, 100 - 100 y), written out here independently of to_pixel.
FrameOptions plain_window() {
  FrameOptions o;
  o.width = 200;
  o.height = 200;
  o.dpi = 72;
  o.window = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  o.show_com = o.show_time = o.show_scale_bar = o.show_axes = o.show_efforts = false;
  o.style.joint_fill = rgb_hex(kMagenta);
  o.style.background = rgb_hex(kPaper);
  o.style.joint_radius = 4;
  return o;
}
unsigned pixel_at_world(const Image& im, double x, double y) {
  return rgb_of(im.at(static_cast<int>(100 + 100 * x), static_cast<int>(100 - 100 * y)));
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
// Width and height from a PNG's IHDR chunk.
std::pair<int, int> png_size(const std::string& png) {
  auto be32 = [&](size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) |
           (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  EXPECT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  return {static_cast<int>(be32(16)), static_cast<int>(be32(20))};
}

fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() /
                     ("mo2d_render_test_" + name + "_" +
                      std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Render, JointsAreDrawnAtTheirProjectedPositions) {
  const Model m = arm();
  const Image im = render_frame(m, single_configuration(m.q0), 0, plain_window());
  EXPECT_EQ(pixel_at_world(im, 0.0, 0.0), kMagenta);   // shoulder
  EXPECT_EQ(pixel_at_world(im, 0.5, 0.3), kMagenta);   // elbow
  EXPECT_NE(pixel_at_world(im, 0.8, 0.6), kMagenta);   // the hand is no joint
  EXPECT_NE(pixel_at_world(im, 0.8, 0.6), kPaper);     // ... but the end of the forearm
  EXPECT_NE(pixel_at_world(im, 0.5, -0.3), kMagenta);  // mirror image of the elbow: empty
  EXPECT_EQ(pixel_at_world(im, 0.5, -0.3), kPaper);
  EXPECT_EQ(pixel_at_world(im, -0.8, 0.8), kPaper);  // far from the mechanism: background
  EXPECT_EQ(pixel_at_world(im, 0.9, -0.9), kPaper);
}

TEST(Render, ToPixelFollowsTheWindow) {
  const Model m = arm();
  const View v = fit_view(m, single_configuration(m.q0), plain_window());
  const Eigen::Vector2d p = to_pixel(v, {0.5, 0.3});
  EXPECT_NEAR(p.x(), 150, 1e-9);
  EXPECT_NEAR(p.y(), 70, 1e-9);
}

TEST(Render, FittedViewKeepsEveryJointOfTheWhitworthRunInside) {
  const mechanisms::Example ex = mechanisms::whitworth();
  const Model m = build_model(ex.system);
  InverseOptions run = ex.run;
  run.samples = 41;
  const Trajectory r = inverse_dynamics(m, ex.motion, run);
  FrameOptions o;
  o.show_com = o.show_efforts = false;
  o.style.joint_fill = rgb_hex(kMagenta);
  const Motion motion = motion_of(r);
  const View v = fit_view(m, motion, o);
  EXPECT_DOUBLE_EQ(v.width, 800);
  for (int k : {0, 13, 27, 40}) {
    const Image im = render_frame(m, motion, k, o);
    const Eigen::VectorXd q0 = r.q0.row(k).transpose();
    // every node of the Whitworth bodies is a revolute joint or a pin (merged joints included)
    for (const Body& b : m.bodies)
      for (const NodeRef& n : b.nodes) {
        const Eigen::Vector2d p = to_pixel(v, node_position(n, q0));
        ASSERT_GT(p.x(), 0);
        ASSERT_LT(p.x(), o.width);
        ASSERT_GT(p.y(), 0);
        ASSERT_LT(p.y(), o.height);
        EXPECT_EQ(rgb_of(im.at(static_cast<int>(p.x()), static_cast<int>(p.y()))), kMagenta)
            << b.name << " at sample " << k;
      }
    EXPECT_EQ(rgb_of(im.at(2, o.height / 2)), 0xFFFFFFu);  // the left border is background
  }
}

TEST(Render, SameInputGivesByteIdenticalFiles) {
  const Model m = arm();
  const Motion one = single_configuration(m.q0, 0.25);
  const fs::path d = scratch_dir("bytes");
  FrameOptions o;
  o.width = 320;
  o.height = 240;
  write_frame(m, one, 0, o, (d / "a.png").string());
  write_frame(m, one, 0, o, (d / "b.png").string());
  const std::string a = read_file(d / "a.png"), b = read_file(d / "b.png");
  EXPECT_GT(a.size(), 100u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(encode_png(render_frame(m, one, 0, o)), a);
  // nothing but the two files is left behind (atomic writes remove their temporaries)
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 2);
  fs::remove_all(d);
}

TEST(Render, ImageSizes) {
  const Model m = arm();
  const Motion one = single_configuration(m.q0);
  FrameOptions o;
  o.width = 321;
  o.height = 123;
  const Image im = render_frame(m, one, 0, o);
  EXPECT_EQ(im.width, 321);
  EXPECT_EQ(im.height, 123);
  EXPECT_EQ(png_size(encode_png(im)), std::pair(321, 123));

  FilmstripOptions f;
  f.frames = 3;
  f.gap = 4;
  f.tile.width = 100;
  f.tile.height = 80;
  f.tile.dpi = 72;  // 4 pt = 4 px
  const Image strip = render_filmstrip(m, one, f);
  EXPECT_EQ(strip.width, 3 * 100 + 2 * 4);
  EXPECT_EQ(strip.height, 80);
  f.columns = 2;
  const Image grid = render_filmstrip(m, one, f);
  EXPECT_EQ(grid.width, 2 * 100 + 4);
  EXPECT_EQ(grid.height, 2 * 80 + 4);

  Plot p;
  p.width = 333;
  p.height = 222;
  p.series.push_back({"s", {0, 1}, {0, 1}, {}, false, false});
  const Image pi = render_plot(p);
  EXPECT_EQ(pi.width, 333);
  EXPECT_EQ(pi.height, 222);
}

TEST(Render, VectorFormats) {
  const Model m = arm();
  const fs::path d = scratch_dir("vector");
  FrameOptions o;
  write_frame(m, single_configuration(m.q0), 0, o, (d / "f.svg").string());
  write_frame(m, single_configuration(m.q0), 0, o, (d / "f.pdf").string());
  EXPECT_EQ(read_file(d / "f.svg").substr(0, 5), "<?xml");
  EXPECT_EQ(read_file(d / "f.pdf").substr(0, 4), "%PDF");
  fs::remove_all(d);
}

TEST(Render, PlotOfAKnownLinePutsItsPixelsOnTheLine) {
  Plot p;
  p.width = 400;
  p.height = 300;
  p.grid = false;
  p.legend = false;
  p.line_width = 4;
  p.x = {"x (m)", false, std::pair{0.0, 10.0}};
  p.y = {"y (m)", false, std::pair{0.0, 20.0}};
  Series s{"y = 2x", {}, {}, rgb_hex(0xFF0000), false, false};
  for (int i = 0; i <= 100; ++i) s.x.push_back(0.1 * i), s.y.push_back(0.2 * i);
  p.series.push_back(s);
  const Image im = render_plot(p);
  const PlotLayout L = plot_layout(p);
  EXPECT_GT(L.right - L.left, 250);
  EXPECT_GT(L.bottom - L.top, 180);
  auto red_rows = [&](int col) {  // centre of the red pixels in a column
    double sum = 0;
    int n = 0;
    for (int y = 0; y < im.height; ++y)
      if (rgb_of(im.at(col, y)) == 0xFF0000u) sum += y, ++n;
    return n ? sum / n : -1.0;
  };
  for (double x : {2.5, 5.0, 7.5}) {
    const Eigen::Vector2d q = to_pixel(L, x, 2 * x);
    EXPECT_NEAR(q.x(), L.left + x / 10 * (L.right - L.left), 1e-9);
    EXPECT_NEAR(q.y(), L.bottom - 2 * x / 20 * (L.bottom - L.top), 1e-9);
    EXPECT_EQ(rgb_of(im.at(static_cast<int>(q.x()), static_cast<int>(q.y()))), 0xFF0000u);
    EXPECT_NEAR(red_rows(static_cast<int>(q.x())), q.y(), 1.5);
    const Eigen::Vector2d off = to_pixel(L, x, 0.5 * x);  // below the line: background
    EXPECT_EQ(rgb_of(im.at(static_cast<int>(off.x()), static_cast<int>(off.y()))), 0xFFFFFFu);
  }
  // the line rises to the right on screen: rows decrease with x
  EXPECT_LT(red_rows(static_cast<int>(to_pixel(L, 7.5, 15).x())),
            red_rows(static_cast<int>(to_pixel(L, 2.5, 5).x())) - 50);
}

TEST(Render, LogAxesPutDecadesEvenlyApart) {
  Plot p;
  p.x.log = p.y.log = true;
  p.series.push_back({"error", {1e-3, 1e-2, 1e-1}, {1e-9, 1e-6, 1e-3}, {}, false, true});
  const PlotLayout L = plot_layout(p);
  EXPECT_DOUBLE_EQ(L.x0, 1e-3);
  EXPECT_DOUBLE_EQ(L.x1, 1e-1);
  EXPECT_DOUBLE_EQ(L.y0, 1e-9);
  EXPECT_DOUBLE_EQ(L.y1, 1e-3);
  const double a = to_pixel(L, 1e-3, 1e-9).y(), b = to_pixel(L, 1e-2, 1e-6).y(),
               c = to_pixel(L, 1e-1, 1e-3).y();
  EXPECT_NEAR(a - b, b - c, 1e-9);
  EXPECT_NO_THROW(render_plot(p));
}

TEST(Render, NiceTicks) {
  const std::vector<double> t = nice_ticks(0, 1, 5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_NEAR(t[1], 0.2, 1e-15);
  EXPECT_EQ(nice_ticks(-3.7, 12.2, 6), (std::vector<double>{0, 5, 10}));
  EXPECT_EQ(nice_ticks(0, 16, 6), (std::vector<double>{0, 5, 10, 15}));
  EXPECT_EQ(nice_ticks(-1.5, 1.0, 5), (std::vector<double>{-1.5, -1.0, -0.5, 0, 0.5, 1.0}));
  EXPECT_EQ(decade_ticks(1e-3, 10).size(), 5u);
  EXPECT_EQ(decade_ticks(1e-16, 1).size(), 9u);  // every second decade past 8
  EXPECT_THROW(nice_ticks(1, 1), Error);
  EXPECT_THROW(decade_ticks(0, 1), Error);
}

TEST(Render, BadInputGivesAClearError) {
  const Model m = arm();
  const Motion one = single_configuration(m.q0);
  FrameOptions o;
  const Motion empty{Eigen::VectorXd(0), Eigen::MatrixXd(0, m.n0), {}};
  EXPECT_THROW(render_frame(m, empty, 0, o), Error);
  EXPECT_THROW(fit_view(m, empty, o), Error);
  FrameOptions zero = o;
  zero.width = 0;
  EXPECT_THROW(render_frame(m, one, 0, zero), Error);
  FrameOptions nodpi = o;
  nodpi.dpi = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(render_frame(m, one, 0, nodpi), Error);
  EXPECT_THROW(render_frame(m, one, 1, o), Error);  // no sample 1

  Motion nan = one;
  nan.q0(0, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    render_frame(m, nan, 0, o);
    ADD_FAILURE() << "no error for a NaN coordinate";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), m.coordinate_labels[1]);
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  Motion wrong = one;
  wrong.q0 = Eigen::MatrixXd::Zero(1, m.n0 + 1);
  EXPECT_THROW(render_frame(m, wrong, 0, o), Error);

  FrameOptions traced = o;
  traced.traces = {"upper.Z"};
  EXPECT_THROW(render_frame(m, one, 0, traced), Error);

  EXPECT_THROW(write_frame(m, one, 0, o, "/nonexistent-mo2d-dir/frame.png"), Error);
  EXPECT_THROW(write_frame(m, one, 0, o, "frame.gif"), Error);
  FilmstripOptions f;
  f.frames = 0;
  EXPECT_THROW(render_filmstrip(m, one, f), Error);

  Plot p;
  EXPECT_THROW(render_plot(p), Error);  // no series
  p.series.push_back({"bad", {0, 1, 2}, {0, 1}, {}, false, false});
  EXPECT_THROW(render_plot(p), Error);  // sizes differ
  p.series[0] = {"zeros", {0, 1}, {0, 0}, {}, false, false};
  p.y.log = true;
  EXPECT_THROW(render_plot(p), Error);  // nothing positive on a log axis
  p.x.range = std::pair{0.0, 1.0};
  p.y.range = std::pair{1e-18, 1e-12};
  EXPECT_NO_THROW(render_plot(p));  // both ranges given: empty axes
  p.x.range.reset();
  p.y.range.reset();
  p.y.log = false;
  p.width = -3;
  EXPECT_THROW(render_plot(p), Error);
  p.width = 400;
  EXPECT_THROW(write_plot(p, "/nonexistent-mo2d-dir/plot.png"), Error);
}

TEST(Render, InverseRunWritesFramesFilmstripAndPlots) {
  const mechanisms::Example ex = mechanisms::whitworth();
  const Model m = build_model(ex.system);
  InverseOptions run = ex.run;
  run.samples = 51;
  const Trajectory r = inverse_dynamics(m, ex.motion, run);
  const fs::path d = scratch_dir("run");
  RenderJob job;
  job.dir = (d / "out").string();
  job.name = "whitworth";
  job.frames = true;
  job.every = 10;
  job.frame.width = 200;
  job.frame.height = 150;
  job.filmstrip_options.frames = 4;
  job.filmstrip_options.tile.width = 160;
  job.filmstrip_options.tile.height = 120;
  const RenderOutputs out = render_run(m, r, job);
  ASSERT_EQ(out.frames.size(), 6u);  // samples 0, 10, ..., 50
  EXPECT_EQ(fs::path(out.frames[0]).filename(), "whitworth_0001.png");
  EXPECT_EQ(fs::path(out.frames[5]).filename(), "whitworth_0006.png");
  for (const std::string& f : out.frames) EXPECT_EQ(png_size(read_file(f)), std::pair(200, 150));
  EXPECT_TRUE(fs::exists(out.filmstrip));
  ASSERT_EQ(out.plots.size(), 2u);
  EXPECT_EQ(fs::path(out.plots[0]).filename(), "whitworth_efforts.png");
  EXPECT_EQ(fs::path(out.plots[1]).filename(), "whitworth_residuals.png");
  for (const std::string& f : out.plots) EXPECT_EQ(png_size(read_file(f)), std::pair(800, 450));
  EXPECT_TRUE(out.video.empty());

  const Plot e = efforts_plot(r);
  ASSERT_EQ(e.series.size(), 1u);
  EXPECT_EQ(e.series[0].label, "crank_pivot.torque");
  EXPECT_EQ(e.y.label, "torque (N\u00B7m)");
  fs::remove_all(d);
}

TEST(Render, ForwardRunWritesFilmstripAndPlots) {
  const mechanisms::Example ex = mechanisms::pendulum({.theta0 = 0.5});
  const Model m = build_model(ex.system);
  const State start = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  ForwardOptions o;
  o.t1 = 1;
  o.samples = 21;
  const Trajectory r = forward_dynamics(m, start, o);
  const fs::path d = scratch_dir("forward");
  RenderJob job;
  job.dir = d.string();
  job.name = "pendulum";
  job.format = "svg";
  job.filmstrip_options.tile.traces = {"link.P"};
  const RenderOutputs out = render_run(m, r, job);
  EXPECT_TRUE(out.frames.empty());
  EXPECT_EQ(fs::path(out.filmstrip).filename(), "pendulum_filmstrip.svg");
  ASSERT_EQ(out.plots.size(), 2u);
  EXPECT_EQ(fs::path(out.plots[0]).filename(), "pendulum_energies.svg");
  EXPECT_EQ(fs::path(out.plots[1]).filename(), "pendulum_residuals.svg");
  for (const std::string& f : out.plots) EXPECT_EQ(read_file(f).substr(0, 5), "<?xml");
  fs::remove_all(d);
}

TEST(Render, EffortSymbolTakesTheColourOfItsSign) {
  const Model m = arm();
  Motion motion = single_configuration(m.q0);
  FrameOptions o = plain_window();
  o.show_efforts = true;
  o.show_effort_values = false;
  o.style.positive = rgb_hex(0x00FF00);
  o.style.negative = rgb_hex(0x0000FF);
  motion.efforts = Eigen::MatrixXd::Constant(1, 1, 2.0);  // the run's peak, positive
  auto count = [](const Image& im, unsigned c) {
    int n = 0;
    for (auto p : im.argb) n += rgb_of(p) == c;
    return n;
  };
  const Image pos = render_frame(m, motion, 0, o);
  EXPECT_GT(count(pos, 0x00FF00), 20);
  EXPECT_EQ(count(pos, 0x0000FF), 0);
  motion.efforts(0, 0) = -2.0;
  const Image neg = render_frame(m, motion, 0, o);
  EXPECT_GT(count(neg, 0x0000FF), 20);
  EXPECT_EQ(count(neg, 0x00FF00), 0);
}

}  // namespace
