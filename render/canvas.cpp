// Cairo surfaces for PNG (image surface), SVG and PDF (stream surfaces into memory), encoded to
// bytes and written with write_file_atomically (temporary file in the same folder, then rename).
#include "canvas.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "mo2d/error.hpp"
#include "output/write_file.hpp"
#include "png.hpp"

namespace mo2d::detail {

namespace {

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

constexpr int kMaxPixels = 16384;  // Cairo's image surface limit is 32767; keep well below

}  // namespace

Format format_of(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "png") return Format::png;
  if (ext == "svg") return Format::svg;
  if (ext == "pdf") return Format::pdf;
  throw Error("render: cannot tell the format of '" + path + "' (use .png, .svg or .pdf)", path);
}

void check_size(int width, int height, double dpi, const std::string& what) {
  if (width <= 0 || height <= 0 || width > kMaxPixels || height > kMaxPixels)
    throw Error("render: " + what + " size " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels is not in 1.." + std::to_string(kMaxPixels),
                what);
  if (!std::isfinite(dpi) || dpi <= 0)
    throw Error("render: " + what + " dpi must be finite and > 0 (got " + std::to_string(dpi) + ")",
                what);
}

void select_font(cairo_t* cr, const std::string& family, cairo_font_slant_t slant,
                 cairo_font_weight_t weight) {
  const bool pixels = cairo_surface_get_type(cairo_get_target(cr)) == CAIRO_SURFACE_TYPE_IMAGE;
  std::string spelt = family;
  for (char& c : spelt)
    c = static_cast<char>(pixels ? std::toupper(static_cast<unsigned char>(c))
                                 : std::tolower(static_cast<unsigned char>(c)));
  cairo_select_font_face(cr, spelt.c_str(), slant, weight);
}

Canvas::Canvas(Format format, int width, int height, double dpi) : format_(format), dpi_(dpi) {
  check_size(width, height, dpi, "image");
  const double w_pt = width * 72.0 / dpi, h_pt = height * 72.0 / dpi;
  switch (format) {
    case Format::png:
      surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
      break;
    case Format::svg:
      bytes_ = std::make_unique<std::string>();
      surface_ = cairo_svg_surface_create_for_stream(append_bytes, bytes_.get(), w_pt, h_pt);
      break;
    case Format::pdf:
      bytes_ = std::make_unique<std::string>();
      surface_ = cairo_pdf_surface_create_for_stream(append_bytes, bytes_.get(), w_pt, h_pt);
      break;
  }
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
    const std::string why = cairo_status_to_string(cairo_surface_status(surface_));
    cairo_surface_destroy(surface_);
    throw Error("render: cannot create a Cairo surface: " + why);
  }
  cr_ = cairo_create(surface_);
  if (format != Format::png) cairo_scale(cr_, 72.0 / dpi, 72.0 / dpi);
}

Canvas::~Canvas() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

Image Canvas::image() const {
  if (format_ != Format::png) throw Error("render: only a PNG canvas has pixels");
  cairo_surface_flush(surface_);
  Image im;
  im.width = cairo_image_surface_get_width(surface_);
  im.height = cairo_image_surface_get_height(surface_);
  const int stride = cairo_image_surface_get_stride(surface_);
  const unsigned char* data = cairo_image_surface_get_data(surface_);
  im.argb.resize(static_cast<size_t>(im.width) * im.height);
  for (int y = 0; y < im.height; ++y) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<size_t>(y) * stride);
    for (int x = 0; x < im.width; ++x)
      im.argb[static_cast<size_t>(y) * im.width + x] = row[x] | 0xFF000000u;
  }
  return im;
}

std::string Canvas::finish() {
  check_status(cr_, "drawing");
  if (format_ == Format::png) {
    cairo_surface_flush(surface_);
    return encode_png_rgb(
        reinterpret_cast<const std::uint32_t*>(cairo_image_surface_get_data(surface_)),
        cairo_image_surface_get_width(surface_), cairo_image_surface_get_height(surface_),
        cairo_image_surface_get_stride(surface_) / 4);
  }
  cairo_surface_finish(surface_);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
    throw Error(std::string("render: vector output failed: ") +
                cairo_status_to_string(cairo_surface_status(surface_)));
  return *bytes_;
}

void check_status(cairo_t* cr, const std::string& what) {
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
    throw Error("render: Cairo failed while " + what + ": " +
                cairo_status_to_string(cairo_status(cr)));
}

void set_colour(cairo_t* cr, const Rgb& c, double alpha) {
  if (alpha >= 1.0)
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
  else
    cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

Rgb mix(const Rgb& a, const Rgb& b, double t) {
  return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  return e.x_advance;
}

void draw_text(cairo_t* cr, const std::string& text, double x, double y, double ax, double ay) {
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double w = text_width(cr, text);
  // ay: 0 top of the capitals at y, 0.5 their middle, 1 the baseline at y
  const double cap = 0.72 * fe.ascent;
  cairo_move_to(cr, x - ax * w, y + cap * (1.0 - ay));
  cairo_show_text(cr, text.c_str());
  cairo_new_path(cr);
}

void write_bytes(const std::string& path, const std::string& bytes) {
  write_file_atomically(path, bytes);
}

}  // namespace mo2d::detail
