// Animations encoded by FFmpeg (libavcodec, libavformat, libswscale) into memory: a custom
// AVIOContext over a std::string that the muxer may seek in (MP4 writes its index at the end),
// so that the file is written at once and atomically by the caller. VP9 runs in libvpx's
// real-time mode (the 2-core target of issue 37: 300 frames of 800 x 600 in 2 s), H.264 with
// x264's veryfast preset, GIF with a palette of the most frequent colours of a few frames.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "encoder.hpp"
#include "mo2d/error.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace mo2d::detail {

namespace {

std::string av_message(int code) {
  std::array<char, AV_ERROR_MAX_STRING_SIZE> buf{};
  av_strerror(code, buf.data(), buf.size());
  return buf.data();
}

struct MemoryFile {
  std::string bytes{};
  std::int64_t pos = 0;
};

int write_memory(void* opaque, uint8_t* buf, int size) {
  auto* f = static_cast<MemoryFile*>(opaque);
  const auto end = static_cast<size_t>(f->pos) + static_cast<size_t>(size);
  if (end > f->bytes.size()) f->bytes.resize(end);
  std::memcpy(f->bytes.data() + f->pos, buf, static_cast<size_t>(size));
  f->pos = static_cast<std::int64_t>(end);
  return size;
}

int64_t seek_memory(void* opaque, int64_t offset, int whence) {
  auto* f = static_cast<MemoryFile*>(opaque);
  const auto size = static_cast<int64_t>(f->bytes.size());
  if (whence & AVSEEK_SIZE) return size;
  switch (whence & ~AVSEEK_FORCE) {
    case SEEK_SET:
      f->pos = offset;
      break;
    case SEEK_CUR:
      f->pos += offset;
      break;
    case SEEK_END:
      f->pos = size + offset;
      break;
    default:
      return AVERROR(EINVAL);
  }
  return f->pos < 0 ? AVERROR(EINVAL) : f->pos;
}

std::string lower_extension(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The 256 most frequent colours (15-bit bins, each the mean of its pixels) of the sample frames,
// and a lookup table from every 15-bit colour to its nearest palette entry.
struct Palette {
  std::array<std::uint32_t, 256> colours{};
  std::vector<std::uint8_t> lut = std::vector<std::uint8_t>(32768, 0);

  static int bin(std::uint32_t p) {
    return static_cast<int>(((p >> 9) & 0x7C00u) | ((p >> 6) & 0x03E0u) | ((p >> 3) & 0x001Fu));
  }

  Palette(const std::vector<const std::uint32_t*>& frames, size_t pixels) {
    std::vector<std::array<double, 4>> sum(32768, {0, 0, 0, 0});  // count, r, g, b
    for (const std::uint32_t* f : frames)
      for (size_t i = 0; i < pixels; ++i) {
        auto& s = sum[static_cast<size_t>(bin(f[i]))];
        s[0] += 1, s[1] += (f[i] >> 16) & 0xFF, s[2] += (f[i] >> 8) & 0xFF, s[3] += f[i] & 0xFF;
      }
    std::vector<int> order(32768);
    for (int i = 0; i < 32768; ++i) order[static_cast<size_t>(i)] = i;
    std::partial_sort(order.begin(), order.begin() + 256, order.end(), [&](int a, int b) {
      return sum[static_cast<size_t>(a)][0] > sum[static_cast<size_t>(b)][0];
    });
    std::array<std::array<int, 3>, 256> rgb{};
    for (size_t k = 0; k < 256; ++k) {
      const auto& s = sum[static_cast<size_t>(order[k])];
      const int c = order[k];
      // an empty bin keeps its own centre
      for (int ch = 0; ch < 3; ++ch)
        rgb[k][static_cast<size_t>(ch)] =
            s[0] > 0 ? static_cast<int>(std::lround(s[static_cast<size_t>(ch) + 1] / s[0]))
                     : (((c >> (10 - 5 * ch)) & 31) << 3) + 4;
      colours[k] = 0xFF000000u | static_cast<std::uint32_t>(rgb[k][0] << 16) |
                   static_cast<std::uint32_t>(rgb[k][1] << 8) |
                   static_cast<std::uint32_t>(rgb[k][2]);
    }
    for (int c = 0; c < 32768; ++c) {
      const int r = ((c >> 10) << 3) + 4, g = (((c >> 5) & 31) << 3) + 4, b = ((c & 31) << 3) + 4;
      int best = 0, best_d = 1 << 30;
      for (int k = 0; k < 256; ++k) {
        const auto& q = rgb[static_cast<size_t>(k)];
        const int d = (r - q[0]) * (r - q[0]) + (g - q[1]) * (g - q[1]) + (b - q[2]) * (b - q[2]);
        if (d < best_d) best_d = d, best = k;
      }
      lut[static_cast<size_t>(c)] = static_cast<std::uint8_t>(best);
    }
  }
};

}  // namespace

std::string encoder_support() {
  return "";
}

EncoderChoice encoder_choice(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "webm") return {"webm", true, false};
  if (ext == "mp4") return {"mp4", true, false};
  if (ext == "gif") return {"gif", false, true};
  if (ext == "apng") return {"apng", false, false};
  throw Error(
      "render: cannot tell the animation format of '" + path + "' (use .webm, .mp4, .gif or .apng)",
      path);
}

