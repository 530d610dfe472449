#pragma once
// A PNG encoder for opaque RGB images (zlib, fast settings). Cairo's own PNG writer uses zlib's
// default compression, about 20 ms for an 800 x 600 frame; this one takes a few milliseconds
// for files of similar size (line drawings on a flat background). Internal to mo2d_render.
#include <cstdint>
#include <string>

namespace mo2d::detail {

// Pixels 0x??RRGGBB (the top byte is ignored), `stride` words per row. Deterministic.
std::string encode_png_rgb(const std::uint32_t* pixels, int width, int height, int stride);

}  // namespace mo2d::detail
