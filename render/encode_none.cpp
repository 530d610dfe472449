// Built when CMake did not find FFmpeg: animations are refused with what to install.
#include "encoder.hpp"
#include "mo2d/error.hpp"

namespace mo2d::detail {

std::string encoder_support() {
  return "mo2d was built without FFmpeg: install the Debian packages libavcodec-dev "
         "libavformat-dev libswscale-dev libavutil-dev (scripts/install-deps.sh), then "
         "reconfigure and rebuild";
}

EncoderChoice encoder_choice(const std::string& path) {
  throw Error("render: cannot write the animation '" + path + "': " + encoder_support(), path);
}

struct Encoder::Impl {};

Encoder::Encoder(const std::string& path, int /*width*/, int /*height*/, double /*fps*/,
                 const std::vector<const std::uint32_t*>& /*palette_frames*/) {
  encoder_choice(path);
}
Encoder::~Encoder() = default;
void Encoder::add(const std::uint32_t* /*argb*/) {}
std::string Encoder::finish() {
  return {};
}
const std::string& Encoder::codec() const {
  static const std::string none;
  return none;
}

}  // namespace mo2d::detail