struct Encoder::Impl {
  std::string path{};
  int width = 0, height = 0;
  MemoryFile file{};
  AVFormatContext* fmt = nullptr;
  AVCodecContext* ctx = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  std::unique_ptr<Palette> palette{};
  std::int64_t next_pts = 0;
  std::string codec{};

  void check(int code, const std::string& what) const {
    if (code < 0)
      throw Error("render: FFmpeg could not " + what + " for '" + path + "': " + av_message(code),
                  path);
  }

  ~Impl() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&ctx);
    if (fmt) {
      if (fmt->pb) {
        av_freep(&fmt->pb->buffer);
        avio_context_free(&fmt->pb);
      }
      avformat_free_context(fmt);
    }
  }

  const AVCodec* find_codec(const std::string& muxer) {
    const std::vector<const char*> names = muxer == "webm"  ? std::vector{"libvpx-vp9", "libvpx"}
                                           : muxer == "mp4" ? std::vector{"libx264", "mpeg4"}
                                                            : std::vector{muxer.c_str()};
    for (const char* n : names)
      if (const AVCodec* c = avcodec_find_encoder_by_name(n)) return c;
    throw Error("render: this FFmpeg (libavcodec " LIBAVCODEC_IDENT ") has no encoder for '" +
                    path + "' (tried " + names.front() +
                    (names.size() > 1 ? std::string(", ") + names.back() : std::string()) + ")",
                path);
  }

  void configure(const AVCodec* c, AVRational fps) {
    ctx->width = width;
    ctx->height = height;
    ctx->time_base = av_inv_q(fps);
    ctx->framerate = fps;
    ctx->gop_size = std::max(1, static_cast<int>(2 * av_q2d(fps)));
    codec = c->name;
    if (codec == "gif") {
      ctx->pix_fmt = AV_PIX_FMT_PAL8;
    } else if (codec == "apng") {
      ctx->pix_fmt = AV_PIX_FMT_RGB24;
      // zlib level 3: 301 frames of 800 x 600 took 4.8 s of CPU, 8 s at the default level (the
      // encoder also tries every blend of each frame with the last; Paeth alone was slower)
      ctx->compression_level = 3;
    } else {
      ctx->pix_fmt = AV_PIX_FMT_YUV420P;
      ctx->thread_count = 2;
    }
    if (codec == "libvpx-vp9" || codec == "libvpx") {
      ctx->bit_rate = 0;
      av_opt_set(ctx->priv_data, "deadline", "realtime", 0);
      av_opt_set(ctx->priv_data, "cpu-used", "8", 0);
      av_opt_set(ctx->priv_data, "crf", "30", 0);
      av_opt_set(ctx->priv_data, "row-mt", "1", 0);
    } else if (codec == "libx264") {
      av_opt_set(ctx->priv_data, "preset", "veryfast", 0);
      av_opt_set(ctx->priv_data, "crf", "23", 0);
    } else if (codec == "mpeg4") {
      ctx->flags |= AV_CODEC_FLAG_QSCALE;
      ctx->global_quality = FF_QP2LAMBDA * 4;
    }
    if (fmt->oformat->flags & AVFMT_GLOBALHEADER) ctx->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  }

  void open(const std::string& muxer, double fps_value) {
    check(avformat_alloc_output_context2(&fmt, nullptr, muxer.c_str(), nullptr),
          "find the " + muxer + " muxer");
    constexpr int kBuffer = 1 << 16;
    auto* buffer = static_cast<unsigned char*>(av_malloc(kBuffer));
    fmt->pb = avio_alloc_context(buffer, kBuffer, 1, &file, nullptr, write_memory, seek_memory);
    if (!fmt->pb) av_free(buffer), check(AVERROR(ENOMEM), "allocate the output");
    fmt->flags |= AVFMT_FLAG_CUSTOM_IO;
    const AVCodec* c = find_codec(muxer);
    ctx = avcodec_alloc_context3(c);
    if (!ctx) check(AVERROR(ENOMEM), "allocate the encoder");
    configure(c, av_d2q(fps_value, 1000000));
    check(avcodec_open2(ctx, c, nullptr), "open the " + codec + " encoder");
    stream = avformat_new_stream(fmt, nullptr);
    if (!stream) check(AVERROR(ENOMEM), "add a stream");
    stream->time_base = ctx->time_base;
    stream->avg_frame_rate = ctx->framerate;
    check(avcodec_parameters_from_context(stream->codecpar, ctx), "set the stream");
    AVDictionary* opts = nullptr;
    if (muxer == "apng") av_dict_set(&opts, "plays", "0", 0);  // loop for ever, as the GIF does
    const int r = avformat_write_header(fmt, &opts);
    av_dict_free(&opts);
    check(r, "write the header");
    frame = av_frame_alloc();
    packet = av_packet_alloc();
    if (!frame || !packet) check(AVERROR(ENOMEM), "allocate a frame");
    frame->format = ctx->pix_fmt;
    frame->width = width;
    frame->height = height;
    check(av_frame_get_buffer(frame, 0), "allocate a frame");
    if (ctx->pix_fmt != AV_PIX_FMT_PAL8) {
      sws = sws_getContext(width, height, AV_PIX_FMT_RGB32, width, height, ctx->pix_fmt,
                           SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
      if (!sws) check(AVERROR(EINVAL), "set up the colour conversion");
    }
  }

  void drain() {
    for (;;) {
      const int r = avcodec_receive_packet(ctx, packet);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      check(r, "encode a frame");
      if (packet->duration == 0) packet->duration = 1;
      av_packet_rescale_ts(packet, ctx->time_base, stream->time_base);
      packet->stream_index = stream->index;
      check(av_interleaved_write_frame(fmt, packet), "write a frame");
    }
  }

  void add(const std::uint32_t* argb) {
    check(av_frame_make_writable(frame), "allocate a frame");
    if (palette) {
      auto* pal = reinterpret_cast<std::uint32_t*>(frame->data[1]);
      std::copy(palette->colours.begin(), palette->colours.end(), pal);
      for (int y = 0; y < height; ++y) {
        const std::uint32_t* row = argb + static_cast<size_t>(y) * static_cast<size_t>(width);
        uint8_t* out = frame->data[0] + static_cast<ptrdiff_t>(y) * frame->linesize[0];
        for (int x = 0; x < width; ++x)
          out[x] = palette->lut[static_cast<size_t>(Palette::bin(row[x]))];
      }
    } else {
      const auto* src = reinterpret_cast<const uint8_t*>(argb);
      const int stride = 4 * width;
      sws_scale(sws, &src, &stride, 0, height, frame->data, frame->linesize);
    }
    frame->pts = next_pts++;
    check(avcodec_send_frame(ctx, frame), "encode a frame");
    drain();
  }

  std::string finish() {
    check(avcodec_send_frame(ctx, nullptr), "flush the encoder");
    drain();
    check(av_write_trailer(fmt), "write the trailer");
    avio_flush(fmt->pb);
    return std::move(file.bytes);
  }
};

Encoder::Encoder(const std::string& path, int width, int height, double fps,
                 const std::vector<const std::uint32_t*>& palette_frames)
    : impl_(std::make_unique<Impl>()) {
  const EncoderChoice choice = encoder_choice(path);
  impl_->path = path;
  impl_->width = width;
  impl_->height = height;
  av_log_set_level(AV_LOG_ERROR);
  if (choice.palette)
    impl_->palette = std::make_unique<Palette>(
        palette_frames, static_cast<size_t>(width) * static_cast<size_t>(height));
  impl_->open(choice.muxer, fps);
}

Encoder::~Encoder() = default;

void Encoder::add(const std::uint32_t* argb) {
  impl_->add(argb);
}

std::string Encoder::finish() {
  return impl_->finish();
}

const std::string& Encoder::codec() const {
  return impl_->codec;
}

}  // namespace mo2d::detail
