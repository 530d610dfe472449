// Rendering benchmarks (Google Benchmark): one 800 x 600 frame of the Whitworth mechanism (501-
// sample reference run, sample 250, efforts and centres of mass shown), drawn into an image
// (BM_FrameDraw: fitting the view over the run, drawing, copying the pixels out) and drawn then
// encoded as PNG bytes (BM_FrameDrawEncode; no disk I/O). See docs/performance.md.
#include <benchmark/benchmark.h>

#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"
#include "mo2d/render.hpp"

namespace {

struct Whitworth {
  mo2d::mechanisms::Example ex = mo2d::mechanisms::whitworth();
  mo2d::Model model = mo2d::build_model(ex.system);
  mo2d::Motion motion = mo2d::motion_of(mo2d::inverse_dynamics(model, ex.motion, ex.run));
  mo2d::FrameOptions options{};  // 800 x 600 at 96 dpi
};

void BM_FrameDraw(benchmark::State& state) {
  const Whitworth w;
  for (auto _ : state) {
    mo2d::Image im = mo2d::render_frame(w.model, w.motion, 250, w.options);
    benchmark::DoNotOptimize(im.argb.data());
  }
}
BENCHMARK(BM_FrameDraw)->Unit(benchmark::kMillisecond);

void BM_FrameDrawEncode(benchmark::State& state) {
  const Whitworth w;
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string png = mo2d::encode_png(mo2d::render_frame(w.model, w.motion, 250, w.options));
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["png_bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_FrameDrawEncode)->Unit(benchmark::kMillisecond);

// The parts: fitting the view over the 501 samples (done once per frame by render_frame), and
// PNG encoding of a finished image.
void BM_FitView(benchmark::State& state) {
  const Whitworth w;
  for (auto _ : state) {
    const mo2d::View v = mo2d::fit_view(w.model, w.motion, w.options);
    benchmark::DoNotOptimize(v.scale);
  }
}
BENCHMARK(BM_FitView)->Unit(benchmark::kMillisecond);

void BM_EncodePng(benchmark::State& state) {
  const Whitworth w;
  const mo2d::Image im = mo2d::render_frame(w.model, w.motion, 250, w.options);
  for (auto _ : state) {
    const std::string png = mo2d::encode_png(im);
    benchmark::DoNotOptimize(png.data());
  }
}
BENCHMARK(BM_EncodePng)->Unit(benchmark::kMillisecond);

}  // namespace
