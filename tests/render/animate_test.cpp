// Animations (mo2d/render/animate.hpp): the files decoded back with libavformat (frame count,
// size, duration) and their frames compared with the still frames of the same times.
#include "mo2d/render/animate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"

#if MO2D_TEST_FFMPEG
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}
#endif

namespace {

using namespace mo2d;
namespace fs = std::filesystem;

// The Whitworth quick-return run sampled at 30 samples per second: frame i of a real-time
// animation at 30 frames/s is sample i.
struct WhitworthRun {
  Model model;
  Trajectory run;
  Motion motion;
  WhitworthRun() : model(build_model(mechanisms::whitworth().system)) {
    const mechanisms::Example ex = mechanisms::whitworth();
    InverseOptions o = ex.run;
    o.t0 = 0, o.t1 = 1, o.samples = 31;
    run = inverse_dynamics(model, ex.motion, o);
    motion = motion_of(run);
  }
};
const WhitworthRun& whitworth_run() {
  static const WhitworthRun r;
  return r;
}

AnimationOptions small_animation() {
  AnimationOptions a;
  a.frame.width = 160;
  a.frame.height = 120;
  a.fps = 30;
  return a;
}

fs::path animation_dir() {
  const fs::path d =
      fs::temp_directory_path() / ("mo2d_animate_test_" + std::to_string(::getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Animate, FrameTimesFollowTheRateAndTheSlowMotionAndAreBounded) {
  const Motion& m = whitworth_run().motion;
  AnimationOptions a = small_animation();
  EXPECT_EQ(animation_times(m, a).size(), 31u);
  a.slow = 4;
  const std::vector<double> t = animation_times(m, a);
  ASSERT_EQ(t.size(), 121u);
  EXPECT_NEAR(t[1], 1.0 / 120, 1e-15);
  a.max_frames = 100;
  try {
    animation_times(m, a);
    FAIL() << "121 frames passed a limit of 100";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("121 frames, more than the limit of 100"),
              std::string::npos)
        << e.what();
  }
  a.max_frames = 3000;
  a.fps = 0;
  EXPECT_THROW(animation_times(m, a), Error);
}

TEST(Animate, TheFrameAtASampleTimeIsTheStillFrame) {
  const WhitworthRun& w = whitworth_run();
  AnimationOptions a = small_animation();
  a.slow = 2;  // frame 2k is sample k; odd frames are between samples
  const Image still = render_frame(w.model, w.motion, 7, a.frame);
  const Image frame = render_animation_frame(w.model, w.motion, a, 14);
  ASSERT_EQ(frame.width, still.width);
  ASSERT_EQ(frame.height, still.height);
  EXPECT_EQ(frame.argb, still.argb);
  EXPECT_NE(render_animation_frame(w.model, w.motion, a, 15).argb, still.argb);
}

TEST(Animate, ThePlotStripsCursorIsAtTheFramesTime) {
  const WhitworthRun& w = whitworth_run();
  AnimationOptions a = small_animation();
  a.frame.width = 320;
  a.plot = true;
  a.strip.label = "crank torque";
  const Eigen::VectorXd u = w.run.efforts.col(0);
  a.strip.values.assign(u.data(), u.data() + u.size());
  a.strip.height = 100;
  Plot p;  // the strip's plot as animate.cpp sets it up: its layout gives the cursor's column
  p.width = 320, p.height = 100, p.dpi = a.frame.dpi, p.legend = false;
  p.x.label = "time (s)", p.x.range = std::pair{0.0, 1.0}, p.y.label = a.strip.label;
  const Eigen::VectorXd& t = w.run.time;
  p.series.push_back(
      {a.strip.label, {t.data(), t.data() + t.size()}, a.strip.values, {}, false, false});
  const PlotLayout L = plot_layout(p);
  for (int i : {3, 20}) {
    const Image im = render_animation_frame(w.model, w.motion, a, i);
    ASSERT_EQ(im.height, 220);
    const int x = static_cast<int>(std::lround(to_pixel(L, i / 30.0, 0).x()));
    // a row of the cursor away from its dot at the value
    const double dot = to_pixel(L, i / 30.0, a.strip.values[static_cast<size_t>(i)]).y();
    const int y = 120 + static_cast<int>(dot - L.top > L.bottom - dot ? L.top + 3 : L.bottom - 3);
    unsigned reddest = 0;
    int at = -1;
    for (int dx = -6; dx <= 6; ++dx) {
      const unsigned c = rgb_of(im.at(x + dx, y));
      const unsigned red = ((c >> 16) & 0xFF) - std::min((c >> 8) & 0xFF, c & 0xFF);
      if ((c >> 16 & 0xFF) > ((c >> 8) & 0xFF) && red > reddest) reddest = red, at = x + dx;
    }
    EXPECT_LE(std::abs(at - x), 1) << "frame " << i;
  }
  a.strip.values.pop_back();
  EXPECT_THROW(render_animation_frame(w.model, w.motion, a, 0), Error);
}

TEST(Animate, TooManyFramesWriteNoFile) {
  const WhitworthRun& w = whitworth_run();
  AnimationOptions a = small_animation();
  a.max_frames = 10;
  const fs::path d = animation_dir();
  if (!animation_support().empty()) GTEST_SKIP() << animation_support();
  EXPECT_THROW(write_animation(w.model, w.motion, a, (d / "run.webm").string()), Error);
  EXPECT_THROW(write_animation(w.model, w.motion, small_animation(), (d / "run.avi").string()),
               Error);
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

#if MO2D_TEST_FFMPEG

// A file decoded back: its frames as 0xRRGGBB pixels, size, and duration (s).
struct Decoded {
  int width = 0, height = 0;
  std::vector<std::vector<std::uint32_t>> frames{};
  double duration = 0;
};

Decoded decode(const std::string& path) {
  Decoded out;
  AVFormatContext* fmt = nullptr;
  if (avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) < 0) return out;
  avformat_find_stream_info(fmt, nullptr);
  const int s = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  const AVStream* st = fmt->streams[s];
  const AVCodec* codec = avcodec_find_decoder(st->codecpar->codec_id);
  AVCodecContext* ctx = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(ctx, st->codecpar);
  avcodec_open2(ctx, codec, nullptr);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  SwsContext* sws = nullptr;
  double end = 0;
  auto receive = [&] {
    while (avcodec_receive_frame(ctx, frame) == 0) {
      out.width = frame->width, out.height = frame->height;
      sws = sws_getCachedContext(
          sws, frame->width, frame->height, static_cast<AVPixelFormat>(frame->format), frame->width,
          frame->height, AV_PIX_FMT_RGB32, SWS_POINT | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
      std::vector<std::uint32_t> px(static_cast<size_t>(frame->width * frame->height));
      uint8_t* dst[1] = {reinterpret_cast<uint8_t*>(px.data())};
      const int stride[1] = {4 * frame->width};
      sws_scale(sws, frame->data, frame->linesize, 0, frame->height, dst, stride);
      for (auto& p : px) p &= 0xFFFFFFu;
      out.frames.push_back(std::move(px));
      const double t = static_cast<double>(frame->best_effort_timestamp) * av_q2d(st->time_base);
      end = std::max(end, t + static_cast<double>(frame->pkt_duration) * av_q2d(st->time_base));
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == s) avcodec_send_packet(ctx, pkt), receive();
    av_packet_unref(pkt);
  }
  avcodec_send_packet(ctx, nullptr);
  receive();
  out.duration = end;
  sws_freeContext(sws);
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&ctx);
  avformat_close_input(&fmt);
  return out;
}

double mean_difference(const std::vector<std::uint32_t>& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int sh : {0, 8, 16})
      sum += std::abs(static_cast<int>((a[i] >> sh) & 0xFF) -
                      static_cast<int>((b.argb[i] >> sh) & 0xFF));
  return sum / static_cast<double>(a.size());
}

std::vector<std::uint32_t> rgb_pixels(const Image& im) {
  std::vector<std::uint32_t> v(im.argb);
  for (auto& p : v) p &= 0xFFFFFFu;
  return v;
}

TEST(Animate, ApngFramesAreTheStillFramesOfTheSameTimes) {
  const WhitworthRun& w = whitworth_run();
  const fs::path d = animation_dir();
  const std::string path = (d / "run.apng").string();
  const AnimationInfo info = write_animation(w.model, w.motion, small_animation(), path);
  EXPECT_EQ(info.frames, 31);
  EXPECT_EQ(info.codec, "apng");
  const Decoded v = decode(path);
  ASSERT_EQ(v.frames.size(), 31u);
  EXPECT_EQ(v.width, 160);
  EXPECT_EQ(v.height, 120);
  EXPECT_NEAR(v.duration, 31 / 30.0, 0.5 / 30);
  for (int i : {0, 12, 30}) {
    const Image still = render_frame(w.model, w.motion, i, small_animation().frame);
    EXPECT_EQ(v.frames[static_cast<size_t>(i)], rgb_pixels(still)) << "frame " << i;
  }
  // a frame one off in time is another picture
  const Image next = render_frame(w.model, w.motion, 13, small_animation().frame);
  EXPECT_NE(v.frames[12], rgb_pixels(next));
  fs::remove_all(d);
}

TEST(Animate, WebmFramesAreClosestToTheStillFramesOfTheSameTimes) {
  const WhitworthRun& w = whitworth_run();
  const fs::path d = animation_dir();
  const std::string path = (d / "run.webm").string();
  const AnimationInfo info = write_animation(w.model, w.motion, small_animation(), path);
  EXPECT_EQ(info.codec, "libvpx-vp9");
  const Decoded v = decode(path);
  ASSERT_EQ(v.frames.size(), 31u);
  EXPECT_EQ(v.width, 160);
  EXPECT_EQ(v.height, 120);
  EXPECT_NEAR(v.duration, 31 / 30.0, 0.5 / 30);
  for (int i : {5, 17, 29}) {
    double diff[3];
    for (int j = 0; j < 3; ++j)
      diff[j] =
          mean_difference(v.frames[static_cast<size_t>(i)],
                          render_frame(w.model, w.motion, i - 1 + j, small_animation().frame));
    EXPECT_LT(diff[1], 0.7 * std::min(diff[0], diff[2]))
        << "frame " << i << ": differences to the stills " << i - 1 << ", " << i << ", " << i + 1
        << ": " << diff[0] << ", " << diff[1] << ", " << diff[2];
  }
  fs::remove_all(d);
}

TEST(Animate, GifAndMp4HaveEveryFrameAtItsSize) {
  const WhitworthRun& w = whitworth_run();
  const fs::path d = animation_dir();
  AnimationOptions a = small_animation();
  a.frame.width = 161;  // odd: the MP4 rounds it up to even, the GIF keeps it
  for (const char* ext : {"gif", "mp4"}) {
    const std::string path = (d / (std::string("run.") + ext)).string();
    const AnimationInfo info = write_animation(w.model, w.motion, a, path);
    const Decoded v = decode(path);
    EXPECT_EQ(v.frames.size(), 31u) << ext;
    EXPECT_EQ(v.width, std::string(ext) == "gif" ? 161 : 162) << ext;
    EXPECT_EQ(info.width, v.width) << ext;
    EXPECT_EQ(v.height, 120) << ext;
    EXPECT_NEAR(v.duration, 31 / 30.0, 0.5 / 30) << ext;
  }
  fs::remove_all(d);
}

#endif

}  // namespace
