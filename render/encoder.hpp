#pragma once
// Internal to mo2d_render: an animation encoded in memory by FFmpeg (encode_ffmpeg.cpp), or the
// error that says FFmpeg is missing (encode_none.cpp, when CMake did not find it).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mo2d::detail {

// "" when FFmpeg is linked, else what to install.
std::string encoder_support();

// The container and codec of an output path: webm (VP9, else VP8), mp4 (libx264, else mpeg4),
// gif, apng. Error for another extension.
struct EncoderChoice {
  std::string muxer{};     // libavformat's name: webm, mp4, gif, apng
  bool even_size = false;  // 4:2:0 video: width and height must be even
  bool palette = false;    // GIF: 256 colours
};
EncoderChoice encoder_choice(const std::string& path);

class Encoder {
 public:
  // Frames of width x height pixels (0xAARRGGBB words, row by row) at `fps` frames per second.
  // `palette_frames` (GIF only): frames whose colours make the palette.
  Encoder(const std::string& path, int width, int height, double fps,
          const std::vector<const std::uint32_t*>& palette_frames);
  ~Encoder();
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  void add(const std::uint32_t* argb);
  // The file's bytes (ends the encoding).
  std::string finish();
  const std::string& codec() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mo2d::detail
