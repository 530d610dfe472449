#pragma once
// Colours, the qualitative palette, and an RGB image in memory (what a frame or a plot is drawn
// into before it is encoded). Rendering uses Cairo, but no Cairo type appears in these headers:
// only the mo2d_render library links Cairo.
#include <cstdint>
#include <string>
#include <vector>

namespace mo2d {

// A colour: red, green, blue in 0..1.
struct Rgb {
  double r = 0, g = 0, b = 0;  // 0..1
};
// 0xRRGGBB -> Rgb.
Rgb rgb_hex(unsigned hex);
// Okabe & Ito's colour-blind-safe qualitative palette without black and yellow (poor on white):
// blue, orange, bluish green, reddish purple, sky blue, vermillion, then grey, yellow.
const std::vector<Rgb>& okabe_ito();

// An opaque image, row-major, one 0xAARRGGBB word per pixel (alpha always 0xFF).
struct Image {
  // size in pixels
  int width = 0, height = 0;
  // width x height pixels, row by row from the top left
  std::vector<std::uint32_t> argb{};
  // The pixel at column x, row y (0-based, from the top left).
  std::uint32_t at(int x, int y) const { return argb[static_cast<size_t>(y) * width + x]; }
};
// 0xRRGGBB part of a pixel.
inline unsigned rgb_of(std::uint32_t pixel) {
  return pixel & 0xFFFFFFu;
}

// The image as PNG bytes (deterministic: the same image gives the same bytes).
std::string encode_png(const Image& image);
// Write the image as PNG to `path`, atomically (temporary file in the same folder, then rename).
// Throws Error naming the path if it cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace mo2d
