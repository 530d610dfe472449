// Colours, the palette, and PNG encoding of an Image.
#include "mo2d/render/image.hpp"

#include "canvas.hpp"
#include "mo2d/error.hpp"
#include "png.hpp"

namespace mo2d {

Rgb rgb_hex(unsigned hex) {
  return {((hex >> 16) & 0xFF) / 255.0, ((hex >> 8) & 0xFF) / 255.0, (hex & 0xFF) / 255.0};
}

const std::vector<Rgb>& okabe_ito() {
  // Okabe, M. & Ito, K. (2008), Color Universal Design; black and yellow moved to the end.
  static const std::vector<Rgb> palette = {rgb_hex(0x0072B2), rgb_hex(0xE69F00), rgb_hex(0x009E73),
                                           rgb_hex(0xCC79A7), rgb_hex(0x56B4E9), rgb_hex(0xD55E00),
                                           rgb_hex(0x7F7F7F), rgb_hex(0xF0E442)};
  return palette;
}

std::string encode_png(const Image& image) {
  detail::check_size(image.width, image.height, 72, "image");
  if (image.argb.size() != static_cast<size_t>(image.width) * image.height)
    throw Error("render: image has " + std::to_string(image.argb.size()) + " pixels, expected " +
                std::to_string(image.width) + " x " + std::to_string(image.height));
  return detail::encode_png_rgb(image.argb.data(), image.width, image.height, image.width);
}

void write_png(const Image& image, const std::string& path) {
  detail::write_bytes(path, encode_png(image));
}

}  // namespace mo2d
